// cd::MoreauJeanStep, the step the fix, the testbed and these tests share: the predictor and
// corrector compose to the Moreau–Jean update, keys travel with their contacts through any
// order, the warm start finds each pair's impulse by key, and only loaded contacts are kept.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cd/step.h"

namespace {

constexpr double radius = 0.5;   // m
constexpr double density = 1.0;  // kg/m^2
constexpr double dt = 1e-3;      // s
const cd::ContactLaw law{0.5, 0.0};

// Rows of disks resting on each other on an immobile bottom row (obstacles: zero inverse mass),
// free velocities those of gravity on rest, every pair (i < j) offered, impulses carried in a
// map by key.
class Pile : public cd::StepHost {
 public:
  explicit Pile(std::uint64_t seed)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> jitter(-1e-7, 1e-7);
    bodies.reset(1);
    for (int row = 0; row < 5; row++)
      for (int column = 0; column < columns; column++) {
        disks.push_back(
            {column * 2.0 * radius + (row % 2) * radius + jitter(rng), radius + row * std::sqrt(3.0) * radius, radius});
        const double mass = M_PI * radius * radius * density;
        const bool obstacle = row == 0;
        bodies.inertia.push_back(obstacle ? cd::BodyInertia{}
                                          : cd::BodyInertia{1.0 / mass, 2.0 / (mass * radius * radius)});
        bodies.start_velocity.push_back({});
        bodies.velocity.push_back({0.0, obstacle ? 0.0 : -9.81 * dt, 0.0});
      }
  }

  void collect_pairs(const cd::PairReach& reach, double from_margin, double to_margin,
                     cd::StepContacts& contacts) override
  {
    for (int i = 0; i < static_cast<int>(disks.size()); i++)
      for (int j = i + 1; j < static_cast<int>(disks.size()); j++) {
        if (j < columns) continue;  // two obstacles: no contact, as the fix lists none
        if (!reach.in_look(1 + i, disks[i], 1 + j, disks[j], from_margin, to_margin)) continue;
        const cd::PairKey key{i, j};
        const auto found = carried.find({key.row, key.partner});
        const cd::Local2 impulse = found == carried.end() ? cd::Local2{} : found->second;
        contacts.offer(cd::disk_disk_geometry(1 + i, disks[i], 1 + j, disks[j]), law, key, impulse);
      }
  }
  // What a host keeps after a step: the loaded contacts' impulses, in place of the last step's.
  void keep(const cd::StepContacts& contacts)
  {
    carried.clear();
    contacts.for_each_loaded([&](const cd::PairKey& key, const cd::Contact& contact, double) {
      EXPECT_TRUE(carried.emplace(std::make_pair(key.row, key.partner), contact.impulse).second)
          << "a pair stored twice";
    });
  }

  static constexpr int columns = 5;  // disks per row; the first row are obstacles
  std::vector<cd::Disk> disks;
  cd::BodySet bodies;
  std::map<std::pair<int, std::int64_t>, cd::Local2> carried;
};

cd::StepSettings settings(cd::ContactOrder order, bool warm_start)
{
  cd::StepSettings s;
  s.solver = {1e-10, 100000, cd::ConvergenceNorm::quadratic};
  s.alert = 0.05 * radius;
  s.order = order;
  s.warm_start = warm_start;
  return s;
}

TEST(MoreauJeanStep, PredictorAndCorrectorComposeToTheThetaUpdate)
{
  const cd::StepParameters step{2e-4, 0.7};
  const cd::BodyVelocity start{1.5, -2.0, 3.0}, end{-0.5, 4.0, 1.0};
  const cd::Displacement first = cd::predicted_motion(start, step);
  const cd::Displacement second = cd::corrected_motion(end, step);
  EXPECT_DOUBLE_EQ(first.dx + second.dx, step.dt * ((1.0 - step.theta) * start.vx + step.theta * end.vx));
  EXPECT_DOUBLE_EQ(first.dy + second.dy, step.dt * ((1.0 - step.theta) * start.vy + step.theta * end.vy));
  const cd::Displacement whole = cd::step_motion(start, end, step);
  EXPECT_DOUBLE_EQ(whole.dx, first.dx + second.dx);
  const cd::BodyVelocity free = cd::free_velocity(start, {0.5, 0.25}, 2.0, -4.0, 8.0, step.dt);
  EXPECT_DOUBLE_EQ(free.vx, start.vx + step.dt * 2.0 * 0.5);
  EXPECT_DOUBLE_EQ(free.vy, start.vy - step.dt * 4.0 * 0.5);
  EXPECT_DOUBLE_EQ(free.spin, start.spin + step.dt * 8.0 * 0.25);
}

TEST(MoreauJeanStep, KeysTravelWithTheirContactsInEveryOrder)
{
  for (const cd::ContactOrder order : {cd::ContactOrder::interleaved, cd::ContactOrder::shuffled}) {
    Pile pile(3);
    cd::MoreauJeanStep moreau_jean(settings(order, true), 11);
    moreau_jean.solve(pile.bodies, dt, pile);
    const cd::StepContacts& contacts = moreau_jean.contacts();
    ASSERT_GT(contacts.solved.size(), 20u);
    ASSERT_EQ(contacts.keys.size(), contacts.solved.size());
    for (std::size_t k = 0; k < contacts.solved.size(); k++) {
      EXPECT_EQ(contacts.keys[k].row, contacts.solved[k].body_a - 1);
      EXPECT_EQ(contacts.keys[k].partner, contacts.solved[k].body_b - 1);
    }
  }
}

// Only loaded contacts are stored, each with its own impulse; the next step of the same state
// starts from them and has nothing left to change.
TEST(MoreauJeanStep, TheWarmStartFindsEachPairsImpulseByKey)
{
  Pile pile(5);
  const cd::BodySet free = pile.bodies;
  cd::MoreauJeanStep moreau_jean(settings(cd::ContactOrder::shuffled, true), 2);
  const cd::StepReport cold = moreau_jean.solve(pile.bodies, dt, pile);
  const cd::StepContacts& contacts = moreau_jean.contacts();
  pile.keep(contacts);
  int loaded = 0;
  for (std::size_t k = 0; k < contacts.solved.size(); k++) {
    const cd::Local2 p = contacts.solved[k].impulse;
    const auto found = pile.carried.find({contacts.keys[k].row, contacts.keys[k].partner});
    if (p.n <= 0.0) {
      EXPECT_EQ(found, pile.carried.end());
      continue;
    }
    ++loaded;
    ASSERT_NE(found, pile.carried.end());
    EXPECT_EQ(found->second.n, p.n);
    EXPECT_EQ(found->second.t, p.t);
  }
  EXPECT_EQ(cold.loaded_contacts, loaded);
  EXPECT_EQ(static_cast<int>(pile.carried.size()), loaded);
  ASSERT_GT(loaded, 20);
  ASSERT_GT(cold.solve.iterations, 5);

  pile.bodies = free;  // the same step again, in another shuffled order
  const cd::StepReport warm = moreau_jean.solve(pile.bodies, dt, pile);
  EXPECT_EQ(warm.solve.iterations, 1) << "started from its own solution";

  pile.bodies = free;
  cd::MoreauJeanStep without(settings(cd::ContactOrder::shuffled, false), 2);
  EXPECT_GT(without.solve(pile.bodies, dt, pile).solve.iterations, 5);
}

// The core checks every host's settings (cd::check): one line naming the fix's keyword, and a
// step refuses settings that cannot run.
TEST(StepSettings, CheckNamesTheSettingOutOfRange)
{
  EXPECT_EQ(cd::check(cd::StepSettings{}), "");
  const auto refused = [](auto change) {
    cd::StepSettings s;
    change(s);
    return cd::check(s);
  };
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.theta = 0.3; }), "theta must be in [0.5,1], got 0.3");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.theta = std::nan(""); }).rfind("theta must be in [0.5,1]", 0), 0u);
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.tolerance = 0.0; }), "tolerance must be in (0,1), got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.tolerance = 1.0; }), "tolerance must be in (0,1), got 1");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.tolerance = 1e300; }), "tolerance must be in (0,1), got 1e+300");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.relaxation = 1.5; }),
            "relaxation must be in (0,1], got 1.5");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.relaxation = 0.0; }),
            "relaxation must be in (0,1], got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.over_relaxation = 2.0; }),
            "over_relaxation must be in [1,2), got 2");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.over_relaxation = 0.9; }),
            "over_relaxation must be in [1,2), got 0.9");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.max_iterations = 0; }), "max_iterations must be >= 1, got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.full_sweep_every = 0; }),
            "full_sweep_every must be >= 1, got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.stall_window = -1; }),
            "stall_window must be >= 0, got -1");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.stall_relaxation = 0.0; }),
            "stall_relaxation must be in (0,1], got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.solver.gauss_seidel.stall_coherence = 1.0; }),
            "stall_coherence must be in (0,1), got 1");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.alert = -1.0; }), "alert must be >= 0, got -1");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.max_solves = 0; }), "max_solves must be >= 1, got 0");
  EXPECT_EQ(refused([](cd::StepSettings& s) { s.alert = INFINITY; }), "") << "infinity: every pair solved";
}

TEST(StepSettings, AStepRefusesSettingsThatCannotRun)
{
  cd::StepSettings bad;
  bad.solver.tolerance = 2.0;
  EXPECT_THROW(cd::MoreauJeanStep{bad}, std::invalid_argument);
  cd::MoreauJeanStep step;
  step.set_mean_diameter(1e-3);
  EXPECT_DOUBLE_EQ(step.alert(), cd::default_alert_diameters * 1e-3) << "no alert given: it follows the grains";
  EXPECT_THROW(step.set_mean_diameter(0.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(step.alert(), cd::default_alert_diameters * 1e-3) << "a refused diameter leaves the last alert";
  cd::StepSettings given;
  given.alert = 2e-5;
  cd::MoreauJeanStep fixed{given};
  fixed.set_mean_diameter(1e-3);
  EXPECT_EQ(fixed.alert(), 2e-5) << "a given alert does not follow the grains";
}

// The model's disks (cd::disk_mass, cd::disk_inertia): m = pi r^2 rho and I = m r^2 / 2.
TEST(DiskModel, MassAndInertiaOfAUniformDisk)
{
  EXPECT_DOUBLE_EQ(cd::disk_mass(0.5, 4.0), M_PI);
  const cd::BodyInertia inertia = cd::disk_inertia(2.0, 0.5);
  EXPECT_DOUBLE_EQ(inertia.inv_mass, 0.5);
  EXPECT_DOUBLE_EQ(inertia.inv_inertia, 1.0 / (0.5 * 2.0 * 0.25));
}

}  // namespace
