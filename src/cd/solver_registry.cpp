// The solver methods by name and their factory (cd/solver_registry.h).
#include "cd/solver_registry.h"

#include <map>
#include <stdexcept>
#include <utility>

#include "cd/gauss_seidel.h"

namespace cd {

namespace {

// The methods by name, Gauss–Seidel among them from the start: the core's own need no
// registration, and a static library keeps no object file nothing calls into.
std::map<std::string, SolverMethod>& methods()
{
  static std::map<std::string, SolverMethod> registered{
      {"gauss_seidel",
       {[](const SolverSettings& settings) { return check(settings.gauss_seidel); },
        [](const SolverSettings& settings) -> std::unique_ptr<ContactSolver> {
          return std::make_unique<GaussSeidel>(settings);
        }}}};
  return registered;
}

// "gauss_seidel or siconos_nsgs", the registered names in order.
std::string listed_names()
{
  std::string listed;
  const std::vector<std::string> names = solver_names();
  for (std::size_t k = 0; k < names.size(); k++)
    listed += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return listed;
}

}  // namespace

bool register_solver(const std::string& name, SolverMethod method)
{
  return methods().emplace(name, std::move(method)).second;
}

std::vector<std::string> solver_names()
{
  std::vector<std::string> names;
  for (const auto& entry : methods()) names.push_back(entry.first);
  return names;
}

std::string check(const SolverSettings& settings)
{
  const std::string stopping = check_stopping(settings);
  if (!stopping.empty()) return stopping;
  const auto method = methods().find(settings.method);
  if (method == methods().end()) return "solver must be " + listed_names() + ", got '" + settings.method + "'";
  return method->second.check(settings);
}

std::unique_ptr<ContactSolver> make_solver(const SolverSettings& settings)
{
  const std::string problem = check(settings);
  if (!problem.empty()) throw std::invalid_argument(problem);
  return methods().at(settings.method).build(settings);
}

}  // namespace cd
