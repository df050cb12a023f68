// One Moreau–Jean step of rigid disks, owned by the core: the host (the LAMMPS fix, the testbed)
// holds positions, forces and the per-body storage of carried impulses; the step does the rest.
//
//   predictor   x_m = x_n + (1 - theta) dt v_n                       (host applies predicted_motion, cd/kinematics.h)
//   free        v_free = v_n + dt F / m, spin likewise                 (free_velocity)
//   pairs       the host offers the pairs near each other (StepHost::collect_pairs): solved if
//               candidates, watched otherwise, each with its key and the impulse it carried,
//               which starts a solved one (the warm start)
//   order       interleaved (cd::interleaved_order) or shuffled; keys travel with the contacts
//   solve       the solver the settings name (cd/solver.h, built by cd::make_solver); watched
//               pairs the solution would drive into overlap join and the solve goes on (the
//               solve loop, step.cpp)
//   store       the host keeps every loaded contact's impulse, by key (StepContacts::for_each_loaded)
//   corrector   x_{n+1} = x_m + theta dt v_{n+1}                       (host applies corrected_motion)
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cd/contact.h"
#include "cd/detection.h"
#include "cd/kinematics.h"
#include "cd/order.h"
#include "cd/problem_file.h"
#include "cd/solver.h"

namespace cd {

// What a step asks of its host: the pairs near each other. The host keeps the carried impulses
// (per body, e.g. cd::impulse_row): it hands each pair's with the pair, and after the step
// stores those of the loaded contacts (StepContacts::for_each_loaded).
class StepHost {
 public:
  virtual ~StepHost() = default;
  // Offers `contacts` (StepContacts::offer) every pair whose disks lie within their reach plus
  // to_margin (PairReach::within) and not within their reach plus from_margin (-infinity: no
  // lower bound), each pair once, with its key and the impulse it carried.
  virtual void collect_pairs(const PairReach& reach, double from_margin, double to_margin, StepContacts& contacts) = 0;
};

// When watched pairs that the velocities drive into overlap join the solved contacts:
//   after_solve   once the solve has converged, and the solve starts again from where it stopped;
//   during_solve  also at every full sweep of the solve (cd::JoiningContacts), which goes on
//                 with them: the same problem and tolerance, usually in one solve.
enum class Joining { after_solve, during_solve };

// The default alert distance, in mean diameters: pairs this close are solved even when their
// free motion does not close them (cd::is_candidate). 0.03 solves the 45 d chute once a step at
// 0.90-1.02x the cost but slows the bed of the mu 0.05 flow (doc/accuracy.md, One solve a step).
inline constexpr double default_alert_diameters = 0.01;

struct StepSettings {
  double theta = 0.5;
  SolverSettings solver;  // the method the step builds (cd::make_solver) and its knobs
  // m: candidate selection (cd::is_candidate); not given, default_alert_diameters times the
  // grains' mean diameter, which the host tells as it learns it (MoreauJeanStep::set_mean_diameter).
  std::optional<double> alert;
  bool warm_start = true;
  ContactOrder order = ContactOrder::interleaved;
  int max_solves = 10;                     // solves of one step, at most (the solve loop)
  Joining joining = Joining::after_solve;  // when watched pairs driven shut join (cd::Joining)
};

// Empty if the settings can run, else one line naming the setting as the fix's keyword and its
// range, e.g. "theta must be in [0.5,1], got 0.3". Every cd::MoreauJeanStep is checked.
std::string check(const StepSettings& settings);

struct StepReport {
  SolveReport solve;
  int loaded_contacts = 0;  // solved contacts carrying a positive normal impulse
};

class MoreauJeanStep {
 public:
  // Throws std::invalid_argument with check's line if the settings cannot run.
  explicit MoreauJeanStep(const StepSettings& settings = {}, std::uint64_t shuffle_seed = 0);

  // The step's settings: it owns them, from its construction on.
  const StepSettings& settings() const { return settings_; }
  // The grains' mean diameter (m), which a host learns only as it runs; the alert distance
  // follows it unless the settings gave one. Throws std::invalid_argument unless > 0.
  void set_mean_diameter(double mean_diameter);
  double alert() const { return alert_; }  // m: the one in use
  PairReach& reach() { return reach_; }

  // Everything before the solve: the pairs, their order, their warm start (not yet applied to
  // the velocities). contacts() then holds the step's problem. bodies.velocity: the free velocities.
  void prepare(const BodySet& bodies, double dt, StepHost& host);

  // Solves the step at the predicted configuration (prepare, then the solve): bodies.velocity must hold the free
  // velocities, and holds v_{n+1} on return. `exchange` (a domain-decomposed run) is called
  // after every sweep.
  StepReport solve(BodySet& bodies, double dt, StepHost& host, SweepExchange* exchange = nullptr);

  // Keep a copy of each step's problem as the solver meets it (contacts and free velocities,
  // cd/problem_file.h), for a host that saves the hard ones; off by default: it costs a copy.
  void keep_problems(bool keep) { keeping_problems_ = keep; }
  // The last solve's problem, if kept: its contacts as offered to the first solve and the free
  // velocities (heights and label are the host's to fill).
  const ContactProblem& kept_problem() const { return kept_; }

  // The step's contacts after solve: solved (in sweep order, with their keys) and watched. The
  // host stores the loaded ones' impulses from here (StepContacts::for_each_loaded).
  const StepContacts& contacts() const { return contacts_; }

 private:
  void reorder(int body_count);

  StepSettings settings_;
  double alert_ = 0.0;                     // m: settings_.alert, or the default's for the grain size
  std::unique_ptr<ContactSolver> solver_;  // settings_.solver's method (cd::make_solver)
  PairReach reach_;
  StepContacts contacts_;
  std::mt19937_64 shuffle_rng_;
  std::vector<int> permutation_;  // scratch of reorder
  bool keeping_problems_ = false;
  ContactProblem kept_;
};

}  // namespace cd
