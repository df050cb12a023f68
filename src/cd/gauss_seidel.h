// Moreau–Jean contact impulses by nonlinear Gauss–Seidel over contacts: sweeps of exact local
// Coulomb solves (cd/coulomb_local.h) over prepared contacts (cd/contact.h) until the
// convergence norm (cd/convergence.h) is met; its knobs are cd::GaussSeidelSettings
// (cd/gauss_seidel_settings.h), its stall rescue cd/stall_rescue.h. Registered as
// "gauss_seidel" (cd::make_solver). The contacts' impulses, warm start included, are applied to
// the velocities before the first sweep (cd::apply_impulses).
#pragma once

#include <string>
#include <vector>

#include "cd/contact.h"
#include "cd/convergence.h"
#include "cd/gauss_seidel_settings.h"
#include "cd/solver.h"
#include "cd/stall_rescue.h"

namespace cd {

// One sweep over the contacts [first, last) in their stored order, accumulating what
// `settings.norm` needs (of the local solves' changes). Frictionless contacts (mu = 0) take the
// shortcut of GaussSeidelSettings::frictionless_shortcut unless it is false. With conjugate
// acceleration each contact then adds `beta` times its direction (0: a plain sweep that records
// the directions).
SweepChange sweep(Contact* first, Contact* last, BodyVelocity* velocity, const SolverSettings& settings,
                  double beta = 0.0);
SweepChange sweep(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity, const SolverSettings& settings,
                  double beta = 0.0);

// Watches a solve sweep by sweep: a study's hook (bench/solver_corpus), called after every full
// sweep with the report so far while the contacts and velocities hold the iterate.
class SweepObserver {
 public:
  virtual ~SweepObserver() = default;
  virtual void after_full_sweep(const SolveReport& so_far) = 0;
};

// Nonlinear Gauss–Seidel. Sweeps until the norm falls to the tolerance or the iteration cap is
// reached, in cycles of GaussSeidelSettings::full_sweep_every. `joining` is asked after the 1st,
// 2nd, 4th, 8th, ... full sweep (the step's collisions drive pairs shut in its first sweeps;
// looking after every sweep would cost a twentieth of the step) and after every converged one.
class GaussSeidel : public ContactSolver {
 public:
  // Throws std::invalid_argument with check's line if the settings cannot run.
  explicit GaussSeidel(const SolverSettings& settings);
  const SolverSettings& settings() const { return settings_; }
  void observe(SweepObserver* observer) { observer_ = observer; }
  SolveReport solve(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                    SweepExchange* exchange = nullptr, JoiningContacts* joining = nullptr) override;

  // Reused from solve to solve: once the largest problem has been seen, a solve allocates nothing.
  struct CycleWorkspace {
    std::vector<double> change_sq;  // each contact's |W dp|^2 in the cycle's full sweep
    std::vector<int> active;        // the contacts that full sweep left changing, in sweep order
    SweepChange quiet;              // the others' share of the norm's scale
  };

 private:
  SolveReport solve_in_full_sweeps(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                                   SweepExchange* exchange, JoiningContacts* joining);
  SolveReport solve_in_cycles(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                              SweepExchange* exchange, JoiningContacts* joining);

  SolverSettings settings_;
  CycleWorkspace cycle_;
  StallWorkspace stall_;
  SweepObserver* observer_ = nullptr;
};

// A one-off solve: GaussSeidel(settings).solve(...).
SolveReport solve_gauss_seidel(std::vector<Contact>& contacts, std::vector<BodyVelocity>& velocity,
                               const SolverSettings& settings, SweepExchange* exchange = nullptr,
                               JoiningContacts* joining = nullptr);

}  // namespace cd
