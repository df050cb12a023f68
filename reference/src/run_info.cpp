#include "run_info.h"

#include <cmath>
#include <filesystem>
#include <regex>

#include "io/line_source.h"
#include "io/tokens.h"

namespace cdref {

using cdpost::InputError;

std::optional<std::string> RunInfo::text(const std::string& key) const
{
  auto found = values.find(key);
  if (found == values.end()) return std::nullopt;
  return found->second;
}

std::optional<double> RunInfo::number(const std::string& key) const
{
  auto value = text(key);
  if (!value) return std::nullopt;
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(*value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value->size() || !std::isfinite(x))
    throw InputError(source, 0, "'" + key + "' is not a finite number: '" + *value + "'");
  return x;
}

RunInfo read_run_info(const std::string& path)
{
  RunInfo info;
  info.source = path;
  if (!std::filesystem::exists(path)) return info;
  cdpost::LineSource source(path);
  std::string line;
  while (source.next(line)) {
    if (cdpost::is_blank(line) || cdpost::is_comment(line)) continue;
    auto tokens = cdpost::split_whitespace(line);
    if (tokens.size() != 2) source.fail("expected 'key value', found " + std::to_string(tokens.size()) + " fields");
    std::string key(tokens[0]);
    if (info.has(key)) source.fail("key '" + key + "' given twice");
    info.values[key] = std::string(tokens[1]);
  }
  return info;
}

std::vector<LoopTime> read_loop_times(const std::string& log_path)
{
  static const std::regex loop(R"(^Loop time of ([0-9.eE+-]+) on ([0-9]+) procs for ([0-9]+) steps)");
  static const std::regex cpu(R"(^\s*([0-9.]+)% CPU use)");
  std::vector<LoopTime> times;
  cdpost::LineSource source(log_path);
  std::string line;
  std::smatch m;
  while (source.next(line)) {
    if (std::regex_search(line, m, loop)) {
      LoopTime t;
      t.seconds = cdpost::parse_number(m.str(1), source, "loop time");
      t.procs = cdpost::parse_integer(m.str(2), source, "procs");
      t.steps = cdpost::parse_integer(m.str(3), source, "steps");
      t.line = source.line_number();
      times.push_back(t);
    } else if (!times.empty() && !times.back().cpu_percent && source.line_number() <= times.back().line + 3 &&
               std::regex_search(line, m, cpu)) {
      times.back().cpu_percent = cdpost::parse_number(m.str(1), source, "CPU use");
    }
  }
  return times;
}

}  // namespace cdref
