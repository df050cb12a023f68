// Solver settings measured on a corpus of saved hard steps (fix contact/dynamics save_problems,
// cd/problem_file.h): for each problem and each setting, the error the solve leaves against the
// work it spent, sweep by sweep.
//
//   solver_corpus --out DIR --d 5e-4 --z0 0.015 [--g 9.81] [--reference-tolerance 1e-9]
//                 [--reference-cap 200000] [--reference "relaxation=0.7"]
//                 --setting NAME "key=value ..." [--setting ...] PROBLEM.cdp ...
//
// Keys of a setting: the fix's solver keywords (cd/solver_keywords.h: tolerance, max_iterations,
// norm, relaxation, acceleration, full_sweep_every, stall_window, ...); and
// cold (yes|no): start from zero impulses instead of the step's warm start.
//
// Error measures, each over the mobile bodies or contacts of the problem:
//   natural_map   sqrt(sum |W_nn (p - proj_K(p - u_hat / W_nn))|^2 / sum |W p|^2): the Coulomb law's
//                 violation in the stopping norm's units, zero exactly at a solution (u_hat: De
//                 Saxce's modified velocity with the normal bias);
//   rms_error     rms |v - v_ref| / sqrt(g d) against a reference solve (--reference at
//                 --reference-tolerance), overall and in depth bands of z = (y - z0) / d;
//   switches      contacts whose status (open, stick, slip +, slip -) changed in the last sweep.
// Files: DIR/solves.csv (one row per problem and setting, at the end of the solve) and
// DIR/history.csv (rows at every full sweep up to 16, then at 1.1x spaced sweep counts).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cd/block_solve.h"
#include "cd/gauss_seidel.h"
#include "cd/problem_file.h"
#include "cd/solver_keywords.h"
#include "cd/solver_registry.h"

namespace {

struct NamedSetting {
  std::string name;
  cd::SolverSettings settings;
  bool cold = false;     // start from zero impulses instead of the saved warm start
  unsigned shuffle = 0;  // > 0: the contacts swept in a random order drawn from this seed
  int block_rounds = 0;  // an unconverged solve: exact block solves around its residual, each then swept again
  int block_hops = 2;
};

struct Options {
  std::string out;
  double diameter = 0.0;  // m
  double z0 = 0.0;        // m: z = 0, the wall tops
  double gravity = 9.81;
  double reference_tolerance = 1e-9;
  int reference_cap = 200000;
  cd::SolverSettings reference;
  std::vector<NamedSetting> settings;
  std::vector<std::string> problems;
  std::vector<double> band_edges{-30, -18, -9, 0, 9, 48};  // d
};

[[noreturn]] void refuse(const std::string& what)
{
  throw std::invalid_argument("solver_corpus: " + what);
}

double number(const std::string& key, const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') refuse(key + " expects a number, got '" + text + "'");
  return value;
}

cd::SolverSettings parse_setting(const std::string& text, cd::SolverSettings settings, NamedSetting* named = nullptr)
{
  std::istringstream items(text);
  std::string item;
  while (items >> item) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) refuse("a setting's item must be key=value, got '" + item + "'");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    if (const std::optional<std::string> solver_key = cd::read_solver_keyword(settings, key, value)) {
      if (!solver_key->empty()) refuse(*solver_key);
    } else if (key == "shuffle" && named) named->shuffle = static_cast<unsigned>(number(key, value));
    else if (key == "block_rounds" && named) named->block_rounds = static_cast<int>(number(key, value));
    else if (key == "block_hops" && named) named->block_hops = static_cast<int>(number(key, value));
    else if (key == "cold" && named && (value == "yes" || value == "no")) named->cold = value == "yes";
    else refuse("unknown setting '" + item + "'");
  }
  const std::string problem = cd::check(settings);
  if (!problem.empty()) refuse(problem);
  return settings;
}

Options parse_options(int argc, char** argv)
{
  Options o;
  o.reference.gauss_seidel.acceleration = cd::Acceleration::none;
  std::string reference_text = "relaxation=0.7";
  for (int i = 1; i < argc; i++) {
    const std::string arg = argv[i];
    const auto value = [&](int count = 1) {
      if (i + count >= argc) refuse(arg + " needs " + std::to_string(count) + " value(s)");
      i += count;
      return std::string(argv[i - count + 1]);
    };
    if (arg == "--out") o.out = value();
    else if (arg == "--d") o.diameter = number(arg, value());
    else if (arg == "--z0") o.z0 = number(arg, value());
    else if (arg == "--g") o.gravity = number(arg, value());
    else if (arg == "--reference-tolerance") o.reference_tolerance = number(arg, value());
    else if (arg == "--reference-cap") o.reference_cap = static_cast<int>(number(arg, value()));
    else if (arg == "--reference") reference_text = value();
    else if (arg == "--setting") {
      NamedSetting setting;
      setting.name = value();
      setting.settings = parse_setting(value(), {}, &setting);
      o.settings.push_back(setting);
    } else if (arg.rfind("--", 0) == 0) refuse("unknown option " + arg);
    else o.problems.push_back(arg);
  }
  if (o.out.empty() || !(o.diameter > 0.0)) refuse("--out and --d are required");
  if (o.settings.empty() || o.problems.empty()) refuse("give at least one --setting and one problem file");
  o.reference = parse_setting(reference_text, o.reference);
  o.reference.tolerance = o.reference_tolerance;
  o.reference.max_iterations = o.reference_cap;
  return o;
}

enum class Status : unsigned char { open, stick, slip_positive, slip_negative };

Status status_of(const cd::Contact& c)
{
  if (c.impulse.n <= 0.0) return Status::open;
  if (c.impulse.t >= c.mu * c.impulse.n) return Status::slip_negative;
  if (c.impulse.t <= -c.mu * c.impulse.n) return Status::slip_positive;
  return Status::stick;
}

double natural_map(const std::vector<cd::Contact>& contacts, const std::vector<cd::BodyVelocity>& velocity)
{
  double residual = 0.0, scale = 0.0;
  for (const cd::Contact& c : contacts) {
    const cd::Local2 u = cd::law_velocity(c, velocity[c.body_a], velocity[c.body_b]);
    const double w = c.delassus.nn;
    residual += cd::natural_map_residual_squared({w * c.impulse.n, w * c.impulse.t}, u, c.mu);
    const cd::Local2 wp = c.delassus.times(c.impulse);
    scale += wp.n * wp.n + wp.t * wp.t;
  }
  return scale > 0.0 ? std::sqrt(residual / scale) : 0.0;
}

// The largest normal impulse over the median loaded one: self-stress shows as a large ratio.
double impulse_spread(const std::vector<cd::Contact>& contacts)
{
  std::vector<double> loaded;
  for (const cd::Contact& c : contacts)
    if (c.impulse.n > 0.0) loaded.push_back(c.impulse.n);
  if (loaded.empty()) return 0.0;
  std::sort(loaded.begin(), loaded.end());
  return loaded.back() / loaded[loaded.size() / 2];
}

// Where an iterate's natural-map residual sits: how many contacts carry 90 % of its square, and
// in how many clusters (contacts linked by a shared mobile body) they lie.
std::string residual_spread(const std::vector<cd::Contact>& contacts, const std::vector<cd::BodyVelocity>& velocity)
{
  const std::vector<int> carriers = cd::residual_carriers(contacts, velocity, 0.9, static_cast<int>(contacts.size()));
  std::vector<int> parent(velocity.size());
  for (std::size_t b = 0; b < parent.size(); b++) parent[b] = static_cast<int>(b);
  const auto root = [&](int b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  };
  const std::size_t count = carriers.size();
  std::size_t on_world = 0;
  std::vector<int> bodies;
  for (const int k : carriers) {
    const cd::Contact& c = contacts[k];
    on_world += c.body_a == 0 || c.body_b == 0;
    if (c.body_a > 0) bodies.push_back(c.body_a);
    if (c.body_b > 0) bodies.push_back(c.body_b);
    if (c.body_a > 0 && c.body_b > 0) parent[root(c.body_a)] = root(c.body_b);
  }
  std::map<int, int> clusters;
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  for (const int b : bodies) clusters[root(b)]++;
  int largest = 0;
  for (const auto& [r, n] : clusters) largest = std::max(largest, n);
  return "90 % of the residual in " + std::to_string(count) + " of " + std::to_string(contacts.size()) + " contacts (" +
         std::to_string(on_world) + " on the world), " + std::to_string(clusters.size()) + " clusters, largest " +
         std::to_string(largest) + " bodies";
}

struct Solved {
  std::vector<cd::Contact> contacts;
  std::vector<cd::BodyVelocity> velocity;
  cd::SolveReport report;
};

// The errors of an iterate against the reference.
struct ErrorMeasure {
  const Options& options;
  const cd::ContactProblem& problem;
  const std::vector<cd::BodyVelocity>* reference = nullptr;

  int band_of(int body) const
  {
    const double z = (problem.height[body] - options.z0) / options.diameter;
    for (std::size_t k = 0; k + 1 < options.band_edges.size(); k++)
      if (z >= options.band_edges[k] && z < options.band_edges[k + 1]) return static_cast<int>(k);
    return -1;
  }

  // rms |v - v_ref| / sqrt(g d): overall first, then per band.
  std::vector<double> rms_errors(const std::vector<cd::BodyVelocity>& v) const
  {
    const std::size_t bands = options.band_edges.size() - 1;
    std::vector<double> sum(bands + 1, 0.0), count(bands + 1, 0.0);
    const double unit = std::sqrt(options.gravity * options.diameter);
    for (std::size_t b = 1; b < v.size(); b++) {
      const double dvx = v[b].vx - (*reference)[b].vx, dvy = v[b].vy - (*reference)[b].vy;
      const double e2 = (dvx * dvx + dvy * dvy) / (unit * unit);
      sum[0] += e2;
      count[0] += 1.0;
      const int band = band_of(static_cast<int>(b));
      if (band >= 0) sum[band + 1] += e2, count[band + 1] += 1.0;
    }
    std::vector<double> rms(bands + 1);
    for (std::size_t k = 0; k <= bands; k++) rms[k] = count[k] > 0.0 ? std::sqrt(sum[k] / count[k]) : NAN;
    return rms;
  }
};

// Rows of history.csv while a solve runs.
class HistoryWriter : public cd::SweepObserver {
 public:
  HistoryWriter(std::ofstream& out, const std::string& tag, const ErrorMeasure& errors, const Solved& run)
      : out_(out), tag_(tag), errors_(errors), run_(run)
  {
  }
  void after_full_sweep(const cd::SolveReport& so_far) override
  {
    int switches = 0;
    statuses_.resize(run_.contacts.size(), Status::open);
    for (std::size_t k = 0; k < run_.contacts.size(); k++) {
      const Status s = status_of(run_.contacts[k]);
      switches += s != statuses_[k];
      statuses_[k] = s;
    }
    if (so_far.iterations < next_row_) return;
    next_row_ = so_far.iterations < 16 ? so_far.iterations + 1 : static_cast<int>(1.1 * so_far.iterations) + 1;
    const double contacts = std::max<double>(1.0, static_cast<double>(run_.contacts.size()));
    out_ << tag_ << ',' << so_far.iterations << ',' << so_far.contact_updates / contacts << ',' << so_far.residual
         << ',' << natural_map(run_.contacts, run_.velocity) << ',' << errors_.rms_errors(run_.velocity)[0] << ','
         << switches << ',' << so_far.stalled_sweeps << '\n';
  }

 private:
  std::ofstream& out_;
  std::string tag_;
  const ErrorMeasure& errors_;
  const Solved& run_;
  std::vector<Status> statuses_;
  int next_row_ = 1;
};

Solved solve(const cd::ContactProblem& problem, const NamedSetting& setting, cd::SweepObserver* observer,
             Solved* into = nullptr)
{
  Solved local;
  Solved& run = into ? *into : local;
  run.contacts = problem.contacts;
  if (setting.shuffle > 0) {
    std::mt19937_64 rng(setting.shuffle);
    std::shuffle(run.contacts.begin(), run.contacts.end(), rng);
  }
  if (setting.cold)
    for (cd::Contact& c : run.contacts) c.impulse = {};
  run.velocity = problem.free_velocity;
  cd::apply_impulses(run.contacts, run.velocity);
  cd::GaussSeidel solver(setting.settings);
  solver.observe(observer);
  run.report = solver.solve(run.contacts, run.velocity);
  for (int round = 0; round < setting.block_rounds && !run.report.converged; round++) {
    const std::vector<int> block =
        cd::block_around(run.contacts, static_cast<int>(run.velocity.size()),
                         cd::residual_carriers(run.contacts, run.velocity, 0.9, 16), setting.block_hops, 400);
    const cd::BlockSolve exact = cd::solve_block(run.contacts, run.velocity, block);
    const cd::SolveReport more = solver.solve(run.contacts, run.velocity);
    std::cerr << "    block of " << block.size() << " contacts: unsolved clusters " << exact.unsolved << " of "
              << exact.clusters << ", " << exact.pivots << " pivots; then " << more.iterations << " sweeps, norm "
              << more.residual << "\n";
    run.report.iterations += more.iterations;
    run.report.contact_updates += more.contact_updates;
    run.report.residual = more.residual;
    run.report.converged = more.converged;
  }
  return run;
}

std::string base_name(const std::string& path)
{
  return path.substr(path.find_last_of('/') + 1);
}

int run(const Options& o)
{
  std::ofstream solves(o.out + "/solves.csv"), history(o.out + "/history.csv");
  if (!solves || !history) refuse("cannot write in " + o.out);
  solves << "problem,setting,contacts,sweeps,local_solves_per_contact,converged,final_norm,natural_map,rms_error";
  for (std::size_t k = 0; k + 1 < o.band_edges.size(); k++)
    solves << ",rms_" << o.band_edges[k] << "_" << o.band_edges[k + 1];
  solves << ",stalled_sweeps,block_solves,kept_block_solves,cold_restarts,reference_sweeps,reference_norm,reference_"
            "natural_map\n";
  history << "problem,setting,sweeps,local_solves_per_contact,norm,natural_map,rms_error,switches,stalled_sweeps\n";
  for (const std::string& path : o.problems) {
    const cd::ContactProblem problem = cd::read_problem(path);
    NamedSetting reference_setting;
    reference_setting.settings = o.reference;
    const Solved reference = solve(problem, reference_setting, nullptr);
    ErrorMeasure errors{o, problem, &reference.velocity};
    const double reference_map = natural_map(reference.contacts, reference.velocity);
    std::cerr << base_name(path) << ": " << problem.contacts.size() << " contacts; reference "
              << reference.report.iterations << " sweeps, norm " << reference.report.residual << ", natural map "
              << reference_map << "\n";
    for (const NamedSetting& s : o.settings) {
      Solved run;
      HistoryWriter writer(history, base_name(path) + "," + s.name, errors, run);
      solve(problem, s, &writer, &run);
      const double contacts = std::max<double>(1.0, static_cast<double>(run.contacts.size()));
      solves << base_name(path) << ',' << s.name << ',' << run.contacts.size() << ',' << run.report.iterations << ','
             << run.report.contact_updates / contacts << ',' << run.report.converged << ',' << run.report.residual
             << ',' << natural_map(run.contacts, run.velocity);
      for (const double e : errors.rms_errors(run.velocity)) solves << ',' << e;
      solves << ',' << run.report.stalled_sweeps << ',' << run.report.block_solves << ','
             << run.report.kept_block_solves << ',' << run.report.cold_restarts << ',' << reference.report.iterations
             << ',' << reference.report.residual << ',' << reference_map << '\n';
      std::cerr << "  " << s.name << ": " << run.report.iterations << " sweeps, converged " << run.report.converged
                << ", rms error " << errors.rms_errors(run.velocity)[0] << "; "
                << residual_spread(run.contacts, run.velocity) << "; largest p_n / median "
                << impulse_spread(run.contacts) << "\n";
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  try {
    return run(parse_options(argc, argv));
  } catch (const std::exception& failure) {
    std::cerr << failure.what() << "\n";
    return 1;
  }
}
