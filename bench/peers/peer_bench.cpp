// Every solver on every problem, one machine, one run (doc/peers.md):
//
//   peer_bench --list   (the solvers' names: ours, Siconos's at their defaults, the variants studied)
//   peer_bench --out CSV [--time-limit 2] [--wall-limit S] [--targets 1e-3,1e-4,1e-6] [--starts cold,warm]
//              [--repeat N] [--solvers ours,fc2d_nsgs,fc3d_nsn_fb[ls=armijo],...] PROBLEM.hdf5 ...
//
// A Siconos solver may be named with options (bench/peers/siconos_variants.h); an unknown name,
// option or value is refused in one line before any solve. --wall-limit: a Siconos child is ended
// after S s of wall clock (default 3x the time limit plus 1 s; ours' children get at least their
// own); longer on a loaded machine, where a child ended short of its CPU limit is "starved".
// Each PROBLEM.hdf5 (an FCLIB local problem, bench/peers/local_problem.h) has its saved step
// beside it (PROBLEM.cdp), which ours solves; the two must be the same problem bit for bit. Its
// class is the name of its folder. For each solver, start (cold: r = 0; warm: the step's warm
// start) and target error (peers::error, Siconos's fc2d_compute_error) it records the time to
// reach the target, the work, the error reached and how it ended, each solve in a child process
// that the time limit ends (a solver that crashes or hangs costs that problem only). Times are
// CPU seconds of the child (peers::cpu_seconds); the limit is wall-clock. --repeat N: a solve is
// run again in its child from the same start, up to N times while its runs add up to under
// repeat_budget, and its time is the runs' median; a solve of a millisecond is otherwise mostly
// the child's first touches of its memory (copy-on-write faults), not the method.
//
// Ours: Gauss–Seidel at the deck's settings (inputs/in.chute: tolerance 1e-3, conjugate
// acceleration, full sweep every 8, stall rescue on); ours_newton: the same with the Newton
// polish (newton_polish yes, cd/newton_polish.h); ours_over_relaxed: with over_relaxation 1.8. Each is stopped at the first full sweep whose
// iterate meets the target; if it ends on its own norm first, it goes on from its iterate with
// its tolerance ten times lower. The error checks are timed apart and left out of its time.
// Siconos: the solver at tolerance = target; if its answer misses the target by our measure, it
// solves again from the same start with its tolerance ten times lower (up to three times), the
// times summed.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cd/gauss_seidel.h"
#include "local_problem.h"
#include "option_number.h"
#include "ours.h"
#include "repeated_runs.h"
#include "siconos_solvers.h"
#include "siconos_variants.h"

namespace {

struct Options {
  std::string out;
  double time_limit = 2.0;  // s per solve
  double wall_limit = 0.0;  // s of wall clock before a child is ended (0: 3x the time limit plus 1 s)
  std::vector<double> targets{1e-3, 1e-4, 1e-6};
  std::vector<std::string> starts{"cold", "warm"};
  int repeat = 1;  // runs of a short solve (above)
  std::vector<std::string> solvers;
  std::vector<std::string> problems;
};

[[noreturn]] void refuse(const std::string& what)
{
  throw std::invalid_argument("peer_bench: " + what);
}

template <class Number>
Number number(const std::string& option, const std::string& text)
{
  return peers::option_number<Number>("peer_bench", option, text);
}

std::vector<std::string> split(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

// Siconos's solvers at their defaults, then the variants studied (bench/peers/siconos_variants.h).
std::vector<std::string> siconos_names()
{
  std::vector<std::string> names = peers::siconos_solver_names();
  for (const std::string& name : peers::siconos_variant_names()) names.push_back(name);
  return names;
}

Options parse_options(int argc, char** argv)
{
  Options o;
  o.solvers = peers::ours_names();
  for (const std::string& name : siconos_names()) o.solvers.push_back(name);
  for (int i = 1; i < argc; i++) {
    const std::string arg = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) refuse(arg + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--out") o.out = value();
    else if (arg == "--time-limit") o.time_limit = number<double>(arg, value());
    else if (arg == "--wall-limit") o.wall_limit = number<double>(arg, value());
    else if (arg == "--targets") {
      o.targets.clear();
      for (const std::string& t : split(value())) o.targets.push_back(number<double>(arg, t));
    } else if (arg == "--starts") o.starts = split(value());
    else if (arg == "--solvers") o.solvers = split(value());
    else if (arg == "--repeat") {
      o.repeat = number<int>(arg, value());
      if (o.repeat < 1) refuse("--repeat must be >= 1, got " + std::to_string(o.repeat));
    } else if (arg == "--list") {
      for (const std::string& name : peers::ours_names()) std::cout << name << ',';
      for (const std::string& name : siconos_names()) std::cout << name << (name == siconos_names().back() ? "" : ",");
      std::cout << '\n';
      std::exit(0);
    } else if (arg.rfind("--", 0) == 0) refuse("unknown option " + arg);
    else o.problems.push_back(arg);
  }
  if (o.out.empty() || o.problems.empty()) refuse("usage: peer_bench --out CSV [options] PROBLEM.hdf5 ...");
  for (const std::string& s : o.starts)
    if (s != "cold" && s != "warm") refuse("a start is cold or warm, got '" + s + "'");
  for (const std::string& s : o.solvers)
    if (!peers::is_ours(s)) peers::siconos_options(s);  // an unknown name or option: refused here
  return o;
}

// What a solve sends back from its child process.
struct Outcome {
  double seconds = 0.0;        // the solver's time (ours: without the error checks)
  double check_seconds = 0.0;  // ours: the error checks
  double error = NAN;
  int iterations = 0;  // ours: sweeps; Siconos: its iterations
  int attempts = 0;    // ours: tolerances used; Siconos: solves
  int info = 0;        // Siconos's last info
  bool solved = false;
  double reaction_norm = NAN;  // |r| of the answer
  // |F| of the answer over the problem's own scale, max(|q|, |r0|, |W r0 + q|) with r0 the warm
  // start, where Siconos's error divides by the answer's: an answer cannot lower it by growing |r|.
  double error_at_problem_scale = NAN;
  int runs = 1;  // --repeat: the runs whose median is `seconds`
};

// reaction_norm and error_at_problem_scale of the answer (measured after the clock).
void record_scales(const peers::LocalProblem& local, const std::vector<double>& reaction, Outcome& outcome)
{
  outcome.reaction_norm = std::sqrt(std::inner_product(reaction.begin(), reaction.end(), reaction.begin(), 0.0));
  outcome.error_at_problem_scale = peers::error_at_problem_scale(local, reaction);
}

// Ours stops here when the iterate meets the target or the time is up.
struct Stop {
  bool solved;
};

class TargetWatch : public cd::SweepObserver {
 public:
  TargetWatch(const peers::LocalProblem& local, const std::vector<cd::Contact>& contacts, double target,
              double time_limit, Outcome& outcome)
      : local_(local), contacts_(contacts), meter_(local), target_(target), time_limit_(time_limit), outcome_(outcome)
  {
  }
  void start(double cpu_begin) { cpu_begin_ = cpu_begin; }
  void after_full_sweep(const cd::SolveReport& so_far) override
  {
    const double begin = peers::cpu_seconds();
    outcome_.error = meter_(peers::reaction_of(local_, contacts_));
    outcome_.check_seconds += peers::cpu_seconds() - begin;
    outcome_.iterations = ladder.so_far(so_far).iterations;
    if (outcome_.error <= target_) throw Stop{true};
    if (peers::cpu_seconds() - cpu_begin_ - outcome_.check_seconds > time_limit_) throw Stop{false};
  }
  peers::Ladder ladder;

 private:
  const peers::LocalProblem& local_;
  const std::vector<cd::Contact>& contacts_;
  peers::ErrorMeter meter_;
  double target_;
  double cpu_begin_ = 0.0;
  double time_limit_;
  Outcome& outcome_;
};

Outcome solve_ours(const cd::ContactProblem& problem, const peers::LocalProblem& local, bool warm, double target,
                   double time_limit, const cd::SolverSettings& settings)
{
  Outcome outcome;
  std::vector<cd::Contact> contacts = problem.contacts;
  if (!warm)
    for (cd::Contact& c : contacts) c.impulse = {};
  std::vector<cd::BodyVelocity> velocity = problem.free_velocity;
  TargetWatch watch(local, contacts, target, time_limit, outcome);  // its error meter's set-up is not timed
  const double cpu_begin = peers::cpu_seconds();
  watch.start(cpu_begin);
  cd::apply_impulses(contacts, velocity);
  try {
    peers::solve_down_the_ladder(contacts, velocity, watch, settings, watch.ladder);
  } catch (const Stop& stop) {
    outcome.solved = stop.solved;
  }
  outcome.attempts = watch.ladder.solves;
  outcome.seconds = peers::cpu_seconds() - cpu_begin - outcome.check_seconds;
  record_scales(local, peers::reaction_of(local, contacts), outcome);
  return outcome;
}

Outcome solve_siconos(const peers::LocalProblem& local, const std::string& solver, bool warm, double target)
{
  Outcome outcome;
  const std::vector<double> start = warm ? local.warm_start : std::vector<double>(local.size(), 0.0);
  peers::SiconosSettings settings;
  settings.tolerance = target;
  for (; outcome.attempts < 4 && !outcome.solved; settings.tolerance /= 10.0) {
    const peers::SiconosResult result = peers::solve_with_siconos(local, solver, settings, start);
    outcome.attempts++;
    outcome.seconds += result.seconds;
    outcome.iterations += result.iterations;
    outcome.error = result.error;
    outcome.info = result.info;
    outcome.solved = std::isfinite(result.error) && result.error <= target;
    record_scales(local, result.reaction, outcome);
  }
  return outcome;
}

constexpr double repeat_budget = 0.05;  // CPU s: the runs of --repeat stop once they add up to this

// Runs `solve` in a child process; the status says how it ended: solved within the time limit
// (CPU seconds), time_limit (over it, or the child still running at `wall_limit` seconds of wall
// clock with more CPU time than the limit), starved (ended at the wall limit short of the CPU
// limit: other jobs took the cores; to be run again), not_solved (ended without the target),
// crashed, refused.
template <class Solve>
Outcome in_child(Solve solve, double time_limit, double wall_limit, std::string& status)
{
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) refuse("cannot make a pipe");
  std::cout.flush();
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    alarm(static_cast<unsigned>(std::ceil(wall_limit)));
    Outcome outcome;
    int code = 0;
    try {
      outcome = solve();
    } catch (const std::exception& refused) {
      std::fprintf(stderr, "%s\n", refused.what());
      code = 3;
    }
    if (write(pipe_ends[1], &outcome, sizeof(outcome)) != static_cast<ssize_t>(sizeof(outcome))) code = 4;
    _exit(code);
  }
  close(pipe_ends[1]);
  Outcome outcome;
  const bool sent = read(pipe_ends[0], &outcome, sizeof(outcome)) == static_cast<ssize_t>(sizeof(outcome));
  close(pipe_ends[0]);
  int how = 0;
  rusage used{};
  wait4(child, &how, 0, &used);
  const double child_cpu = static_cast<double>(used.ru_utime.tv_sec + used.ru_stime.tv_sec) +
                           1e-6 * static_cast<double>(used.ru_utime.tv_usec + used.ru_stime.tv_usec);
  if (WIFSIGNALED(how) && WTERMSIG(how) == SIGALRM)  // under the CPU limit at the wall limit: the machine starved it
    status = child_cpu < time_limit ? "starved" : "time_limit";
  else if (WIFSIGNALED(how)) status = "crashed";
  else if (WEXITSTATUS(how) == 3) status = "refused";
  else if (!sent) status = "crashed";
  else if (outcome.solved && outcome.seconds <= time_limit) status = "solved";
  else status = outcome.seconds > time_limit ? "time_limit" : "not_solved";
  return outcome;
}

// Ours stops itself at the CPU limit; its error checks, left out of its time, can cost more wall
// clock than its sweeps on large problems, so its child is given room for them.
double ours_wall_limit(double time_limit)
{
  return 20.0 * time_limit + 1.0;
}

std::string folder_name(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  const std::string folder = path.substr(0, slash);
  return folder.substr(folder.find_last_of('/') + 1);
}

std::string base_name(const std::string& path)
{
  return path.substr(path.find_last_of('/') + 1);
}

int run(const Options& o)
{
  std::ofstream csv(o.out);
  if (!csv) refuse("cannot write " + o.out);
  csv << "problem,class,contacts,solver,start,target,status,seconds,iterations,error,check_seconds,attempts,info,"
         "reaction_norm,error_at_problem_scale,runs\n";
  for (const std::string& path : o.problems) {
    const peers::LocalProblem local = peers::read_fclib(path);
    const std::string saved = path.substr(0, path.rfind(".hdf5")) + ".cdp";
    const cd::ContactProblem problem = cd::read_problem(saved);
    if (!peers::same_problem(local, peers::local_problem(problem)))
      refuse(path + " and " + saved + " are not the same problem");
    std::cerr << base_name(path) << ": " << local.contacts << " contacts\n";
    for (const std::string& solver : o.solvers)
      for (const std::string& start : o.starts) {
        const bool warm = start == "warm";
        bool gave_up = false;  // a looser target missed in time: the tighter ones are not tried
        for (const double target : o.targets) {
          std::string status = "skipped";
          Outcome outcome;
          if (!gave_up) {
            if (peers::is_ours(solver))
              outcome = in_child(
                  [&] {
                    return peers::repeated<Outcome>(
                        [&] {
                          return solve_ours(problem, local, warm, target, o.time_limit, peers::ours_settings(solver));
                        },
                        o.repeat, repeat_budget);
                  },
                  o.time_limit, std::max(o.wall_limit, ours_wall_limit(o.time_limit)), status);
            else
              outcome = in_child(
                  [&] {
                    return peers::repeated<Outcome>([&] { return solve_siconos(local, solver, warm, target); },
                                                    o.repeat, repeat_budget);
                  },
                  o.time_limit, o.wall_limit > 0.0 ? o.wall_limit : 3.0 * o.time_limit + 1.0, status);
          }
          gave_up = status != "solved" && status != "not_solved";
          csv << base_name(path) << ',' << folder_name(path) << ',' << local.contacts << ',' << solver << ',' << start
              << ',' << target << ',' << status << ',' << outcome.seconds << ',' << outcome.iterations << ','
              << outcome.error << ',' << outcome.check_seconds << ',' << outcome.attempts << ',' << outcome.info << ','
              << outcome.reaction_norm << ',' << outcome.error_at_problem_scale << ',' << outcome.runs << '\n';
          csv.flush();
          std::cerr << "  " << solver << ' ' << start << ' ' << target << ": " << status << ", " << outcome.seconds
                    << " s, error " << outcome.error << "\n";
        }
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
