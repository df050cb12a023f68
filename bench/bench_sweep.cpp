// Google Benchmark of the solver core on a dense bed of 4000 polydisperse disks resting on a
// floor under gravity (src/testbed/granular_bed.h): one Gauss–Seidel sweep, the local Coulomb
// solver alone, the preparation of a step, and a whole step to tolerance.
//
// Throughput is reported as items per second: contact updates (one local solve and impulse
// application) for the sweeps, local solves for the local solver, neighbour pairs for the
// preparation, steps for the whole step. Google Benchmark divides by CPU time, which on a
// shared machine is less disturbed than wall time by other processes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cd/step.h"
#include "testbed/granular_bed.h"

namespace {

constexpr std::uint64_t shuffle_seed = 12345;

// Contact orders of a sweep. fixed: as collected, the pairs of each disk together; shuffled:
// a random permutation (the fix's `order shuffle`); interleaved: the collected order locally
// permuted so that contacts a few places apart share no body (cd::interleaved_order, what
// the fix's `order fixed` does).
enum Order : int { fixed_order = 0, shuffled_order = 1, interleaved_order = 2 };

void shuffle(std::vector<cd::Contact>& contacts, std::mt19937_64& rng)
{
  for (std::size_t k = contacts.size(); k > 1; k--) {
    std::uniform_int_distribution<std::size_t> pick(0, k - 1);
    std::swap(contacts[k - 1], contacts[pick(rng)]);
  }
}

// The core's interleaving (what the fix's `order fixed` applies to the collected order).
void interleave(std::vector<cd::Contact>& contacts, int body_count)
{
  std::vector<cd::Contact> out;
  out.reserve(contacts.size());
  for (int k : cd::interleaved_order(contacts, body_count)) out.push_back(contacts[k]);
  contacts.swap(out);
}

void put_in_order(std::vector<cd::Contact>& contacts, Order order, int body_count, std::mt19937_64& rng)
{
  if (order == shuffled_order) shuffle(contacts, rng);
  if (order == interleaved_order) interleave(contacts, body_count);
}

// One local problem as the sweep poses it: W, the velocity without this contact's own
// impulse (velocity bias included), and mu.
struct LocalProblem {
  cd::Delassus2 delassus;
  cd::Local2 free_velocity;
  double mu;
};

LocalProblem local_problem(const cd::Contact& c, const std::vector<cd::BodyVelocity>& velocity)
{
  const cd::Local2 u = cd::law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
  const cd::Local2 own = c.delassus.times(c.impulse);
  return {c.delassus.full(), {u.n - own.n, u.t - own.t}, c.mu};
}

// The bed, its next step frozen, and the solver state at the start of that step's solve.
struct Scene {
  const testbed::GranularBed& bed;
  testbed::FrozenStep frozen;
  std::vector<cd::Contact> contacts[3];      // prepared and warm-started, in each Order
  std::vector<cd::BodyVelocity> velocity;    // free velocity plus the warm-start impulses
  std::vector<LocalProblem> bed_problems;    // what the first sweep's local solves see
  std::vector<LocalProblem> mixed_problems;  // spread over every branch of the local solver

  Scene(const testbed::GranularBed& settled, testbed::FrozenStep step) : bed(settled), frozen(std::move(step))
  {
    testbed::prepare_contacts(frozen, true, contacts[fixed_order]);
    const int body_count = static_cast<int>(frozen.bodies.velocity.size());
    std::mt19937_64 rng(shuffle_seed);
    for (Order order : {shuffled_order, interleaved_order}) {
      contacts[order] = contacts[fixed_order];
      put_in_order(contacts[order], order, body_count, rng);
    }
    velocity = frozen.bodies.velocity;
    cd::apply_impulses(contacts[fixed_order], velocity);
    for (const cd::Contact& c : contacts[fixed_order]) bed_problems.push_back(local_problem(c, velocity));

    // Same Delassus blocks, free velocities of the bed's size in uniformly random directions:
    // half separate (no contact), the rest split between sticking and sliding.
    double speed = 0.0;
    for (const LocalProblem& p : bed_problems) speed += std::hypot(p.free_velocity.n, p.free_velocity.t);
    speed /= static_cast<double>(bed_problems.size());
    std::mt19937_64 directions(shuffle_seed + 1);
    for (const LocalProblem& p : bed_problems) {
      const double angle = 2.0 * 3.14159265358979323846 * static_cast<double>(directions() >> 11) * 0x1.0p-53;
      mixed_problems.push_back({p.delassus, {speed * std::cos(angle), speed * std::sin(angle)}, p.mu});
    }
  }
};

// The default bed: mu = e = 0.5 for grains and floor.
const testbed::GranularBed& frictional_bed()
{
  static const testbed::GranularBed built{testbed::BedSpec{}};
  return built;
}

// The same rain settled with mu = 0 everywhere (e = 0.5): a frictionless scene.
const testbed::GranularBed& frictionless_bed()
{
  static const testbed::GranularBed built{[] {
    testbed::BedSpec spec;
    spec.grain_law.mu = 0.0;
    spec.wall_law.mu = 0.0;
    return spec;
  }()};
  return built;
}

const Scene& scene()
{
  static const Scene built{frictional_bed(), frictional_bed().freeze()};
  return built;
}

// Scenes that need less than the default bed, for "model only what a scene requires"
// (doc/benchmarks.md): each is the default bed's rain with one feature switched off.
enum class Lean {
  frictionless,    // settled and solved with mu = 0 everywhere
  inelastic,       // the default frozen step with e = 0 everywhere
  immobile_layer,  // settled with the disks centred below 10 d immobile obstacles
};

// The default bed's next step with e = 0 for grains and floor.
testbed::FrozenStep inelastic_step()
{
  testbed::FrozenStep frozen = frictional_bed().freeze();
  frozen.grain_law.restitution = frozen.floor.law.restitution = 0.0;
  return frozen;
}

// Built on first use: a bed takes seconds to rain and settle.
const Scene& lean_scene(Lean kind)
{
  switch (kind) {
    case Lean::frictionless: {
      static const Scene built{frictionless_bed(), frictionless_bed().freeze()};
      return built;
    }
    case Lean::inelastic: {
      static const Scene built{frictional_bed(), inelastic_step()};
      return built;
    }
    case Lean::immobile_layer: break;
  }
  testbed::BedSpec spec;
  spec.immobile_layer = 10.0;
  static const testbed::GranularBed layered{spec};
  static const Scene built{layered, layered.freeze()};
  return built;
}

void set_contact_counters(benchmark::State& state, std::size_t contacts)
{
  state.counters["contacts"] = static_cast<double>(contacts);
}

// (a) One sweep from the state at the start of the solve; the state is restored, untimed,
// before each sweep so that every timed sweep does the same work.
void time_restored_sweeps(benchmark::State& state, const Scene& s, Order order, bool frictionless_shortcut)
{
  const std::vector<cd::Contact>& start = s.contacts[order];
  std::vector<cd::Contact> contacts = start;
  std::vector<cd::BodyVelocity> velocity = s.velocity;
  cd::SolverSettings settings = s.bed.spec().solver;
  settings.gauss_seidel.frictionless_shortcut = frictionless_shortcut;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(start.begin(), start.end(), contacts.begin());
    std::copy(s.velocity.begin(), s.velocity.end(), velocity.begin());
    state.ResumeTiming();
    benchmark::DoNotOptimize(cd::sweep(contacts, velocity, settings));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(contacts.size()));
  set_contact_counters(state, contacts.size());
}

void BM_Sweep(benchmark::State& state)
{
  time_restored_sweeps(state, scene(), static_cast<Order>(state.range(0)), true);
}
BENCHMARK(BM_Sweep)->ArgName("order")->DenseRange(fixed_order, interleaved_order)->Unit(benchmark::kMicrosecond);

// (a') Sweeps chained without restoring, as inside a solve: the impulses converge while the
// benchmark runs, so this is the late, nearly converged part of a solve.
void BM_SweepChained(benchmark::State& state)
{
  const Scene& s = scene();
  std::vector<cd::Contact> contacts = s.contacts[state.range(0)];
  std::vector<cd::BodyVelocity> velocity = s.velocity;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cd::sweep(contacts, velocity, cd::SolverSettings{}));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(contacts.size()));
  set_contact_counters(state, contacts.size());
}
BENCHMARK(BM_SweepChained)->ArgName("order")->DenseRange(fixed_order, interleaved_order)->Unit(benchmark::kMicrosecond);

// (c) The exact local Coulomb solver alone, on the bed's local problems (nearly all sticking
// or separating) and on problems spread over every branch.
void BM_LocalSolver(benchmark::State& state)
{
  const Scene& s = scene();
  const std::vector<LocalProblem>& problems = state.range(0) == 0 ? s.bed_problems : s.mixed_problems;
  int counts[4] = {0, 0, 0, 0};
  for (const LocalProblem& p : problems)
    counts[static_cast<int>(cd::solve_coulomb_local(p.delassus, p.free_velocity, p.mu).status)]++;
  for (auto _ : state) {
    for (const LocalProblem& p : problems)
      benchmark::DoNotOptimize(cd::solve_coulomb_local(p.delassus, p.free_velocity, p.mu));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(problems.size()));
  const double total = static_cast<double>(problems.size());
  state.counters["no_contact"] = counts[0] / total;
  state.counters["stick"] = counts[1] / total;
  state.counters["slip"] = (counts[2] + counts[3]) / total;
}
BENCHMARK(BM_LocalSolver)->ArgName("mixed")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The preparation of a step: geometry, frame and selection of every pair of the neighbour
// list, mechanics of the selected ones, and the warm start read.
void time_prepare(benchmark::State& state, const Scene& s)
{
  std::vector<cd::Contact> contacts;
  for (auto _ : state) {
    testbed::prepare_contacts(s.frozen, true, contacts);
    benchmark::DoNotOptimize(contacts.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.frozen.pairs.size()));
  state.counters["neighbour_pairs"] = static_cast<double>(s.frozen.pairs.size());
  set_contact_counters(state, contacts.size());
}

void BM_Prepare(benchmark::State& state)
{
  time_prepare(state, scene());
}
BENCHMARK(BM_Prepare)->Unit(benchmark::kMicrosecond);

// (b) A whole step of the core (cd::MoreauJeanStep::solve): pairs, order, warm start, Gauss–Seidel
// to 1e-4, plain or with conjugate acceleration, the watched pairs that close joining, the store of
// impulses. Counters: sweeps and solves per step, and the contact updates per second of the step.
cd::ContactOrder step_order(Order order)
{
  if (order == shuffled_order) return cd::ContactOrder::shuffled;
  if (order == interleaved_order) return cd::ContactOrder::interleaved;
  return cd::ContactOrder::as_offered;
}

void time_whole_steps(benchmark::State& state, const Scene& s, bool warm, Order order, bool frictionless_shortcut,
                      cd::Acceleration acceleration = cd::Acceleration::none)
{
  cd::SolverSettings solver = s.bed.spec().solver;
  solver.gauss_seidel.frictionless_shortcut = frictionless_shortcut;
  solver.gauss_seidel.acceleration = acceleration;
  cd::StepSettings settings = testbed::step_settings(s.frozen, solver, warm);
  settings.order = step_order(order);
  cd::MoreauJeanStep moreau_jean(settings, shuffle_seed);
  testbed::FrozenPairs host(s.frozen);
  double sweeps = 0.0, solves = 0.0, updates = 0.0;
  bool converged = true;
  for (auto _ : state) {
    cd::BodySet bodies = s.frozen.bodies;
    const cd::SolveReport report = moreau_jean.solve(bodies, s.frozen.step.dt, host).solve;
    sweeps += report.iterations;
    solves += report.solves;
    updates += report.contact_updates;
    converged = converged && report.converged;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["sweeps"] = benchmark::Counter(sweeps, benchmark::Counter::kAvgIterations);
  state.counters["solves"] = benchmark::Counter(solves, benchmark::Counter::kAvgIterations);
  state.counters["updates_per_second"] = benchmark::Counter(updates, benchmark::Counter::kIsRate);
  state.counters["converged"] = converged ? 1.0 : 0.0;
  set_contact_counters(state, moreau_jean.contacts().solved.size());
}

void BM_WholeStep(benchmark::State& state)
{
  const auto acceleration = state.range(2) != 0 ? cd::Acceleration::conjugate : cd::Acceleration::none;
  time_whole_steps(state, scene(), state.range(0) != 0, static_cast<Order>(state.range(1)), true, acceleration);
}
BENCHMARK(BM_WholeStep)
    ->ArgNames({"warm", "order", "conjugate"})
    ->Args({1, fixed_order, 0})
    ->Args({1, shuffled_order, 0})
    ->Args({1, interleaved_order, 0})
    ->Args({1, interleaved_order, 1})
    ->Args({0, fixed_order, 0})
    ->Args({0, interleaved_order, 1})
    ->Unit(benchmark::kMillisecond);

// "Model only what a scene requires": each feature a scene can do without, timed with and
// without it on the same bed, in the fix's contact order (interleaved), one name per case:
//   BM_Lean/{sweep,step}/{frictionless,frictional}/{coulomb,shortcut}: mu = 0 contacts through
//       the Coulomb local solver or the frictionless shortcut (SolverSettings), on the bed
//       settled with mu = 0, and the shortcut's branch on the default (mu = 0.5) bed;
//   BM_Lean/{prepare,step}/{restitution,inelastic}: e = 0.5 (the default) against e = 0;
//   BM_Lean/{sweep,step}/{all_mobile,immobile_layer}: the default bed, and the bed settled
//       with its bottom 10 d immobile (fewer contacts: compare items_per_second, per update).
// Run A and B together, e.g. --benchmark_filter=BM_Lean/sweep/frictionless.
void register_lean_benchmarks()
{
  auto add = [](const std::string& name, auto timed) {
    benchmark::RegisterBenchmark(("BM_Lean/" + name).c_str(), timed)->Unit(benchmark::kMicrosecond);
  };
  for (const bool shortcut : {false, true}) {
    const std::string path = shortcut ? "/shortcut" : "/coulomb";
    add("sweep/frictionless" + path, [shortcut](benchmark::State& st) {
      time_restored_sweeps(st, lean_scene(Lean::frictionless), interleaved_order, shortcut);
    });
    add("sweep/frictional" + path,
        [shortcut](benchmark::State& st) { time_restored_sweeps(st, scene(), interleaved_order, shortcut); });
    add("step/frictionless" + path, [shortcut](benchmark::State& st) {
      time_whole_steps(st, lean_scene(Lean::frictionless), true, interleaved_order, shortcut);
    });
    add("step/frictional" + path,
        [shortcut](benchmark::State& st) { time_whole_steps(st, scene(), true, interleaved_order, shortcut); });
  }
  add("prepare/restitution", [](benchmark::State& st) { time_prepare(st, scene()); });
  add("prepare/inelastic", [](benchmark::State& st) { time_prepare(st, lean_scene(Lean::inelastic)); });
  add("step/restitution", [](benchmark::State& st) { time_whole_steps(st, scene(), true, interleaved_order, true); });
  add("step/inelastic",
      [](benchmark::State& st) { time_whole_steps(st, lean_scene(Lean::inelastic), true, interleaved_order, true); });
  add("sweep/all_mobile", [](benchmark::State& st) { time_restored_sweeps(st, scene(), interleaved_order, true); });
  add("step/all_mobile", [](benchmark::State& st) { time_whole_steps(st, scene(), true, interleaved_order, true); });
  add("sweep/immobile_layer", [](benchmark::State& st) {
    time_restored_sweeps(st, lean_scene(Lean::immobile_layer), interleaved_order, true);
  });
  add("step/immobile_layer", [](benchmark::State& st) {
    time_whole_steps(st, lean_scene(Lean::immobile_layer), true, interleaved_order, true);
  });
}

// What the packing is, in the report's context block (console header and JSON).
void describe_scene()
{
  const Scene& s = scene();
  const testbed::GranularBed& bed = s.bed;
  const testbed::BedSpec& spec = bed.spec();
  const auto& contacts = s.contacts[fixed_order];
  const int disks = static_cast<int>(bed.disks().size());
  int wall_contacts = 0;
  for (const cd::Contact& c : contacts) wall_contacts += c.body_b == cd::world_body;
  const int pair_contacts = static_cast<int>(contacts.size()) - wall_contacts;

  // Solve the frozen step once for its loads: a bed at rest carries its weight on the floor.
  std::vector<cd::Contact> solved = contacts;
  std::vector<cd::BodyVelocity> velocity = s.velocity;
  const cd::SolveReport report = cd::solve_gauss_seidel(solved, velocity, spec.solver);
  double floor_impulse = 0.0, weight_impulse = 0.0, area = 0.0, top = 0.0;
  int loaded = 0;
  for (const cd::Contact& c : solved) {
    loaded += c.impulse.n > 0.0;
    if (c.body_b == cd::world_body) floor_impulse += c.impulse.n;
  }
  for (int k = 0; k < disks; k++) {
    const double r = bed.disks()[k].radius;
    weight_impulse += spec.gravity * spec.dt / s.frozen.bodies.inertia[1 + k].inv_mass;
    area += 3.14159265358979323846 * r * r;
    top = std::max(top, bed.disks()[k].y + r);
  }
  // Sweeps per step over the second half of the settling: the spread the frozen step sits in.
  std::vector<int> sweeps;
  const auto& settle = bed.settle_reports();
  for (std::size_t k = settle.size() / 2; k < settle.size(); k++) sweeps.push_back(settle[k].iterations);
  std::sort(sweeps.begin(), sweeps.end());
  double mean_sweeps = 0.0;
  for (int n : sweeps) mean_sweeps += n;
  mean_sweeps /= std::max<std::size_t>(1, sweeps.size());

  auto text = [](double v) { return std::to_string(v); };
  benchmark::AddCustomContext("bed_disks", std::to_string(disks));
  benchmark::AddCustomContext("bed_cell", text(spec.cell_length) + " d periodic in x, d = " + text(spec.mean_diameter) +
                                              " m, (dmax-dmin)/d = " + text(spec.polydispersity));
  benchmark::AddCustomContext("bed_height_d", text(top / spec.mean_diameter));
  benchmark::AddCustomContext("bed_solid_fraction", text(area / (top * bed.length_x())));
  benchmark::AddCustomContext("bed_settle_steps", std::to_string(spec.settle_steps) + " of dt = " + text(spec.dt) +
                                                      " s, max speed after " + text(bed.max_speed()) + " m/s");
  if (!sweeps.empty())
    benchmark::AddCustomContext("bed_settle_sweeps", "last " + std::to_string(sweeps.size()) + " steps: median " +
                                                         std::to_string(sweeps[sweeps.size() / 2]) + ", mean " +
                                                         text(mean_sweeps) + ", max " + std::to_string(sweeps.back()));
  benchmark::AddCustomContext("step_neighbour_pairs", std::to_string(s.frozen.pairs.size()));
  benchmark::AddCustomContext("step_active_contacts", std::to_string(contacts.size()) + " (" +
                                                          std::to_string(pair_contacts) + " disk-disk, " +
                                                          std::to_string(wall_contacts) + " floor)");
  benchmark::AddCustomContext("step_coordination", text(2.0 * pair_contacts / disks) + " disk-disk contacts per disk");
  benchmark::AddCustomContext("step_loaded_contacts", std::to_string(loaded));
  benchmark::AddCustomContext("step_solve", std::to_string(report.iterations) + " sweeps to " +
                                                text(spec.solver.tolerance) +
                                                ", floor load / weight = " + text(floor_impulse / weight_impulse));
}

}  // namespace

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  describe_scene();
  register_lean_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
