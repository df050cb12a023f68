// The exact block solve of the stall rescue: Lemke's method on complementarity problems whose
// solutions are known in closed form (and on one that has none), the block's contacts against
// Gauss–Seidel converged to round-off, other contacts left alone, and the rescue that ends with
// block solves converging where forced stalls interrupt it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "cd/block_solve.h"
#include "cd/dense_solve.h"
#include "cd/friction_states.h"
#include "cd/lemke.h"
#include "cd/problem_file.h"
#include "pile.h"

namespace {

// w = M z + q at the answer, and the three conditions of complementarity.
void expect_complementary(const std::vector<double>& M, const std::vector<double>& q, const std::vector<double>& z)
{
  const std::size_t n = q.size();
  for (std::size_t i = 0; i < n; i++) {
    double w = q[i];
    for (std::size_t j = 0; j < n; j++) w += M[i * n + j] * z[j];
    EXPECT_GE(z[i], -1e-12) << "z_" << i;
    EXPECT_GE(w, -1e-12) << "w_" << i;
    EXPECT_NEAR(w * z[i], 0.0, 1e-12) << "w_" << i << " z_" << i;
  }
}

// M = I: z = max(-q, 0) component by component.
TEST(Lemke, IdentityGivesTheNegativePartOfQ)
{
  const std::vector<double> M{1, 0, 0, 0, 1, 0, 0, 0, 1}, q{-1.0, 2.0, -3.0};
  std::vector<double> z;
  ASSERT_TRUE(cd::solve_lcp_lemke(M, q, z, 100).solved);
  EXPECT_NEAR(z[0], 1.0, 1e-14);
  EXPECT_EQ(z[1], 0.0);
  EXPECT_NEAR(z[2], 3.0, 1e-14);
}

// A positive definite 2x2 with both constraints active: 2 z1 + z2 = 5, z1 + 2 z2 = 6, so
// z = (4/3, 7/3); with q_2 = +6 only the first: z = (5/2, 0).
TEST(Lemke, PositiveDefiniteProblemsInClosedForm)
{
  const std::vector<double> M{2, 1, 1, 2};
  std::vector<double> z;
  ASSERT_TRUE(cd::solve_lcp_lemke(M, {-5.0, -6.0}, z, 100).solved);
  EXPECT_NEAR(z[0], 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(z[1], 7.0 / 3.0, 1e-14);
  ASSERT_TRUE(cd::solve_lcp_lemke(M, {-5.0, 6.0}, z, 100).solved);
  EXPECT_NEAR(z[0], 2.5, 1e-14);
  EXPECT_EQ(z[1], 0.0);
}

// A singular M (two rows alike, a tie in every ratio test): any z1 + z2 = 1 solves it; the
// lexicographic rule must end at one of them.
TEST(Lemke, DegenerateProblemEndsAtASolution)
{
  const std::vector<double> M{1, 1, 1, 1}, q{-1.0, -1.0};
  std::vector<double> z;
  ASSERT_TRUE(cd::solve_lcp_lemke(M, q, z, 100).solved);
  EXPECT_NEAR(z[0] + z[1], 1.0, 1e-14);
  expect_complementary(M, q, z);
}

// A positive definite M = B B^T / n + I/10 of size n (B's entries a fixed pseudo-random pattern)
// with q of both signs: Lemke must solve it.
std::pair<std::vector<double>, std::vector<double>> dense_problem(std::size_t n)
{
  std::vector<double> B(n * n), M(n * n), q(n);
  for (std::size_t k = 0; k < n * n; k++) B[k] = std::sin(1.7 * static_cast<double>(k) + 0.3);
  for (std::size_t i = 0; i < n; i++) {
    for (std::size_t j = 0; j < n; j++)
      for (std::size_t k = 0; k < n; k++) M[i * n + j] += B[i * n + k] * B[j * n + k] / static_cast<double>(n);
    M[i * n + i] += 0.1;
    q[i] = std::cos(2.3 * static_cast<double>(i));
  }
  return {M, q};
}

// Many pivots, variables leaving and entering again, and the tableau's memory reused by a later
// solve of another size: each answer is complementary and the same as the first time.
TEST(Lemke, DenseProblemsOfSeveralSizesEndAtTheSameSolutions)
{
  const auto [small_M, small_q] = dense_problem(12);
  const auto [large_M, large_q] = dense_problem(40);
  std::vector<double> first, large, again;
  const cd::LemkeResult small = cd::solve_lcp_lemke(small_M, small_q, first, 1000);
  ASSERT_TRUE(small.solved);
  const cd::LemkeResult larger = cd::solve_lcp_lemke(large_M, large_q, large, 1000);
  ASSERT_TRUE(larger.solved);
  EXPECT_GT(larger.pivots, 20);
  expect_complementary(small_M, small_q, first);
  expect_complementary(large_M, large_q, large);
  ASSERT_TRUE(cd::solve_lcp_lemke(small_M, small_q, again, 1000).solved);
  EXPECT_EQ(again, first);
}

// w = -z - 1 >= 0 has no z >= 0: Lemke ends on a ray and says so.
TEST(Lemke, AProblemWithoutSolutionEndsUnsolved)
{
  std::vector<double> z;
  EXPECT_FALSE(cd::solve_lcp_lemke({-1.0}, {-1.0}, z, 100).solved);
}

double law_residual(const cd::Contact& c, const std::vector<cd::BodyVelocity>& velocity)
{
  const cd::Local2 u = cd::law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
  const double w = c.delassus.nn;
  return std::sqrt(cd::natural_map_residual_squared({w * c.impulse.n, w * c.impulse.t}, u, c.mu));
}

std::vector<int> all_of(const std::vector<cd::Contact>& contacts)
{
  std::vector<int> block(contacts.size());
  for (std::size_t k = 0; k < block.size(); k++) block[k] = static_cast<int>(k);
  return block;
}

// The whole pile as one block (mu 0.5, restitution 0.5: impacts, rests and openings) against
// Gauss–Seidel at a tolerance of 1e-13. A block solve is a proximal step of weight 1e-4 W_ii
// towards the block's exact answer (cd/block_solve.h); four of them reach it to round-off: the
// same body velocities to 1e-9 m/s (the grains move at ~0.05 m/s), and the Coulomb law met by
// every contact.
TEST(BlockSolve, TheWholePileAgreesWithGaussSeidelConvergedToRoundOff)
{
  Pile exact = make_pile(0.5, 0.5);
  Pile swept = exact;
  cd::apply_impulses(swept.contacts, swept.bodies.velocity);
  cd::SolverSettings tight;
  tight.tolerance = 1e-13;
  tight.max_iterations = 100000;
  ASSERT_TRUE(cd::solve_gauss_seidel(swept.contacts, swept.bodies.velocity, tight).converged);

  cd::apply_impulses(exact.contacts, exact.bodies.velocity);
  for (int step = 0; step < 4; step++) {
    const cd::BlockSolve block = cd::solve_block(exact.contacts, exact.bodies.velocity, all_of(exact.contacts));
    EXPECT_EQ(block.unsolved, 0);
    EXPECT_GE(block.clusters, 1);
  }
  for (std::size_t b = 1; b < exact.bodies.velocity.size(); b++) {
    EXPECT_NEAR(exact.bodies.velocity[b].vx, swept.bodies.velocity[b].vx, 1e-9) << "body " << b;
    EXPECT_NEAR(exact.bodies.velocity[b].vy, swept.bodies.velocity[b].vy, 1e-9) << "body " << b;
    EXPECT_NEAR(exact.bodies.velocity[b].spin, swept.bodies.velocity[b].spin, 1e-8) << "body " << b;
  }
  for (const cd::Contact& c : exact.contacts) EXPECT_LT(law_residual(c, exact.bodies.velocity), 1e-12);
}

TEST(FrictionStates, StateOfAnImpulse)
{
  EXPECT_EQ(cd::state_of({0.0, 0.0}, 2.0), cd::FrictionState::open);
  EXPECT_EQ(cd::state_of({-1e-9, 0.0}, 2.0), cd::FrictionState::open);
  EXPECT_EQ(cd::state_of({1.0, 1.9}, 2.0), cd::FrictionState::stick);
  EXPECT_EQ(cd::state_of({1.0, 2.0}, 2.0), cd::FrictionState::slide_positive);
  EXPECT_EQ(cd::state_of({1.0, -2.0}, 2.0), cd::FrictionState::slide_negative);
}

// A block of every other contact at mu 2, solved (four proximal steps): its contacts meet the law
// at the others' frozen impulses, and the others keep theirs to the bit.
TEST(BlockSolve, SolvesItsContactsAndLeavesTheOthersAlone)
{
  Pile pile = make_pile(2.0, 2.0);
  cd::apply_impulses(pile.contacts, pile.bodies.velocity);
  std::vector<int> block;
  for (std::size_t k = 0; k < pile.contacts.size(); k += 2) block.push_back(static_cast<int>(k));
  const std::vector<cd::Contact> before = pile.contacts;
  for (int step = 0; step < 4; step++)
    EXPECT_EQ(cd::solve_block(pile.contacts, pile.bodies.velocity, block).unsolved, 0);
  for (std::size_t k = 0; k < pile.contacts.size(); k++) {
    if (k % 2 == 0) {
      EXPECT_LT(law_residual(pile.contacts[k], pile.bodies.velocity), 1e-12) << "contact " << k;
    } else {
      EXPECT_EQ(pile.contacts[k].impulse.n, before[k].impulse.n);
      EXPECT_EQ(pile.contacts[k].impulse.t, before[k].impulse.t);
    }
  }
}

// block_around: the seed, then the contacts sharing a mobile body with it, then theirs; the
// world (body 0) links nothing; the size cap holds.
TEST(BlockSolve, BlockAroundGrowsThroughSharedBodiesOnly)
{
  cd::Contact on_floor, ab, bc, cd_, floor_d;
  on_floor.body_a = 1, on_floor.body_b = 0;  // 0: grain 1 on the world
  ab.body_a = 1, ab.body_b = 2;              // 1
  bc.body_a = 2, bc.body_b = 3;              // 2
  cd_.body_a = 3, cd_.body_b = 4;            // 3
  floor_d.body_a = 5, floor_d.body_b = 0;    // 4: another grain on the world
  const std::vector<cd::Contact> contacts{on_floor, ab, bc, cd_, floor_d};
  EXPECT_EQ(cd::block_around(contacts, 6, {0}, 0, 10), (std::vector<int>{0}));
  EXPECT_EQ(cd::block_around(contacts, 6, {0}, 1, 10), (std::vector<int>{0, 1}));
  EXPECT_EQ(cd::block_around(contacts, 6, {0}, 3, 10), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(cd::block_around(contacts, 6, {0}, 3, 2), (std::vector<int>{0, 1}));
}

// The block's budget: Lemke's cubic work within the stall window's sweeps, (window contacts)^(1/3),
// never below the seeds nor above 200.
TEST(BlockSolve, BlockBudgetKeepsLemkeWithinTheWindowsSweeps)
{
  EXPECT_EQ(cd::block_budget(100, 4800, 16), 78);    // 480 000^(1/3) = 78.3
  EXPECT_EQ(cd::block_budget(1000, 4800, 16), 168);  // 900 sweeps after the first stall
  EXPECT_EQ(cd::block_budget(100, 190, 16), 26);     // 19 000^(1/3) = 26.7
  EXPECT_EQ(cd::block_budget(100, 10, 16), 16);      // the seeds, whatever the cost
  EXPECT_EQ(cd::block_budget(100, 1000000, 16), 200);
  EXPECT_EQ(cd::block_budget(100, 10, 300), 300);  // more seeds than the ceiling: all of them
}

// Stalls forced at the end of windows of 5 sweeps (a coherence only a window whose sweeps change
// nothing can stay above), 23 sweeps at tolerance 0: from the first stall on, every window ends
// in a block solve, none starts the solve from zero, and the mu 2 pile ends on the Coulomb law.
TEST(StallRescue, ForcedStallsEndInBlockSolvesNotRestarts)
{
  Pile pile = make_pile(2.0, 2.0);
  cd::apply_impulses(pile.contacts, pile.bodies.velocity);
  cd::SolverSettings settings;
  settings.tolerance = 0.0;
  settings.max_iterations = 23;
  settings.gauss_seidel.stall_window = 5;
  settings.gauss_seidel.stall_coherence = 1.0 - 1e-15;
  settings.gauss_seidel.stall_block = 3;
  const cd::SolveReport report = cd::solve_gauss_seidel(pile.contacts, pile.bodies.velocity, settings);
  const int first_stall = report.iterations - report.stalled_sweeps;
  EXPECT_EQ(report.iterations, 23);
  EXPECT_EQ(first_stall % 5, 0) << "a stall is found where a window ends";
  EXPECT_GE(report.block_solves, 2);
  EXPECT_EQ(report.block_solves, (23 - first_stall) / 5 + 1);
  EXPECT_EQ(report.cold_restarts, 0);
  for (const cd::Contact& c : pile.contacts) EXPECT_LT(law_residual(c, pile.bodies.velocity), 1e-9);
}

// The chute deck's solver settings at `tolerance`: a cap of 1e4 sweeps, conjugate acceleration.
cd::SolverSettings chute_deck(double tolerance)
{
  cd::SolverSettings deck;
  deck.tolerance = tolerance;
  deck.max_iterations = 10000;
  deck.gauss_seidel.acceleration = cd::Acceleration::conjugate;
  return deck;
}

// A saved step solved from its warm start.
cd::SolveReport solve_saved_step(const char* file, const cd::SolverSettings& settings)
{
  const cd::ContactProblem problem = cd::read_problem(file);
  std::vector<cd::Contact> contacts = problem.contacts;
  std::vector<cd::BodyVelocity> velocity = problem.free_velocity;
  cd::apply_impulses(contacts, velocity);
  return cd::solve_gauss_seidel(contacts, velocity, settings);
}

const char* const relaxed_plateau_step = CD_TEST_DATA "/trapped_after_relaxation_mu2_28deg.cdp";

// A step of the mu 2, 28 degree chute (layer reading, 45 d, 4601 contacts) that the run met at the
// 1e4 cap twice (tests/data/trapped_mu2_28deg.cdp, saved by save_problems from the 28 degree
// replica): the deck's sweeps with the block rescue converge it within a few hundred sweeps;
// with restarts from zero instead it stays unconverged at the cap, as it did in the run.
TEST(StallRescue, ATrappedChuteStepConvergesByBlocksWhereRestartsDoNot)
{
  const auto solve = [&](int stall_block) {
    cd::SolverSettings settings = chute_deck(1e-3);
    settings.gauss_seidel.stall_block = stall_block;
    return solve_saved_step(CD_TEST_DATA "/trapped_mu2_28deg.cdp", settings);
  };
  const cd::SolveReport blocks = solve(3);
  EXPECT_TRUE(blocks.converged);
  EXPECT_LT(blocks.iterations, 1000);
  EXPECT_GE(blocks.block_solves, 1);
  const cd::SolveReport restarts = solve(0);
  EXPECT_FALSE(restarts.converged);
  EXPECT_GE(restarts.cold_restarts, 1);
}

// A step of the same chute at 10 s (4550 contacts) whose first stall, relaxed, drifts on a plateau
// of 2e-3 that the coherence test no longer sees as a cycle: with the deck's cycles of 8 sweeps
// it needs the windows that do not halve the norm counted as stalls (it stayed at the cap after
// one block solve before they were).
TEST(StallRescue, ARelaxedPlateauAfterAStallEndsInMoreBlockSolves)
{
  cd::SolverSettings deck = chute_deck(1e-3);
  deck.gauss_seidel.full_sweep_every = 8;
  const cd::SolveReport report = solve_saved_step(relaxed_plateau_step, deck);
  EXPECT_TRUE(report.converged) << report.iterations << " sweeps";
  EXPECT_LT(report.iterations, 2000);
  EXPECT_GE(report.block_solves, 2);
  // Its blocks stay within the budget, (100 x 4550)^(1/3) = 76 contacts (up to 200 they held 129).
  EXPECT_EQ(
      cd::block_budget(deck.gauss_seidel.stall_window, cd::read_problem(relaxed_plateau_step).contacts.size(), 16), 76);
  EXPECT_LE(report.largest_block, 76);
  EXPECT_GE(report.largest_block, 16);
}

// A block's answer lies on the Coulomb cone to the bit (p_n >= 0, |p_t| <= mu p_n): Lemke's
// round-off once left an open contact a tangential impulse, which the sweeps took off and the next
// solve of the same block put back (doc/stalls.md). Blocks of the budget's 76 contacts around
// every 50th contact of a trapped chute step, at mu 2, each solved four times.
TEST(BlockSolve, AnswersLieOnTheCone)
{
  cd::ContactProblem problem = cd::read_problem(relaxed_plateau_step);
  std::vector<cd::BodyVelocity> velocity = problem.free_velocity;
  cd::apply_impulses(problem.contacts, velocity);
  int off_cone = 0, solved = 0;
  for (std::size_t seed = 0; seed < problem.contacts.size(); seed += 50) {
    const std::vector<int> block =
        cd::block_around(problem.contacts, static_cast<int>(velocity.size()), {static_cast<int>(seed)}, 3, 76);
    for (int round = 0; round < 4; round++) cd::solve_block(problem.contacts, velocity, block);
    for (const int k : block) {
      const cd::Contact& c = problem.contacts[k];
      off_cone += !(c.impulse.n >= 0.0 && std::abs(c.impulse.t) <= c.mu * c.impulse.n);
      ++solved;
    }
  }
  EXPECT_EQ(off_cone, 0) << "of " << solved;
  EXPECT_GT(solved, 1000);
}

// A step of the mu 2, 30 degree corpus run (4 529 contacts; tests/data/kept_block_mu2_30deg_1e-4.cdp)
// at tolerance 1e-4, every sweep full: blocks solved only at stalls are undone by the sweeps
// between them and the solve stays at the cap of 1e4 (99 block solves, the residual left in 5
// contacts); with the kept block solved again every 25 sweeps it converges in 760 sweeps, with the
// deck's cycles of 8 in 977 (doc/stalls.md).
TEST(StallRescue, AKeptBlockConvergesAStepThatStallBlocksAloneDoNot)
{
  const auto solve = [&](int full_sweep_every, int stall_block_every) {
    cd::SolverSettings settings = chute_deck(1e-4);
    settings.gauss_seidel.full_sweep_every = full_sweep_every;
    settings.gauss_seidel.stall_block_every = stall_block_every;
    return solve_saved_step(CD_TEST_DATA "/kept_block_mu2_30deg_1e-4.cdp", settings);
  };
  const cd::SolveReport kept = solve(1, 25);
  EXPECT_TRUE(kept.converged) << kept.iterations << " sweeps";
  EXPECT_LT(kept.iterations, 4000);
  EXPECT_GE(kept.kept_block_solves, 10);
  const cd::SolveReport stalls_only = solve(1, 0);
  EXPECT_FALSE(stalls_only.converged);
  EXPECT_EQ(stalls_only.kept_block_solves, 0);
  EXPECT_GE(stalls_only.block_solves, 10);
  const cd::SolveReport kept_in_cycles = solve(8, 25);
  EXPECT_TRUE(kept_in_cycles.converged) << kept_in_cycles.iterations << " sweeps";
  EXPECT_LT(kept_in_cycles.iterations, 8000);
  EXPECT_GE(kept_in_cycles.kept_block_solves, 10);
}

// A step of the plane shear at mu 2, phi 0.76, tolerance 1e-4 (1 450 contacts; the fix's
// defaults, plain sweeps, cap 1e4) whose norm went from 1.1e-3 at sweep 1 411 back to 3.6e-3 at
// 3 669 and stayed above that to the cap, no contact switching and no window seen as a cycle: a
// cycle slower than the window. Ten windows with no new lowest norm and a path that went back
// and forth make it a stall, and one block solve converges it.
TEST(StallRescue, ACycleSlowerThanTheWindowIsAStall)
{
  cd::SolverSettings fix_defaults;
  fix_defaults.tolerance = 1e-4;
  fix_defaults.max_iterations = 10000;
  const cd::SolveReport report = solve_saved_step(CD_TEST_DATA "/slow_cycle_plane_shear_mu2_1e-4.cdp", fix_defaults);
  EXPECT_TRUE(report.converged) << report.iterations << " sweeps, norm " << report.residual;
  EXPECT_LT(report.iterations, 3000);
  EXPECT_GE(report.block_solves, 1);
}

// A step of the plane shear at mu 2, phi 0.76, tolerance 1e-4 (1 415 contacts; the fix's
// defaults) that blocks within the first stall's budget, (100 x 1 415)^(1/3) = 52 contacts, left at
// the cap of 1e4 (doc/stalls_tight.md): it converges only with a block larger than that, the
// budget grown with the sweeps spent since the first stall.
TEST(StallRescue, ABudgetGrowingWithTheSweepsSpentConvergesAStepSmallBlocksDoNot)
{
  cd::SolverSettings fix_defaults;
  fix_defaults.tolerance = 1e-4;
  fix_defaults.max_iterations = 10000;
  const char* const step = CD_TEST_DATA "/growing_budget_plane_shear_mu2_1e-4.cdp";
  const cd::SolveReport report = solve_saved_step(step, fix_defaults);
  EXPECT_TRUE(report.converged) << report.iterations << " sweeps, norm " << report.residual;
  const int first_budget =
      cd::block_budget(fix_defaults.gauss_seidel.stall_window, cd::read_problem(step).contacts.size(), 16);
  EXPECT_EQ(first_budget, 52);
  EXPECT_GT(report.largest_block, first_budget);
}

// A mu 0.5 step of the 12 d chute cell just after its tilt (1 652 contacts, the deck's sweeps,
// tolerance 1e-3) whose norm wanders between 1.1e-3 and 2.2e-3 for 2 469 sweeps, 5 to 16
// contacts switching a sweep, before it converges: over each 1000 sweeps its impulses keep their
// direction, so the slow test leaves it alone (ten windows without a new lowest norm alone
// rescued it 14 times and changed its answer).
TEST(StallRescue, AWanderingSolveThatStillProgressesIsNoSlowCycle)
{
  cd::SolverSettings deck = chute_deck(1e-3);
  deck.gauss_seidel.full_sweep_every = 8;
  const cd::SolveReport report = solve_saved_step(CD_TEST_DATA "/wandering_mu0.5_12d_1e-3.cdp", deck);
  EXPECT_TRUE(report.converged);
  EXPECT_GT(report.iterations, 2000);
  EXPECT_EQ(report.block_solves, 0);
}

// A block of the trapped chute step (mu 2, 4 601 contacts) after 300 of the deck's sweeps at
// 1e-4, no rescue: the contacts around the residual's carriers, two shared grains out, and
// Lemke's answer to its complementarity problem.
struct TrappedBlock {
  cd::BlockProblem problem;
  std::vector<cd::FrictionState> swept;  // the contacts' states the sweeps left
  std::vector<cd::Local2> impulses;      // and their impulses
  std::vector<double> lemke;
};

TrappedBlock trapped_block(int hops)
{
  const cd::ContactProblem saved = cd::read_problem(CD_TEST_DATA "/trapped_mu2_28deg.cdp");
  std::vector<cd::Contact> contacts = saved.contacts;
  std::vector<cd::BodyVelocity> velocity = saved.free_velocity;
  cd::apply_impulses(contacts, velocity);
  cd::SolverSettings sweeps = chute_deck(1e-4);
  sweeps.max_iterations = 300;
  sweeps.gauss_seidel.stall_window = 0;
  cd::solve_gauss_seidel(contacts, velocity, sweeps);
  const std::vector<int> seeds = cd::residual_carriers(contacts, velocity, 0.9, 16);
  const std::vector<int> block = cd::block_around(contacts, static_cast<int>(velocity.size()), seeds, hops, 200);
  TrappedBlock trapped;
  trapped.problem = cd::block_problem(contacts, velocity, block);
  for (const int k : block) {
    trapped.swept.push_back(cd::state_of(contacts[k].impulse, contacts[k].mu));
    trapped.impulses.push_back(contacts[k].impulse);
  }
  const cd::BlockLcp lcp = cd::to_lcp(trapped.problem);
  EXPECT_TRUE(cd::solve_lcp_lemke(lcp.M, lcp.q, trapped.lemke, 100000).solved);
  return trapped;
}

// The contacts that break the Coulomb–Signorini law at impulses p against the block's own
// response u = u0 + W p, to 1e-9 of the scales of p and u0.
std::size_t law_breakers(const cd::BlockProblem& problem, const std::vector<cd::Local2>& p)
{
  const std::size_t m = problem.size();
  double p_scale = 0.0;
  for (std::size_t i = 0; i < m; i++) p_scale = std::max({p_scale, std::fabs(p[i].n), std::fabs(p[i].t)});
  const double p_floor = 1e-9 * p_scale, u_floor = 1e-9 * problem.velocity_scale();
  std::size_t breakers = 0;
  for (std::size_t i = 0; i < m; i++) {
    const cd::Local2 u = problem.velocity(i, p);
    const double un = u.n, ut = u.t;
    const double mu = problem.mu[i];
    const bool closed = p[i].n > p_floor;
    bool holds = p[i].n >= -p_floor && un >= -u_floor && (!closed || std::fabs(un) <= u_floor) &&
                 std::fabs(p[i].t) <= mu * p[i].n + p_floor;
    if (closed && p[i].t >= mu * p[i].n - p_floor) holds = holds && ut <= u_floor;         // sliding, u_t <= 0
    else if (closed && p[i].t <= -mu * p[i].n + p_floor) holds = holds && ut >= -u_floor;  // sliding, u_t >= 0
    else if (closed) holds = holds && std::fabs(ut) <= u_floor;                            // sticking
    breakers += !holds;
  }
  return breakers;
}

// Lemke's answer as impulses.
std::vector<cd::Local2> lemkes_impulses(const TrappedBlock& trapped)
{
  return cd::impulses_from_lcp(trapped.lemke, trapped.swept.size());
}

// From the states the sweeps left, the contacts' states end at a solution of the law (at mu 2 it
// need not be Lemke's: the problem has more than one) on the block one shared grain around the
// carriers. Lemke's own answer meets the same check, and the impulses the sweeps left do not.
TEST(FrictionStates, SolveATrappedChuteBlock)
{
  const TrappedBlock trapped = trapped_block(1);
  std::size_t closed = 0;
  for (std::size_t i = 0; i < trapped.swept.size(); i++) closed += trapped.lemke[i] > 0.0;
  EXPECT_GE(closed, 10u) << "of " << trapped.swept.size();
  EXPECT_EQ(law_breakers(trapped.problem, lemkes_impulses(trapped)), 0u);
  EXPECT_GT(law_breakers(trapped.problem, trapped.impulses), 0u);
  const cd::StatesSolve solve = cd::solve_by_states(trapped.problem, trapped.swept, 12);
  ASSERT_TRUE(solve.solved);
  EXPECT_EQ(law_breakers(trapped.problem, solve.answer), 0u);
}

// The block two shared grains around the carriers in the states of Lemke's answer, but every third
// contact guessed open and marked cycling, and two held closed ones guessed open: Lemke's method on
// the cycling contacts alone, the held ones following, ends at a solution once the two have
// joined the cycling ones.
TEST(FrictionStates, LemkeOnTheCyclingContactsAloneGivesTheWholeAnswer)
{
  const TrappedBlock trapped = trapped_block(2);
  const std::size_t m = trapped.swept.size();
  const std::vector<double>& z = trapped.lemke;
  std::vector<cd::FrictionState> states(m);
  std::vector<bool> cycling(m, false);
  std::size_t held_wrong = 0;
  for (std::size_t i = 0; i < m; i++) {
    states[i] = cd::state_of({z[i], z[m + i] - z[2 * m + i]}, trapped.problem.mu[i]);
    if (i % 3 == 0) {
      cycling[i] = true;
      states[i] = cd::FrictionState::open;
    } else if (held_wrong < 2 && states[i] != cd::FrictionState::open) {
      states[i] = cd::FrictionState::open;
      ++held_wrong;
    }
  }
  ASSERT_EQ(held_wrong, 2u);
  const cd::StatesSolve solve = cd::solve_cycling_by_lemke(trapped.problem, states, cycling, 4);
  ASSERT_TRUE(solve.solved);
  EXPECT_GE(solve.solves, 2);  // the two held ones wrong: a second problem
  EXPECT_EQ(law_breakers(trapped.problem, solve.answer), 0u);
}

// The states' dense solve: a system that needs a row swap (a zero first pivot), two right-hand
// sides at once, solved to round-off; a singular one refused.
TEST(DenseSolve, SolvesWithPivotingAndRefusesASingularSystem)
{
  std::vector<double> A{0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0};
  const std::vector<double> x{1.0, -2.0, 0.5, 3.0, 4.0, -1.0};  // 3 x 2, row-major
  std::vector<double> B(6, 0.0);
  for (std::size_t row = 0; row < 3; row++)
    for (std::size_t c = 0; c < 2; c++)
      for (std::size_t j = 0; j < 3; j++) B[row * 2 + c] += A[row * 3 + j] * x[j * 2 + c];
  ASSERT_TRUE(cd::solve_dense(A, B, 3, 2));
  for (std::size_t k = 0; k < x.size(); k++) EXPECT_NEAR(B[k], x[k], 1e-14);
  std::vector<double> singular{1.0, 2.0, 2.0, 4.0}, b{1.0, 2.0};
  EXPECT_FALSE(cd::solve_dense(singular, b, 2));
}

}  // namespace
