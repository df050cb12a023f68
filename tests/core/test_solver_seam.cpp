// The solver seam's parts: methods registered by name and built by cd::make_solver (one from
// outside the core, as a bench registers its own), the solver keywords read from text, a step's
// reports summed, the stopping norm under relaxation (analytic), the stall rescue's
// mechanics (a forced stall equals a plain solve continued relaxed, to the bit), the rescue
// untouched where no stall occurs, problem files read back exactly or refused in one line, and
// the run statistics' counts and quantiles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "cd/gauss_seidel.h"
#include "cd/problem_file.h"
#include "cd/solve_statistics.h"
#include "cd/solver_keywords.h"
#include "cd/solver_registry.h"
#include "cd/step.h"
#include "pile.h"

namespace {

// One disk of unit inverse mass resting on the floor, pressed down at 1 m/s: one contact whose
// solution stops it (e = 0).
struct Landing {
  std::vector<cd::Contact> contacts;
  std::vector<cd::BodyVelocity> velocity;
};

Landing make_landing()
{
  Landing landing;
  cd::BodySet bodies;
  bodies.reset(2);
  bodies.inertia[1] = {1.0, 2.0};
  bodies.start_velocity[1] = {0.0, -1.0, 0.0};
  bodies.velocity = bodies.start_velocity;
  const cd::Contact c = cd::prepared_contact(cd::disk_world_geometry(1, cd::Disk{0.0, 0.5, 0.5}, 0.0, 0.0, 0.0, 1.0),
                                             {0.5, 0.0}, bodies, step);
  landing.contacts = {c};
  landing.velocity = bodies.velocity;
  return landing;
}

// Relaxation w leaves p_k = p* (1 - (1-w)^k) after k sweeps of one contact. The norm takes the
// plain local solve's change, |p* - p_(k-1)| / |p_k| = (1-w)^(k-1) / (1 - (1-w)^k): at w = 0.5 and
// tolerance 1e-3 that first holds at k = 11 (k = 10 gives 1.95e-3). A norm of the relaxed change
// would have stopped at k = 10.
TEST(RelaxedNorm, StopsWhereThePlainSweepWouldChangeNoMoreThanTheTolerance)
{
  Landing landing = make_landing();
  cd::SolverSettings settings;
  settings.gauss_seidel.relaxation = 0.5;
  settings.tolerance = 1e-3;
  const cd::SolveReport report = cd::solve_gauss_seidel(landing.contacts, landing.velocity, settings);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.iterations, 11);
  EXPECT_NEAR(report.residual, std::pow(0.5, 10) / (1.0 - std::pow(0.5, 11)), 1e-12);
  EXPECT_NEAR(landing.velocity[1].vy, -std::pow(0.5, 11), 1e-12);
}

// An image sliding across a deforming box's side gives the contact law a tangential bias
// (Contact::velocity_bias.t). Every kind of sweep (plain, conjugate, in cycles) must carry it: the
// landing disk, pressed with p_n = 1 N s, sticks (|p_t| = 0.2 / W_tt < 0.5 p_n) with its law
// velocity at rest, so its own tangential velocity is the image's -0.2 m/s. A sweep compiled
// without the bias (ordinary boxes) would leave it at 0.
TEST(SlidingImages, TheTangentialBiasReachesEveryKindOfSweep)
{
  for (const cd::Acceleration acceleration : {cd::Acceleration::none, cd::Acceleration::conjugate})
    for (const int full_sweep_every : {1, 8}) {
      Landing landing = make_landing();
      landing.contacts[0].velocity_bias.t = 0.2;
      cd::SolverSettings settings;
      settings.tolerance = 1e-12;
      settings.gauss_seidel.acceleration = acceleration;
      settings.gauss_seidel.full_sweep_every = full_sweep_every;
      ASSERT_TRUE(cd::solve_gauss_seidel(landing.contacts, landing.velocity, settings).converged);
      const cd::Contact& c = landing.contacts[0];
      EXPECT_NEAR(cd::law_velocity(c, landing.velocity[1], landing.velocity[0]).t, 0.0, 1e-9);
      EXPECT_NEAR(cd::relative_velocity(c, landing.velocity[1], landing.velocity[0]).t, -0.2, 1e-9);
      EXPECT_LT(std::abs(c.impulse.t), 0.5 * c.impulse.n);
    }
}

cd::SolverSettings pile_settings()
{
  cd::SolverSettings settings;
  settings.tolerance = 1e-10;
  settings.max_iterations = 5000;
  return settings;
}

cd::SolverSettings capped_settings(int sweeps)
{
  cd::SolverSettings settings;
  settings.tolerance = 0.0;
  settings.max_iterations = sweeps;
  return settings;
}

// Drops the impulses from the velocities and sets them to zero: a solve from nothing.
void start_from_zero(Pile& pile)
{
  for (cd::Contact& c : pile.contacts) c.impulse = {-c.impulse.n, -c.impulse.t};
  cd::apply_impulses(pile.contacts, pile.bodies.velocity);
  for (cd::Contact& c : pile.contacts) c.impulse = {};
}

// Stalls forced at the end of every window of 5 sweeps (a coherence no plain solve reaches unless
// its sweeps change nothing: its net change is at most the sum of its sweeps' changes). The 60
// sweeps are the plain ones before the first stall, 5 relaxed by w = 0.6, then from zero
// impulses 5 at w^2, 5 at w^3 and the rest at w^4 = 0.13 (w^5 would be below 0.1), bit for bit;
// the sweeps after the first stall and the restarts are counted. (Tolerance 0: every solve runs
// to its cap.)
TEST(StallRescue, ForcedStallsGoOnRelaxedThenFromZeroMoreRelaxed)
{
  constexpr int cap = 60, window = 5;
  Pile rescued = make_pile(2.0, 2.0);
  Pile by_hand = rescued;
  cd::apply_impulses(rescued.contacts, rescued.bodies.velocity);
  cd::apply_impulses(by_hand.contacts, by_hand.bodies.velocity);

  cd::SolverSettings settings = capped_settings(cap);
  settings.gauss_seidel.stall_window = window;
  settings.gauss_seidel.stall_coherence = 1.0 - 1e-15;
  settings.gauss_seidel.stall_relaxation = 0.6;
  settings.gauss_seidel.stall_block = 0;  // the ladder of restarts from zero
  const cd::SolveReport report = cd::solve_gauss_seidel(rescued.contacts, rescued.bodies.velocity, settings);
  const int plain_sweeps = report.iterations - report.stalled_sweeps;
  EXPECT_EQ(report.iterations, cap);
  EXPECT_EQ(report.cold_restarts, 3);
  EXPECT_EQ(plain_sweeps % window, 0) << "a stall is found where a window ends";
  ASSERT_LT(plain_sweeps + 3 * window, cap);

  cd::solve_gauss_seidel(by_hand.contacts, by_hand.bodies.velocity, capped_settings(plain_sweeps));
  int swept = plain_sweeps;
  double relaxation = 1.0;
  cd::SolveReport last;
  for (int stage = 1; stage <= 4; stage++) {
    if (stage > 1) start_from_zero(by_hand);
    relaxation *= 0.6;
    cd::SolverSettings relaxed = capped_settings(stage < 4 ? window : cap - swept);
    relaxed.gauss_seidel.relaxation = relaxation;
    last = cd::solve_gauss_seidel(by_hand.contacts, by_hand.bodies.velocity, relaxed);
    swept += last.iterations;
  }
  EXPECT_EQ(report.residual, last.residual);
  for (std::size_t k = 0; k < rescued.contacts.size(); k++) {
    EXPECT_EQ(rescued.contacts[k].impulse.n, by_hand.contacts[k].impulse.n);
    EXPECT_EQ(rescued.contacts[k].impulse.t, by_hand.contacts[k].impulse.t);
  }
}

// Windows of one sweep: its net change is its change, a coherence of 1, never a stall. The
// test runs at every sweep and the solve is the one without it, to the bit.
TEST(StallRescue, ASolveWhoseSweepsKeepTheirDirectionIsUntouched)
{
  Pile with = make_pile(2.0, 2.0);
  Pile without = with;
  cd::apply_impulses(with.contacts, with.bodies.velocity);
  cd::apply_impulses(without.contacts, without.bodies.velocity);
  cd::SolverSettings settings = pile_settings();
  const cd::SolveReport plain = cd::solve_gauss_seidel(without.contacts, without.bodies.velocity, settings);
  settings.gauss_seidel.stall_window = 1;
  settings.gauss_seidel.stall_coherence = 0.9;
  const cd::SolveReport watched = cd::solve_gauss_seidel(with.contacts, with.bodies.velocity, settings);
  EXPECT_EQ(watched.iterations, plain.iterations);
  EXPECT_EQ(watched.stalled_sweeps, 0);
  for (std::size_t b = 0; b < with.bodies.velocity.size(); b++) {
    EXPECT_EQ(with.bodies.velocity[b].vx, without.bodies.velocity[b].vx);
    EXPECT_EQ(with.bodies.velocity[b].spin, without.bodies.velocity[b].spin);
  }
}

std::string temporary_path(const char* name)
{
  return ::testing::TempDir() + name;
}

// The core tests' pile as a saved problem, every body at one height.
cd::ContactProblem pile_problem(const char* label, double height)
{
  const Pile pile = make_pile(0.5, 0.5);
  cd::ContactProblem problem{pile.contacts, pile.bodies.velocity, {}, label};
  problem.height.assign(problem.free_velocity.size(), height);
  return problem;
}

TEST(ProblemFile, ReadsBackWhatWasWritten)
{
  const cd::ContactProblem problem = pile_problem("pile of the core tests", 0.25);
  const std::string path = temporary_path("pile.cdp");
  cd::write_problem(path, problem);
  const cd::ContactProblem read = cd::read_problem(path);
  EXPECT_EQ(read.label, problem.label);
  ASSERT_EQ(read.contacts.size(), problem.contacts.size());
  ASSERT_EQ(read.free_velocity.size(), problem.free_velocity.size());
  for (std::size_t k = 0; k < read.contacts.size(); k++) {
    EXPECT_EQ(read.contacts[k].body_a, problem.contacts[k].body_a);
    EXPECT_EQ(read.contacts[k].delassus.inverse_tt, problem.contacts[k].delassus.inverse_tt);
    EXPECT_EQ(read.contacts[k].velocity_bias.n, problem.contacts[k].velocity_bias.n);
    EXPECT_EQ(read.contacts[k].velocity_bias.t, problem.contacts[k].velocity_bias.t);
  }
  EXPECT_EQ(read.free_velocity.back().vy, problem.free_velocity.back().vy);
  EXPECT_EQ(read.height, problem.height);
  std::remove(path.c_str());
}

std::string refusal_reading(const std::string& path)
{
  try {
    cd::read_problem(path);
  } catch (const std::runtime_error& failure) {
    return failure.what();
  }
  return "";
}

TEST(ProblemFile, RefusesWhatIsNotAWholeProblemInOneLine)
{
  const cd::ContactProblem problem = pile_problem("pile", 0.0);
  const std::string path = temporary_path("whole.cdp");
  cd::write_problem(path, problem);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const std::string truncated = temporary_path("truncated.cdp");
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() - 8);
  EXPECT_EQ(refusal_reading(truncated), "contact problem " + truncated + ": truncated in its heights");

  const std::string longer = temporary_path("longer.cdp");
  std::ofstream(longer, std::ios::binary) << bytes << "x";
  EXPECT_EQ(refusal_reading(longer), "contact problem " + longer + ": longer than its header says");

  const std::string text = temporary_path("text.cdp");
  std::ofstream(text) << "ITEM: TIMESTEP\n0\n";
  EXPECT_EQ(refusal_reading(text), "contact problem " + text + ": not a contact problem file");

  EXPECT_EQ(refusal_reading(temporary_path("missing.cdp")),
            "contact problem " + temporary_path("missing.cdp") + ": cannot be opened");
  for (const std::string& p : {path, truncated, longer, text}) std::remove(p.c_str());
}

TEST(SolveStatistics, CountsAndNearestRankQuantiles)
{
  cd::SolveStatistics statistics;
  for (int sweeps = 1; sweeps <= 200; sweeps++) {
    cd::SolveReport step;
    step.iterations = sweeps;
    step.residual = sweeps == 200 ? 3e-3 : 1e-3 * sweeps / 200.0;
    step.converged = sweeps != 200;
    step.stalled_sweeps = sweeps > 190 ? 5 : 0;
    step.cold_restarts = sweeps > 197 ? 1 : 0;
    step.block_solves = sweeps > 195 && sweeps <= 197 ? 2 : 0;
    statistics.record(step);
  }
  const cd::SolveSummary s = statistics.summary();
  EXPECT_EQ(s.steps, 200);
  EXPECT_EQ(s.unconverged, 1);
  EXPECT_EQ(s.rescued, 10);
  EXPECT_EQ(s.restarted, 3);
  EXPECT_EQ(s.block_solved, 2);
  EXPECT_DOUBLE_EQ(s.largest_final_norm, 3e-3);
  EXPECT_EQ(s.median_sweeps, 100);  // the 100th of 200
  EXPECT_EQ(s.p99_sweeps, 198);     // the 198th of 200
  EXPECT_EQ(s.max_sweeps, 200);
  EXPECT_EQ(cd::describe(s),
            "200 steps, 1 unconverged (0.5 %), largest final norm 0.003, sweeps per step median 100, 99th "
            "percentile 198, max 200, 10 rescued from a stall (3 started again from zero, 2 by exact block "
            "solves)");
  statistics.clear();
  EXPECT_EQ(statistics.summary().steps, 0);
}

// A method living outside the core, as bench/ or tests/ would write one: it stops every contact
// at once (a frictionless landing's exact answer) and counts its calls.
class StoppingSolver : public cd::ContactSolver {
 public:
  static int calls;
  cd::SolveReport solve(std::vector<cd::Contact>& contacts, std::vector<cd::BodyVelocity>& velocity, cd::SweepExchange*,
                        cd::JoiningContacts*) override
  {
    ++calls;
    return cd::solve_gauss_seidel(contacts, velocity, cd::SolverSettings{});
  }
};
int StoppingSolver::calls = 0;

std::string refuse_odd_caps(const cd::SolverSettings& settings)
{
  return settings.max_iterations % 2 == 1 ? "max_iterations must be even, got odd" : "";
}

// Registered when the test program starts, as a bench's solver registers itself.
const bool stopping_registered = cd::register_solver(
    "stopping", {refuse_odd_caps, [](const cd::SolverSettings&) { return std::make_unique<StoppingSolver>(); }});

TEST(SolverRegistry, AMethodRegisteredOutsideTheCoreIsBuiltByNameAndChecked)
{
  ASSERT_TRUE(stopping_registered);
  EXPECT_FALSE(cd::register_solver("stopping", {})) << "a name is registered once";
  cd::SolverSettings settings;
  settings.method = "stopping";
  settings.max_iterations = 1001;
  EXPECT_EQ(cd::check(settings), "max_iterations must be even, got odd");
  EXPECT_THROW(cd::make_solver(settings), std::invalid_argument);
  settings.max_iterations = 1000;
  Landing landing = make_landing();
  const int before = StoppingSolver::calls;
  EXPECT_TRUE(cd::make_solver(settings)->solve(landing.contacts, landing.velocity).converged);
  EXPECT_EQ(StoppingSolver::calls, before + 1);
  EXPECT_NEAR(landing.velocity[1].vy, 0.0, 1e-12);
}

TEST(SolverRegistry, TheStepBuildsTheMethodItsSettingsName)
{
  cd::StepSettings settings;
  settings.solver.method = "stopping";
  EXPECT_NO_THROW(cd::MoreauJeanStep{settings});
  settings.solver.method = "lemke";
  EXPECT_EQ(cd::check(settings), "solver must be gauss_seidel or stopping, got 'lemke'");
  EXPECT_THROW(cd::MoreauJeanStep{settings}, std::invalid_argument);
}

TEST(SolverKeywords, AreReadOnceForEveryHost)
{
  cd::SolverSettings settings;
  EXPECT_EQ(cd::read_solver_keyword(settings, "theta", "0.5"), std::nullopt) << "not the solver's";
  EXPECT_EQ(cd::read_solver_keyword(settings, "stall_block", "5"), "");
  EXPECT_EQ(settings.gauss_seidel.stall_block, 5);
  EXPECT_EQ(cd::read_solver_keyword(settings, "tolerance", "1e-4"), "");
  EXPECT_EQ(settings.tolerance, 1e-4);
  EXPECT_EQ(cd::read_solver_keyword(settings, "norm", "maximum"), "");
  EXPECT_EQ(settings.norm, cd::ConvergenceNorm::maximum);
  EXPECT_EQ(cd::read_solver_keyword(settings, "solver", "stopping"), "");
  EXPECT_EQ(settings.method, "stopping");
  EXPECT_EQ(cd::read_solver_keyword(settings, "tolerance", "e"), "tolerance expects a number, got 'e'");
  EXPECT_EQ(cd::read_solver_keyword(settings, "relaxation", "0x1p-1"), "relaxation expects a number, got '0x1p-1'");
  EXPECT_EQ(cd::read_solver_keyword(settings, "tolerance", "1e999"),
            "tolerance '1e999' is outside the range of a double");
  EXPECT_EQ(cd::read_solver_keyword(settings, "max_iterations", "2.5"), "max_iterations expects an integer, got '2.5'");
  EXPECT_EQ(cd::read_solver_keyword(settings, "stall_window", "99999999999"),
            "stall_window must fit an int, got '99999999999'");
  EXPECT_EQ(cd::read_solver_keyword(settings, "acceleration", "anderson"),
            "acceleration must be none or conjugate, got 'anderson'");
  EXPECT_FALSE(settings.gauss_seidel.newton_polish);
  EXPECT_EQ(cd::read_solver_keyword(settings, "newton_polish", "yes"), "");
  EXPECT_TRUE(settings.gauss_seidel.newton_polish);
  EXPECT_EQ(cd::read_solver_keyword(settings, "newton_polish", "1"), "newton_polish must be no or yes, got '1'");
  EXPECT_EQ(cd::read_solver_keyword(settings, "relaxation", ".5"), "");
  EXPECT_EQ(settings.gauss_seidel.relaxation, 0.5);
}

TEST(SolveReport, AStepsSolvesAddUpAndEndWithTheLast)
{
  cd::SolveReport first, later;
  first.iterations = 30, first.contact_updates = 300.0, first.largest_block = 7, first.block_solves = 1;
  later.iterations = 5, later.contact_updates = 50.0, later.largest_block = 4, later.residual = 1e-4;
  later.converged = false, later.stalled_sweeps = 2;
  first.add(later);
  EXPECT_EQ(first.iterations, 35);
  EXPECT_EQ(first.solves, 2);
  EXPECT_EQ(first.contact_updates, 350.0);
  EXPECT_EQ(first.largest_block, 7);
  EXPECT_EQ(first.block_solves, 1);
  EXPECT_EQ(first.stalled_sweeps, 2);
  EXPECT_EQ(first.residual, 1e-4);
  EXPECT_FALSE(first.converged);
}

}  // namespace
