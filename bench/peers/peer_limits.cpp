// What bounds ours on each problem (doc/peer_limits.md): W's structure, the answer's uniqueness
// and the sweeps' convergence, one CSV row per problem, start and target:
//
//   peer_limits --out CSV [--run-limit 5] [--limit 0.25] [--floor 1e-8] [--targets 1e-3,1e-4,1e-6]
//               [--state-tolerance 1e-6] [--dense-limit 6000] PROBLEM.hdf5 ...
//
// Each PROBLEM.hdf5 (FCLIB, bench/peers/local_problem.h) has its saved step beside it
// (PROBLEM.cdp), whose contacts give W's factor B (bench/peers/solve_limits.h), checked against the
// file's W. Ours (bench/peers/ours.h) is run from each start (cold, warm) for up to --run-limit
// CPU s of sweeps or until the error (peers::error) is below --floor, the error measured after
// every full sweep and left out of the time; where the ladder of tolerances ends first (14
// solves at their cap), it starts down the ladder again from its iterate. The answer studied is the lowest-error iterate of
// the two runs; its contacts' states, its active block and the directions its impulses are free
// in come from it (bench/peers/solve_limits.h).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "solve_limits.h"
#include "local_problem.h"
#include "option_number.h"
#include "ours.h"
#include "siconos_solvers.h"

namespace {

struct Options {
  std::string out;
  double run_limit = 5.0;  // CPU s of sweeps per run
  double limit = 0.25;     // the comparison's limit: where the runs are read
  double floor = 1e-8;     // a run ends below this error
  double state_tolerance = 1e-6;
  int dense_limit = 6000;  // Gram matrices larger than this: rank by sparse QR, no eigenvalues
  std::vector<double> targets{1e-3, 1e-4, 1e-6};
  std::vector<std::string> problems;
};

template <class Number>
Number number(const std::string& option, const std::string& text)
{
  return peers::option_number<Number>("peer_limits", option, text);
}

[[noreturn]] void refuse(const std::string& what)
{
  throw std::invalid_argument("peer_limits: " + what);
}

Options parse_options(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; i++) {
    const std::string arg = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) refuse(arg + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--out") o.out = value();
    else if (arg == "--run-limit") o.run_limit = number<double>(arg, value());
    else if (arg == "--limit") o.limit = number<double>(arg, value());
    else if (arg == "--floor") o.floor = number<double>(arg, value());
    else if (arg == "--state-tolerance") o.state_tolerance = number<double>(arg, value());
    else if (arg == "--dense-limit") o.dense_limit = number<int>(arg, value());
    else if (arg == "--targets") {
      o.targets.clear();
      std::stringstream list(value());
      for (std::string t; std::getline(list, t, ',');) o.targets.push_back(number<double>(arg, t));
    } else if (arg.rfind("--", 0) == 0) refuse("unknown option " + arg);
    else o.problems.push_back(arg);
  }
  if (o.out.empty() || o.problems.empty()) refuse("usage: peer_limits --out CSV [options] PROBLEM.hdf5 ...");
  return o;
}

// A run ends here: the time is up, or the error is below the floor.
struct RunOver {};

// Records the error after every full sweep and keeps the best iterate.
class Recorder : public cd::SweepObserver {
 public:
  Recorder(const peers::LocalProblem& local, const std::vector<cd::Contact>& contacts, const Options& o)
      : local_(local), contacts_(contacts), meter_(local), o_(o)
  {
  }
  void start() { begin_ = peers::cpu_seconds(); }
  void after_full_sweep(const cd::SolveReport& so_far) override
  {
    const double check_begin = peers::cpu_seconds();
    std::vector<double> reaction = peers::reaction_of(local_, contacts_);
    const double error = meter_(reaction);
    const double seconds = check_begin - begin_ - checks_;
    const cd::SolveReport run = ladder.so_far(so_far);
    trace.push_back({run.iterations, seconds, error, run.contact_updates, run.block_solves + run.kept_block_solves,
                     run.cold_restarts});
    if (!(error >= best_error)) {
      best_error = error;
      best = std::move(reaction);
    }
    checks_ += peers::cpu_seconds() - check_begin;
    if (error <= o_.floor || seconds > o_.run_limit) throw RunOver{};
  }
  peers::Ladder ladder;
  std::vector<peers::TracePoint> trace;
  std::vector<double> best;
  double best_error = NAN;

 private:
  const peers::LocalProblem& local_;
  const std::vector<cd::Contact>& contacts_;
  peers::ErrorMeter meter_;
  const Options& o_;
  double begin_ = 0.0;
  double checks_ = 0.0;
};

struct Run {
  std::vector<peers::TracePoint> trace;
  std::vector<double> best;  // the lowest-error iterate
  double best_error = NAN;
};

Run run_ours(const cd::ContactProblem& problem, const peers::LocalProblem& local, bool warm, const Options& o)
{
  std::vector<cd::Contact> contacts = problem.contacts;
  if (!warm)
    for (cd::Contact& c : contacts) c.impulse = {};
  std::vector<cd::BodyVelocity> velocity = problem.free_velocity;
  Recorder recorder(local, contacts, o);
  recorder.start();
  cd::apply_impulses(contacts, velocity);
  try {  // down the ladder, and down again from its iterate while the run has time
    for (int before = -1; recorder.ladder.finished.iterations > before;) {
      before = recorder.ladder.finished.iterations;
      peers::solve_down_the_ladder(contacts, velocity, recorder, peers::deck_settings(), recorder.ladder);
    }
  } catch (const RunOver&) {
  }
  return {recorder.trace, recorder.best, recorder.best_error};
}

Eigen::Map<const Eigen::VectorXd> as_vector(const std::vector<double>& x)
{
  return {x.data(), static_cast<Eigen::Index>(x.size())};
}

// One problem's structure at its answer.
struct Structure {
  int grains = 0;
  double mismatch = 0.0;
  peers::Spectrum w, active, faces;  // faces: P^T W P scaled to unit diagonal
  int sticking = 0, sliding = 0;
  double answer_error = NAN;
  double spread_r = NAN, spread_u = NAN;  // cold and warm answers apart, relative
};

Structure structure(const cd::ContactProblem& problem, const peers::LocalProblem& local, const Run& cold,
                    const Run& warm, const Options& o)
{
  Structure s;
  const peers::Mobility b = peers::mobility(problem.contacts, local.impulse_scale);
  s.grains = b.grains;
  s.mismatch = peers::factor_mismatch(b, local);
  if (!(s.mismatch < 1e-10)) refuse(local.label + ": B B^T differs from W by " + std::to_string(s.mismatch));
  s.w = peers::gram_spectrum(b.factor, o.dense_limit);
  const Run& answer = cold.best_error <= warm.best_error ? cold : warm;
  s.answer_error = answer.best_error;
  const std::vector<peers::State> states = peers::contact_states(local, answer.best, o.state_tolerance);
  for (const peers::State state : states) {
    s.sticking += state == peers::State::stick;
    s.sliding += state == peers::State::slide;
  }
  s.active = peers::gram_spectrum(peers::active_rows(b.factor, states), o.dense_limit);
  const peers::SparseMatrix faces =  // B^T P: (B^T P)^T B^T P = P^T W P
      peers::SparseMatrix(b.factor.transpose()) * peers::free_directions(local, answer.best, states);
  s.faces = peers::gram_spectrum(peers::SparseMatrix(peers::unit_diagonal(faces).transpose()), o.dense_limit);
  s.spread_r = (as_vector(cold.best) - as_vector(warm.best)).norm() / as_vector(answer.best).norm();
  s.spread_u = (as_vector(local.velocity(cold.best)) - as_vector(local.velocity(warm.best))).norm() /
               as_vector(local.velocity(answer.best)).norm();
  return s;
}

int run(const Options& o)
{
  std::ofstream csv(o.out);
  if (!csv) refuse("cannot write " + o.out);
  csv << "problem,class,start,target,contacts,unknowns,grains,dof,"
         "w_rank,w_null,w_largest,w_smallest_nonzero,w_largest_zero,w_range_condition,"
         "sticking,sliding,active_rank,active_null,faces,indeterminate,faces_smallest_nonzero,faces_largest_zero,"
         "predicted_rate,predicted_sweeps_per_decade,answer_error,spread_r,spread_u,"
         "error_at_limit,last_error_at_limit,sweeps_at_limit,updates_at_limit,block_solves_at_limit,"
         "cold_restarts_at_limit,sweep_seconds,update_seconds,"
         "tail_rate,tail_sweeps_per_decade,tail_decades_per_second,"
         "sweeps_to_target,seconds_to_target,measured_sweeps_per_decade,"
         "predicted_sweeps_to_target,predicted_seconds_to_target,run_sweeps,run_seconds,run_error\n";
  csv.precision(6);
  for (const std::string& path : o.problems) {
    const peers::LocalProblem local = peers::read_fclib(path);
    const std::string saved = path.substr(0, path.rfind(".hdf5")) + ".cdp";
    const cd::ContactProblem problem = cd::read_problem(saved);
    if (!peers::same_problem(local, peers::local_problem(problem)))
      refuse(path + " and " + saved + " are not the same problem");
    const std::filesystem::path where(path);
    std::cerr << where.filename().string() << ": " << local.contacts << " contacts\n";
    const Run runs[] = {run_ours(problem, local, false, o), run_ours(problem, local, true, o)};
    const Structure s = structure(problem, local, runs[0], runs[1], o);
    const double predicted = peers::predicted_rate(s.faces);
    std::cerr << "  rank " << s.w.rank << " of " << local.size() << ", active null " << s.active.null_dimension
              << ", indeterminate " << s.faces.null_dimension << ", answer error " << s.answer_error << "\n";
    for (int start = 0; start < 2; start++) {
      const Run& r = runs[start];
      if (r.trace.empty()) refuse(path + ": a run ended before its first full sweep");
      const peers::TailFit tail = peers::fit_tail(r.trace, o.limit);
      const double at_limit = peers::best_error_within(r.trace, o.limit);
      peers::TracePoint limit_sweep{0, 0.0, NAN};  // the last full sweep within the limit: its own error
      for (const peers::TracePoint& p : r.trace)
        if (p.seconds <= o.limit) limit_sweep = p;
      const peers::TracePoint& last = r.trace.back();
      for (const double target : o.targets) {
        const peers::TracePoint* reached = peers::first_reaching(r.trace, target);
        // The run's own pace over the two decades before the target.
        const peers::TracePoint* two_decades_before = peers::first_reaching(r.trace, 100.0 * target);
        const double measured_pace =
            reached && two_decades_before ? 0.5 * (reached->sweeps - two_decades_before->sweeps) : NAN;
        // From where the run stands at the limit, at the pace of its tail.
        const double decades_left = std::max(0.0, std::log10(at_limit / target));
        const double sweeps_per_decade = std::log(0.1) / std::log(tail.rate_per_sweep);
        const double forecast_sweeps = decades_left > 0.0 ? limit_sweep.sweeps + decades_left * sweeps_per_decade : NAN;
        const double forecast_seconds = decades_left == 0.0 ? NAN
                                        : tail.decades_per_second > 0.0
                                            ? o.limit + decades_left / tail.decades_per_second
                                            : INFINITY;
        csv << where.filename().string() << ',' << where.parent_path().filename().string() << ','
            << (start == 0 ? "cold" : "warm") << ',' << target << ',' << local.contacts << ',' << local.size() << ','
            << s.grains << ',' << 3 * s.grains << ',' << s.w.rank << ',' << s.w.null_dimension << ',' << s.w.largest
            << ',' << s.w.smallest_nonzero << ',' << s.w.largest_zero << ',' << s.w.range_condition() << ','
            << s.sticking << ',' << s.sliding << ',' << s.active.rank << ',' << s.active.null_dimension << ','
            << s.faces.rows << ',' << s.faces.null_dimension << ',' << s.faces.smallest_nonzero << ','
            << s.faces.largest_zero << ',' << predicted << ',' << std::log(0.1) / std::log(predicted) << ','
            << s.answer_error << ',' << s.spread_r << ',' << s.spread_u << ',' << at_limit << ',' << limit_sweep.error
            << ',' << limit_sweep.sweeps << ',' << limit_sweep.contact_updates << ',' << limit_sweep.block_solves << ','
            << limit_sweep.cold_restarts << ',' << last.seconds / last.sweeps << ','
            << last.seconds / last.contact_updates << ',' << tail.rate_per_sweep << ',' << sweeps_per_decade << ','
            << tail.decades_per_second << ',' << (reached ? reached->sweeps : -1) << ','
            << (reached ? reached->seconds : NAN) << ',' << measured_pace << ',' << forecast_sweeps << ','
            << forecast_seconds << ',' << last.sweeps << ',' << last.seconds << ',' << r.best_error << '\n';
      }
    }
    csv.flush();
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
