// Siconos numerics' solvers behind the core's seam (cd/solver.h): a step built with
// `solver siconos_fc2d_nsgs` (or siconos_ and any name of peers::siconos_solver_names()) hands
// its contacts here; they become the local problem u = W r + q (bench/peers/local_problem.h),
// Siconos solves it from the warm start to its own error (peers::error) at the settings'
// tolerance, within their max_iterations, and the impulses come back in N s. Registered from
// this file's static initializer: linked only into the bench and tests that list it
// (bench/peers/CMakeLists.txt, target cd_peer_solvers), never into the fix.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cd/solver_registry.h"
#include "local_problem.h"
#include "siconos_solvers.h"

namespace peers {

namespace {

constexpr const char* prefix = "siconos_";

class SiconosContactSolver : public cd::ContactSolver {
 public:
  SiconosContactSolver(std::string solver, const cd::SolverSettings& settings) : solver_(std::move(solver))
  {
    settings_.tolerance = settings.tolerance;
    settings_.max_iterations = settings.max_iterations;
  }

  cd::SolveReport solve(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity,
                        cd::SweepExchange* exchange, cd::JoiningContacts* joining) override
  {
    if (exchange) throw std::invalid_argument(prefix + solver_ + " runs on one rank only");
    cd::SolveReport report = solve_once(contacts, velocity);
    // Pairs driven shut join (their impulses zero, so the velocities stand) and the whole
    // problem is solved again from this answer, until none joins.
    while (joining && joining->join(report.converged)) report.add(solve_once(contacts, velocity));
    return report;
  }

 private:
  cd::SolveReport solve_once(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity) const
  {
    cd::ContactProblem problem{contacts, velocity, {}, solver_};
    for (cd::Contact& c : problem.contacts) c.impulse = {-c.impulse.n, -c.impulse.t};
    cd::apply_impulses(problem.contacts, problem.free_velocity);  // the warm start taken off
    const LocalProblem local = local_problem(problem);            // its warm_start: contacts' impulses
    const SiconosResult answer = solve_with_siconos(local, solver_, settings_, local.warm_start);

    velocity = problem.free_velocity;
    for (std::size_t k = 0; k < contacts.size(); k++)
      contacts[k].impulse = {answer.reaction[2 * k] / local.impulse_scale,
                             answer.reaction[2 * k + 1] / local.impulse_scale};
    cd::apply_impulses(contacts, velocity);

    cd::SolveReport report;
    report.iterations = answer.iterations;  // Siconos's own unit: sweeps of NSGS, Newton steps of NSN
    report.contact_updates = 0.0;           // not counted inside Siconos
    report.residual = answer.error;
    report.converged = answer.error <= settings_.tolerance;
    return report;
  }

  std::string solver_;
  SiconosSettings settings_;
};

// Siconos stops on its own error, never on the core's norms: another norm would be ignored.
std::string check_norm(const cd::SolverSettings& settings)
{
  return settings.norm == cd::ConvergenceNorm::quadratic
             ? ""
             : settings.method + " stops on Siconos's own error: norm must be quadratic (the default)";
}

bool register_siconos_solvers()
{
  bool all = true;
  for (const std::string& name : siconos_solver_names())
    all = cd::register_solver(prefix + name,
                              {check_norm,
                               [name](const cd::SolverSettings& settings) -> std::unique_ptr<cd::ContactSolver> {
                                 return std::make_unique<SiconosContactSolver>(name, settings);
                               }}) &&
          all;
  return all;
}

}  // namespace

// Every Siconos solver of the comparison, as siconos_NAME, when the program starts.
extern const bool siconos_solvers_registered = register_siconos_solvers();

}  // namespace peers
