// What a reference run directory says about itself: the run.info the decks write ("key value"
// per line) and the loop times in its LAMMPS or LIGGGHTS log.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cdref {

// run.info of a deck: one "key value" pair per line (see doc/reference.md for the keys).
class RunInfo {
 public:
  std::string source;
  std::map<std::string, std::string> values;

  bool has(const std::string& key) const { return values.count(key) > 0; }
  std::optional<std::string> text(const std::string& key) const;
  // The value of `key` as a finite number; nothing if absent, an InputError if not a number.
  std::optional<double> number(const std::string& key) const;
};

// Reads PATH; a missing file gives an empty RunInfo (a run from another deck), a malformed
// line an InputError naming the file and line.
RunInfo read_run_info(const std::string& path);

// One "Loop time of T on P procs for N steps" line of a LAMMPS or LIGGGHTS log, with the
// "X% CPU use" line LAMMPS prints after it.
struct LoopTime {
  double seconds = 0;  // wall time of the run command's loop
  long procs = 0;
  long steps = 0;
  std::optional<double> cpu_percent;
  long line = 0;
};

// Every loop time of the log, in order (a deck's last run is its flow stage).
std::vector<LoopTime> read_loop_times(const std::string& log_path);

}  // namespace cdref
