// Siconos's solvers at documented options other than their defaults (bench/peers/siconos_variants.h).
#include "siconos_variants.h"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <map>
#include <stdexcept>

#include "Friction_cst.h"
#include "SolverOptions.h"

namespace peers {

namespace {

using Choices = std::map<std::string, int>;
using Setter = std::function<void(SolverOptions&, const std::string&)>;

[[noreturn]] void refuse(const std::string& what)
{
  throw std::invalid_argument("siconos_variants: " + what);
}

int choice(const Choices& choices, const std::string& value)
{
  const auto found = choices.find(value);
  if (found == choices.end()) throw std::out_of_range(value);
  return found->second;
}

double number(const std::string& value)
{
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0') throw std::out_of_range(value);
  return x;
}

// A key that picks one of `choices` into iparam[index] (of the internal solver if `internal`).
Setter pick(int index, Choices choices, bool internal = false)
{
  return [=](SolverOptions& o, const std::string& value) {
    SolverOptions& target = internal ? *o.internalSolvers[0] : o;
    target.iparam[index] = choice(choices, value);
  };
}

// A key that replaces the internal solver by one of `choices` (with its own defaults).
Setter internal_solver(Choices choices)
{
  return [=](SolverOptions& o, const std::string& value) {
    solver_options_update_internal(&o, 0, choice(choices, value));
  };
}

Setter real(int index)
{
  return [=](SolverOptions& o, const std::string& value) { o.dparam[index] = number(value); };
}

const Choices line_searches = {{"gp", SICONOS_FRICTION_3D_NSN_LINESEARCH_GOLDSTEINPRICE},
                               {"armijo", SICONOS_FRICTION_3D_NSN_LINESEARCH_ARMIJO},
                               {"none", SICONOS_FRICTION_3D_NSN_LINESEARCH_NO}};
const Choices hybrids = {{"no", SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY_NO},
                         {"pli_nsn", SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY_PLI_NSN_LOOP},
                         {"nsn_pli", SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY_NSN_AND_PLI_NSN_LOOP},
                         {"vi_eg_nsn", SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY_VI_EG_NSN}};
const Choices formulations = {{"ac", SICONOS_FRICTION_3D_NSN_FORMULATION_ALARTCURNIER_STD},
                              {"jm", SICONOS_FRICTION_3D_NSN_FORMULATION_JEANMOREAU_STD},
                              {"ac_gen", SICONOS_FRICTION_3D_NSN_FORMULATION_ALARTCURNIER_GENERATED},
                              {"jm_gen", SICONOS_FRICTION_3D_NSN_FORMULATION_JEANMOREAU_GENERATED}};

std::map<std::string, Setter> nsn_keys(bool alart_curnier)
{
  std::map<std::string, Setter> keys = {{"ls", pick(SICONOS_FRICTION_3D_NSN_LINESEARCH, line_searches)},
                                        {"hybrid", pick(SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY, hybrids)}};
  if (alart_curnier) {
    keys["form"] = pick(SICONOS_FRICTION_3D_NSN_FORMULATION, formulations);
    keys["rho"] = pick(SICONOS_FRICTION_3D_NSN_RHO_STRATEGY,
                       {{"constant", SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_CONSTANT},
                        {"spectral", SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_SPECTRAL_NORM},
                        {"split_cond", SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_SPLIT_SPECTRAL_NORM_COND},
                        {"split", SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_SPLIT_SPECTRAL_NORM},
                        {"adaptive", SICONOS_FRICTION_3D_NSN_FORMULATION_RHO_STRATEGY_ADAPTIVE}});
  }
  return keys;
}

std::map<std::string, Setter> nsgs_keys()
{
  return {
      {"local", internal_solver({{"nsn", SICONOS_FRICTION_3D_ONECONTACT_NSN},
                                 {"nsn_gp", SICONOS_FRICTION_3D_ONECONTACT_NSN_GP},
                                 {"nsn_gp_hybrid", SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID},
                                 {"pli", SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnConeWithLocalIteration},
                                 {"p", SICONOS_FRICTION_3D_ONECONTACT_ProjectionOnCone},
                                 {"quartic", SICONOS_FRICTION_3D_ONECONTACT_QUARTIC_NU}})},
      {"local_form", pick(SICONOS_FRICTION_3D_NSN_FORMULATION, formulations, true)},
      {"local_hybrid", pick(SICONOS_FRICTION_3D_NSN_HYBRID_STRATEGY, hybrids, true)},
      {"local_tol", pick(SICONOS_FRICTION_3D_IPARAM_INTERNAL_ERROR_STRATEGY,
                         {{"adaptive", SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE},
                          {"given", SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_GIVEN_VALUE},
                          {"adaptive_n", SICONOS_FRICTION_3D_INTERNAL_ERROR_STRATEGY_ADAPTIVE_N_CONTACT}})},
      {"local_tolerance",
       [](SolverOptions& o, const std::string& value) {
         o.internalSolvers[0]->dparam[SICONOS_DPARAM_TOL] = number(value);
       }},
      {"shuffle", pick(SICONOS_FRICTION_3D_NSGS_SHUFFLE, {{"no", SICONOS_FRICTION_3D_NSGS_SHUFFLE_FALSE},
                                                          {"once", SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE},
                                                          {"each", SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE_EACH_LOOP}})},
      {"omega",
       [](SolverOptions& o, const std::string& value) {
         o.iparam[SICONOS_FRICTION_3D_NSGS_RELAXATION] = SICONOS_FRICTION_3D_NSGS_RELAXATION_TRUE;
         o.dparam[SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE] = number(value);
       }},
      {"error", pick(SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION,
                     {{"full", SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL},
                      {"light", SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_LIGHT},
                      {"light_full_final", SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_LIGHT_WITH_FULL_FINAL},
                      {"adaptive", SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_ADAPTIVE}})},
  };
}

std::map<std::string, Setter> admm_keys()
{
  return {
      {"rho", pick(SICONOS_FRICTION_3D_ADMM_IPARAM_RHO_STRATEGY,
                   {{"constant", SICONOS_FRICTION_3D_ADMM_RHO_STRATEGY_CONSTANT},
                    {"residual_balancing", SICONOS_FRICTION_3D_ADMM_RHO_STRATEGY_RESIDUAL_BALANCING},
                    {"scaled_residual_balancing", SICONOS_FRICTION_3D_ADMM_RHO_STRATEGY_SCALED_RESIDUAL_BALANCING}})},
      {"initial_rho", pick(SICONOS_FRICTION_3D_ADMM_IPARAM_INITIAL_RHO,
                           {{"given", SICONOS_FRICTION_3D_ADMM_INITIAL_RHO_GIVEN},
                            {"norm_inf", SICONOS_FRICTION_3D_ADMM_INITIAL_RHO_NORM_INF},
                            {"eigenvalues", SICONOS_FRICTION_3D_ADMM_INITIAL_RHO_EIGENVALUES}})},
      {"accel", pick(SICONOS_FRICTION_3D_ADMM_IPARAM_ACCELERATION,
                     {{"no", SICONOS_FRICTION_3D_ADMM_NO_ACCELERATION},
                      {"yes", SICONOS_FRICTION_3D_ADMM_ACCELERATION},
                      {"restart", SICONOS_FRICTION_3D_ADMM_ACCELERATION_AND_RESTART}})},
  };
}

std::map<std::string, Setter> prox_keys()
{
  return {
      {"inner", internal_solver({{"nsn_ac", SICONOS_FRICTION_3D_NSN_AC},
                                 {"nsn_fb", SICONOS_FRICTION_3D_NSN_FB},
                                 {"nsgs", SICONOS_FRICTION_3D_NSGS}})},
      {"strategy", pick(SICONOS_FRICTION_3D_PROXIMAL_IPARAM_STRATEGY,
                        {{"prox", SICONOS_FRICTION_3D_PROXIMAL_PROX},
                         {"regularization", SICONOS_FRICTION_3D_PROXIMAL_REGULARIZATION}})},
      {"alpha", real(SICONOS_FRICTION_3D_PROXIMAL_DPARAM_ALPHA)},
      {"sigma", real(SICONOS_FRICTION_3D_PROXIMAL_DPARAM_SIGMA)},
      {"nu", real(SICONOS_FRICTION_3D_PROXIMAL_DPARAM_NU)},
  };
}

std::map<std::string, Setter> tfp_keys()
{
  return {{"inner", internal_solver({{"nsgs", SICONOS_FRICTION_3D_NSGS},
                                     {"pg_cylinder", SICONOS_FRICTION_3D_CONVEXQP_PG_CYLINDER},
                                     {"vi_fpp_cylinder", SICONOS_FRICTION_3D_VI_FPP_Cylinder}})}};
}

std::map<std::string, Setter> keys_of(const std::string& solver)
{
  if (solver == "fc3d_nsn_ac") return nsn_keys(true);
  if (solver == "fc3d_nsn_fb" || solver == "fc3d_nsn_nm") return nsn_keys(false);
  if (solver == "fc3d_nsgs") return nsgs_keys();
  if (solver == "fc3d_admm") return admm_keys();
  if (solver == "fc3d_prox") return prox_keys();
  if (solver == "fc3d_tfp") return tfp_keys();
  return {};
}

}  // namespace

VariantName parse_variant(const std::string& name)
{
  const auto open = name.find('[');
  VariantName variant{name.substr(0, open), {}};
  if (open == std::string::npos) return variant;
  if (name.back() != ']' || open + 2 >= name.size()) refuse("'" + name + "' is not SOLVER[KEY=VALUE+...]");
  const std::string list = name.substr(open + 1, name.size() - open - 2);
  for (std::size_t begin = 0; begin <= list.size();) {
    const auto end = std::min(list.find('+', begin), list.size());
    const std::string item = list.substr(begin, end - begin);
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == item.size())
      refuse("'" + name + "': option '" + item + "' is not KEY=VALUE");
    variant.options.emplace_back(item.substr(0, equals), item.substr(equals + 1));
    begin = end + 1;
  }
  return variant;
}

void apply_variant(const VariantName& variant, SolverOptions& options)
{
  const std::map<std::string, Setter> keys = keys_of(variant.solver);
  for (const auto& [key, value] : variant.options)
    if (keys.count(key) == 0) refuse(variant.solver + " has no option '" + key + "'");
  const auto is_solver = [](const std::string& key) { return key == "local" || key == "inner"; };
  for (const bool solvers_first : {true, false})  // the internal solver first: the other keys set its options
    for (const auto& [key, value] : variant.options) {
      if (is_solver(key) != solvers_first) continue;
      try {
        keys.at(key)(options, value);
      } catch (const std::out_of_range&) {
        refuse(variant.solver + " option " + key + ": no value '" + value + "'");
      }
    }
}

const std::vector<std::string>& siconos_variant_names()
{
  static const std::vector<std::string> names = {
      // the nonsmooth Newton family: formulation, line search, rho, hybrids
      "fc3d_nsn_ac[form=ac]", "fc3d_nsn_ac[ls=none]", "fc3d_nsn_ac[ls=armijo]", "fc3d_nsn_ac[form=ac+ls=none]",
      "fc3d_nsn_ac[form=jm]", "fc3d_nsn_ac[form=jm_gen]", "fc3d_nsn_ac[form=jm+ls=none]",
      "fc3d_nsn_ac[form=jm+ls=armijo]", "fc3d_nsn_ac[rho=constant+ls=none]", "fc3d_nsn_ac[rho=split]",
      "fc3d_nsn_ac[rho=split_cond]", "fc3d_nsn_ac[rho=adaptive]", "fc3d_nsn_ac[form=ac+ls=none+hybrid=vi_eg_nsn]",
      "fc3d_nsn_ac[hybrid=pli_nsn]", "fc3d_nsn_ac[hybrid=nsn_pli]", "fc3d_nsn_fb[ls=none]", "fc3d_nsn_fb[ls=armijo]",
      "fc3d_nsn_fb[hybrid=vi_eg_nsn]", "fc3d_nsn_nm[ls=none]", "fc3d_nsn_nm[ls=armijo]",
      // NSGS: the local solver, its tolerance, shuffling, relaxation, the error's evaluation
      "fc3d_nsgs[local=nsn]", "fc3d_nsgs[local=nsn_gp]", "fc3d_nsgs[local=nsn+local_form=jm]",
      "fc3d_nsgs[local=nsn_gp+local_form=jm]", "fc3d_nsgs[local=pli]", "fc3d_nsgs[local=p]", "fc3d_nsgs[local=quartic]",
      "fc3d_nsgs[local_hybrid=pli_nsn]", "fc3d_nsgs[local_tol=adaptive]", "fc3d_nsgs[local=pli+local_tol=adaptive]",
      "fc3d_nsgs[shuffle=once]", "fc3d_nsgs[shuffle=each]", "fc3d_nsgs[omega=1.5]", "fc3d_nsgs[omega=0.8]",
      "fc3d_nsgs[error=full]", "fc3d_nsgs[error=adaptive]",
      // ADMM's rho strategies and acceleration
      "fc3d_admm[rho=residual_balancing]", "fc3d_admm[rho=scaled_residual_balancing]",
      "fc3d_admm[initial_rho=norm_inf]", "fc3d_admm[initial_rho=eigenvalues]", "fc3d_admm[accel=no]",
      "fc3d_admm[accel=yes]",
      // the proximal point method's internal solver and alpha
      "fc3d_prox[inner=nsn_fb]", "fc3d_prox[inner=nsgs]", "fc3d_prox[alpha=-1e4]", "fc3d_prox[alpha=1e3]",
      "fc3d_prox[strategy=regularization+alpha=1e4]",
      // later: the local tolerance's value, Tresca's fixed point's internal solver
      "fc3d_nsgs[local_tolerance=1e-6]", "fc3d_nsgs[local_tolerance=1e-10]", "fc3d_tfp[inner=pg_cylinder]",
      "fc3d_tfp[inner=vi_fpp_cylinder]"};
  return names;
}

}  // namespace peers
