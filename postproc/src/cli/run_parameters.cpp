#include "cli/run_parameters.h"

#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "io/line_source.h"

namespace cdpost {

namespace {

std::string number_text(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

// A recorded value that must be positive (d, g, the sample rate), or nothing if not recorded.
std::optional<double> recorded_positive(const ChuteRecord* record, const std::string& name)
{
  if (!record) return std::nullopt;
  auto value = record->find(name);
  if (value && !(*value > 0))
    throw InputError(record->source, 0, name + " " + number_text(*value) + ": must be positive");
  return value;
}

// "A, B from X; C by default": the values grouped by their source, in order of first appearance.
std::string grouped_by_source(const std::vector<std::pair<std::string, std::string>>& values_and_sources)
{
  std::vector<std::string> sources;
  std::map<std::string, std::string> values;
  for (const auto& [value, source] : values_and_sources) {
    if (!values.count(source)) sources.push_back(source);
    values[source] += (values[source].empty() ? "" : ", ") + value;
  }
  std::string line;
  for (const auto& source : sources)
    line += (line.empty() ? "" : "; ") + values[source] + (source.empty() ? "" : " " + source);
  return line;
}

}  // namespace

Units units_from(const ParsedOptions& options, const std::string& command, const ChuteRecord* record)
{
  Units units;
  units.d_m = options.number("d").value_or(recorded_positive(record, "d_m").value_or(units.d_m));
  units.g_mps2 = options.number("g").value_or(recorded_positive(record, "g_mps2").value_or(units.g_mps2));
  if (!(units.d_m > 0 && units.g_mps2 > 0)) throw UsageError(command + ": --d and --g must be positive");
  auto system = options.text("units").value_or("si");
  if (system == "reduced") units.use_reduced_input();
  else if (system != "si") throw UsageError(command + ": --units must be 'si' or 'reduced', not '" + system + "'");
  for (const char* name : {"length-unit", "time-unit"})
    if (auto value = options.number(name)) {
      if (!(*value > 0)) throw UsageError(command + ": --" + name + " must be positive");
      (std::string(name) == "length-unit" ? units.length_unit_m : units.time_unit_s) = *value;
      units.input = Units::Input::custom;
    }
  return units;
}

RunParameters run_parameters(const ParsedOptions& options, const std::string& command, const std::string& directory,
                             WallTops wall_tops)
{
  const auto record = read_chute_record(directory);
  const ChuteRecord* recorded = record ? &*record : nullptr;
  RunParameters p;
  p.recorded = recorded != nullptr;
  p.units = units_from(options, command, recorded);
  p.d_given = options.text("d") || (recorded && recorded->find("d_m"));
  const std::string from_record = recorded ? "from " + recorded->source : "";
  auto source = [&](const std::string& option, bool in_record) {
    return options.text(option) ? "from --" + option : in_record ? from_record : std::string("by default");
  };
  std::vector<std::pair<std::string, std::string>> described;

  if (auto z0 = options.number("z0")) p.z0 = *z0;
  else if (auto y_top = recorded ? recorded->find("y_top_m") : std::nullopt) p.z0 = *y_top / p.units.length_unit_m;
  // The input's units, when not SI (the unit a chute.params records its values in).
  const bool reduced = p.units.input == Units::Input::reduced;
  if (reduced) described.emplace_back(input_units_text(p.units), "from --units");
  else if (p.units.input == Units::Input::custom)
    described.emplace_back(input_units_text(p.units), "from --length-unit, --time-unit");
  if (p.z0)
    described.emplace_back(
        reduced ? "z0 " + number_text(*p.z0) + " d" : "z0 " + number_text(*p.z0 * p.units.length_unit_m) + " m",
        source("z0", true));
  else if (wall_tops == WallTops::required)
    throw InputError(recorded ? recorded->source : directory, 0,
                     std::string(recorded ? "no y_top_m" : "no chute.params (inputs/in.chute writes it)") +
                         ": give --z0, the height of the wall tops that z is measured from");

  p.sample_rate_hz = options.number("sample-rate");
  if (!p.sample_rate_hz) p.sample_rate_hz = recorded_positive(recorded, "sample_rate_hz");
  if (p.sample_rate_hz)
    described.emplace_back("sample rate " + number_text(*p.sample_rate_hz) + " Hz", source("sample-rate", true));
  else described.emplace_back("sample rate none given or recorded (the time file's longest interval)", "");
  // In reduced input d and g only turn times into seconds and rates into Hz: said so.
  const std::string scales = reduced ? " (converting sqrt(d/g) to s, for the results in Hz and s)" : "";
  described.emplace_back("d " + number_text(p.units.d_m) + " m", source("d", recorded && recorded->find("d_m")));
  described.emplace_back("g " + number_text(p.units.g_mps2) + " m/s^2" + scales,
                         source("g", recorded && recorded->find("g_mps2")));
  p.cell_length_d = options.number("cell-length");
  if (!p.cell_length_d) p.cell_length_d = recorded_positive(recorded, "L_d");
  if (p.cell_length_d)
    described.emplace_back("L " + number_text(*p.cell_length_d) + " d",
                           source("cell-length", recorded && recorded->find("L_d")));
  p.description = grouped_by_source(described);
  return p;
}

void apply_run_parameters(RunSettings& settings, const ParsedOptions& options, const std::string& command)
{
  auto p = run_parameters(options, command, settings.directory, WallTops::required);
  settings.units = p.units;
  settings.z0 = *p.z0;
  settings.sample_rate_hz = p.sample_rate_hz;
  if (!settings.cell_length_d) settings.cell_length_d = p.cell_length_d;  // a series manifest's L comes first
  settings.parameters = p.description;
}

}  // namespace cdpost
