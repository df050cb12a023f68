// Which pairs a step looks at (cd::PairReach) and the solve that lets watched pairs join
// (cd::solve_step, through cd::MoreauJeanStep): the reach test against the gap it stands for, the margin a solve needs,
// pairs joining after the solve and during it, a step with the reach against the same step
// with every pair looked at.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "cd/detection.h"
#include "cd/step.h"

namespace {

constexpr double radius = 0.5;   // m
constexpr double density = 1.0;  // kg/m^2
const cd::StepParameters step{1e-3, 0.5};
const cd::ContactLaw law{0.5, 0.5};
constexpr double alert = 1e-3 * radius;

// Disks with free velocities; every pair (i < j) is "listed", as a neighbour list would.
struct Scene {
  std::vector<cd::Disk> disks;  // body 1 + k
  cd::BodySet bodies;

  void add(cd::Disk disk, cd::BodyVelocity velocity)
  {
    disks.push_back(disk);
    const double mass = M_PI * disk.radius * disk.radius * density;
    bodies.inertia.push_back({1.0 / mass, 1.0 / (0.5 * mass * disk.radius * disk.radius)});
    bodies.start_velocity.push_back(velocity);
    bodies.velocity.push_back(velocity);
  }
  Scene() { bodies.reset(1); }
};

// A host as the fix is one: every pair (i < j) offered when its gap lies in (reach + from,
// reach + to], keyed (i, j); no impulse carried.
class AllPairs : public cd::StepHost {
 public:
  explicit AllPairs(const Scene& scene) : scene(scene) {}
  void collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                     cd::StepContacts& contacts) override
  {
    ++calls;
    for (int i = 0; i < static_cast<int>(scene.disks.size()); i++)
      for (int j = i + 1; j < static_cast<int>(scene.disks.size()); j++) {
        const cd::Disk &a = scene.disks[i], &b = scene.disks[j];
        if (!reach.in_look(1 + i, a, 1 + j, b, from_margin, to_margin)) continue;
        contacts.offer(cd::disk_disk_geometry(1 + i, a, 1 + j, b), law, {i, j}, {});
        ++looked_at;
      }
  }

  int calls = 0;
  int looked_at = 0;

 private:
  const Scene& scene;
};

struct StepResult {
  cd::BodySet bodies;
  int collections = 0;
  int looked_at = 0;
  int solves = 0;
};

// One step of the core from the scene's free velocities, solving the candidates at `alert`
// (infinity: every pair, all solved), closing pairs joining as `joining` says.
StepResult solve(const Scene& scene, double alert, cd::Joining joining = cd::Joining::after_solve,
                 int full_sweep_every = 1)
{
  StepResult result;
  result.bodies = scene.bodies;
  cd::StepSettings settings;
  settings.solver = {1e-12, 100000, cd::ConvergenceNorm::quadratic};
  settings.solver.gauss_seidel.full_sweep_every = full_sweep_every;
  settings.alert = alert;
  settings.joining = joining;
  cd::MoreauJeanStep moreau_jean(settings);
  AllPairs host(scene);
  result.solves = moreau_jean.solve(result.bodies, step.dt, host).solve.solves;
  result.collections = host.calls;
  result.looked_at = host.looked_at;
  return result;
}

constexpr cd::Joining both_joinings[] = {cd::Joining::after_solve, cd::Joining::during_solve};

double end_gap(const Scene& scene, const cd::BodySet& bodies, int i, int j)
{
  const cd::ContactGeometry g = cd::disk_disk_geometry(1 + i, scene.disks[i], 1 + j, scene.disks[j]);
  const double u_n = cd::relative_velocity(cd::contact_frame(g), bodies.velocity[1 + i], bodies.velocity[1 + j]).n;
  return cd::end_of_step_gap(g.gap, u_n, step);
}

TEST(PairReach, WithinIsTheGapAgainstBothReachesPlusTheMargin)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> position(-2.0, 2.0), speed(-300.0, 300.0), size(0.4, 0.6);
  for (int trial = 0; trial < 2000; trial++) {
    Scene scene;
    scene.add({0.0, 0.0, size(rng)}, {speed(rng), speed(rng), 0.0});
    scene.add({position(rng), position(rng), size(rng)}, {speed(rng), speed(rng), 0.0});
    cd::PairReach reach;
    reach.begin_step(scene.bodies, step);
    const double margin = 0.01;
    const double gap = cd::disk_disk_geometry(1, scene.disks[0], 2, scene.disks[1]).gap;
    const double limit = reach.reach(1) + reach.reach(2) + margin;
    if (std::abs(gap - limit) < 1e-12) continue;  // rounding decides
    EXPECT_EQ(reach.within(1, scene.disks[0], 2, scene.disks[1], margin), gap <= limit) << "trial " << trial;
    const cd::BodyVelocity& v = scene.bodies.velocity[1];
    EXPECT_DOUBLE_EQ(reach.reach(1), step.theta * step.dt * std::hypot(v.vx, v.vy));
  }
}

TEST(PairReach, NeededMarginIsTwiceTheLargestSpeedGainOverTheStep)
{
  Scene scene;
  scene.add({0.0, 0.0, radius}, {3.0, 4.0, 0.0});  // free speed 5
  scene.add({2.0, 0.0, radius}, {1.0, 0.0, 0.0});  // free speed 1
  cd::PairReach reach;
  reach.begin_step(scene.bodies, step);
  std::vector<cd::BodyVelocity> solved = scene.bodies.velocity;
  solved[1] = {0.0, 4.0, 0.0};   // slower: no gain
  solved[2] = {0.0, -3.0, 0.0};  // speed 3: gained 2
  EXPECT_NEAR(reach.needed_margin(solved, step), 2.0 * step.theta * step.dt * 2.0, 1e-15);
  solved[2] = {0.5, 0.0, 0.0};
  EXPECT_EQ(reach.needed_margin(solved, step), 0.0);
}

// A fast disk hits a resting one, which is driven into a third that was beyond every reach
// before the solve: the solve must look wider, watch the new pair and promote it.
TEST(SolveStep, BodiesFasterThanTheMarginMakeTheSolveLookWider)
{
  const double v = 10.0;             // m/s: moves theta dt v = 5e-3 m in the step
  const double gap_to_third = 2e-3;  // beyond the margin (alert), within the reach after the hit
  Scene scene;
  scene.add({0.0, radius, radius}, {v, 0.0, 0.0});
  scene.add({2.0 * radius, radius, radius}, {0.0, 0.0, 0.0});
  scene.add({4.0 * radius + gap_to_third, radius, radius}, {0.0, 0.0, 0.0});
  const StepResult narrow = solve(scene, alert);
  EXPECT_EQ(narrow.collections, 2) << "the first look and one wider look";
  EXPECT_GE(end_gap(scene, narrow.bodies, 1, 2), -1e-12) << "the second and third disks do not overlap";
  EXPECT_GT(narrow.bodies.velocity[3].vx, 0.0) << "the third disk is pushed";

  const StepResult everything = solve(scene, std::numeric_limits<double>::infinity());
  for (int b = 1; b <= 3; b++) EXPECT_NEAR(narrow.bodies.velocity[b].vx, everything.bodies.velocity[b].vx, 1e-9);
}

// A fast disk hits a resting one, which is driven into a third, watched (looked at, moving
// away too slowly to be a candidate): joining during the solve takes it in one solve, joining
// after takes two; both reach the solution of every pair solved, in full sweeps and in cycles.
TEST(SolveStep, PairsJoiningDuringTheSolveNeedOneSolve)
{
  const double v = 10.0;    // m/s; the second disk leaves the hit at 7.5 m/s (e = 0.5)
  const double away = 2.0;  // m/s: the third disk's reach theta dt away = 1e-3 m
  const double gap = 1e-3;  // above the alert, within the look; closed by 5.5 m/s in theta dt
  Scene scene;
  scene.add({0.0, radius, radius}, {v, 0.0, 0.0});
  scene.add({2.0 * radius, radius, radius}, {0.0, 0.0, 0.0});
  scene.add({4.0 * radius + gap, radius, radius}, {away, 0.0, 0.0});
  const StepResult everything = solve(scene, std::numeric_limits<double>::infinity());
  for (const int full_sweep_every : {1, 8}) {
    const StepResult after = solve(scene, alert, cd::Joining::after_solve, full_sweep_every);
    const StepResult during = solve(scene, alert, cd::Joining::during_solve, full_sweep_every);
    EXPECT_EQ(after.solves, 2);
    EXPECT_EQ(during.solves, 1);
    for (int b = 1; b <= 3; b++) {
      EXPECT_NEAR(after.bodies.velocity[b].vx, everything.bodies.velocity[b].vx, 1e-9) << "body " << b;
      EXPECT_NEAR(during.bodies.velocity[b].vx, everything.bodies.velocity[b].vx, 1e-9) << "body " << b;
    }
    EXPECT_GT(during.bodies.velocity[3].vx, away) << "the third disk is pushed";
  }
}

// A random gas of disks, fast and slow: the reach looks at fewer pairs and reaches the same
// solution as looking at every pair, whenever closing pairs join.
TEST(SolveStep, TheReachGivesTheSameStepAsLookingAtEveryPair)
{
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20; trial++) {
    Scene scene;
    for (int row = 0; row < 6; row++)
      for (int column = 0; column < 6; column++)
        scene.add({column * 2.02 * radius + 0.002 * unit(rng), row * 2.02 * radius + 0.002 * unit(rng),
                   radius * (1.0 - 0.05 * std::abs(unit(rng)))},
                  {(row == 3 ? 20.0 : 1.0) * unit(rng), unit(rng), unit(rng)});
    const StepResult everything = solve(scene, std::numeric_limits<double>::infinity());
    for (const cd::Joining joining : both_joinings) {
      const StepResult narrow = solve(scene, alert, joining);
      EXPECT_LT(narrow.looked_at, everything.looked_at) << "trial " << trial;
      for (std::size_t b = 1; b < scene.bodies.velocity.size(); b++) {
        EXPECT_NEAR(narrow.bodies.velocity[b].vx, everything.bodies.velocity[b].vx, 1e-8) << "trial " << trial;
        EXPECT_NEAR(narrow.bodies.velocity[b].vy, everything.bodies.velocity[b].vy, 1e-8) << "trial " << trial;
      }
      for (int i = 0; i < 36; i++)
        for (int j = i + 1; j < 36; j++)
          EXPECT_GE(end_gap(scene, narrow.bodies, i, j), -1e-9) << "trial " << trial << " pair " << i << " " << j;
    }
  }
}

}  // namespace

namespace {

// One loaded pair of grains 1 and 2 with n = (0.6, 0.8), levers 1 and 2 m (with a gap of 0.5 m:
// l = 3.5 n); p = (3, 1) in the local frame is (3 n + 1 t) = (1.0, 3.0) in the world
// (t = (-0.8, 0.6)).
cd::Contact loaded_pair()
{
  cd::Contact pair;
  pair.body_a = 1;
  pair.body_b = 2;
  pair.normal_x = 0.6;
  pair.normal_y = 0.8;
  pair.lever_a = 1.0;
  pair.lever_b = 2.0;
  pair.inv_mass_a = 0.5;
  pair.inv_mass_b = 0.25;
  pair.impulse = {3.0, 1.0};
  return pair;
}

// A wall contact (lever_b 0, inverse mass 0) counts with its branch from the contact point,
// (lever_a + gap) n = 1.5 n; an unloaded pair adds nothing.
cd::Contact wall_contact()
{
  cd::Contact wall = loaded_pair();
  wall.body_b = cd::world_body;
  wall.lever_b = 0.0;
  wall.inv_mass_b = 0.0;
  return wall;
}

TEST(BranchImpulseSums, AreTheBranchVectorTimesTheImpulseOfLoadedContactsWallsIncluded)
{
  const cd::Contact pair = loaded_pair();
  cd::Contact unloaded = pair;
  unloaded.impulse = {0.0, 0.0};
  cd::StepContacts contacts;
  contacts.solved = {pair, wall_contact(), unloaded};
  contacts.gaps = {0.5, 0.5, 0.5};
  const cd::BranchImpulseSums sums = cd::branch_impulse_sums(contacts);
  const double branches = 3.5 + 1.5;  // the pair's and the wall's, both along n = (0.6, 0.8)
  EXPECT_NEAR(sums.xx, branches * 0.6 * 1.0, 1e-14);
  EXPECT_NEAR(sums.yy, branches * 0.8 * 3.0, 1e-14);
  EXPECT_NEAR(sums.xy, branches * 0.6 * 3.0, 1e-14);
  EXPECT_NEAR(sums.yx, branches * 0.8 * 1.0, 1e-14);
}

// The loaded pair between two grains, once more against an obstacle (body 3, inverse mass 0), and
// a wall contact: the grains' shares are half of the first each, all of the second and of the
// wall's to grain 1; they add up to the sums.
TEST(BranchImpulseSums, AreSplitHalfBetweenGrainsAndWhollyToTheGrainAgainstAnObstacleOrAWall)
{
  const cd::Contact pair = loaded_pair();
  cd::Contact obstacle = pair;
  obstacle.body_b = 3;
  obstacle.inv_mass_b = 0.0;
  cd::StepContacts contacts;
  contacts.solved = {pair, obstacle, wall_contact()};
  contacts.gaps = {0.5, 0.5, 0.5};
  std::vector<cd::BranchImpulseSums> share(4);
  cd::for_each_branch_impulse_share(contacts, [&](int body, const cd::BranchImpulseSums& s) {
    share[body].xx += s.xx;
    share[body].yy += s.yy;
    share[body].xy += s.xy;
    share[body].yx += s.yx;
  });
  const double ly = 3.5 * 0.8;
  EXPECT_NEAR(share[1].yy, 1.5 * ly * 3.0 + 1.5 * 0.8 * 3.0, 1e-14);
  EXPECT_NEAR(share[2].yy, 0.5 * ly * 3.0, 1e-14);
  EXPECT_EQ(share[3].yy, 0.0);
  EXPECT_EQ(share[0].yy, 0.0);
  const cd::BranchImpulseSums sums = cd::branch_impulse_sums(contacts);
  EXPECT_DOUBLE_EQ(share[1].xx + share[2].xx, sums.xx);
  EXPECT_DOUBLE_EQ(share[1].yy + share[2].yy, sums.yy);
  EXPECT_DOUBLE_EQ(share[1].xy + share[2].xy, sums.xy);
  EXPECT_DOUBLE_EQ(share[1].yx + share[2].yx, sums.yx);
}

}  // namespace
