// The solver methods by name and the factory a step builds its solver with (cd/solver.h is the
// seam they implement). The core registers Gauss–Seidel; a method built outside the core (in
// bench/ or tests/) registers itself, and the core never names it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cd/solver.h"

namespace cd {

// A method as the factory knows it: its check (empty, or one line naming a keyword) and how it
// is built from settings that passed that check.
struct SolverMethod {
  std::function<std::string(const SolverSettings&)> check;
  std::function<std::unique_ptr<ContactSolver>(const SolverSettings&)> build;
};

// Adds a method under `name`; false if the name is taken. Gauss–Seidel is "gauss_seidel" from
// the start. A method built outside the core registers itself when its program starts:
//   const bool registered = cd::register_solver("siconos_nsgs", {check_nsgs, build_nsgs});
bool register_solver(const std::string& name, SolverMethod method);
// The registered names, in alphabetical order.
std::vector<std::string> solver_names();

// The method the settings name, built; throws std::invalid_argument with check's line if the
// settings cannot run.
std::unique_ptr<ContactSolver> make_solver(const SolverSettings& settings);

// check_stopping, then the method's name and its own check.
std::string check(const SolverSettings& settings);

}  // namespace cd
