#include "analysis/published_run.h"

#include <filesystem>
#include <set>

#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/tokens.h"

namespace cdpost {

namespace {

// The fields of one line of a CSV written by ResultTable::write_csv: quoted fields may hold
// commas and doubled quotes.
std::vector<std::string> csv_fields(const std::string& line, const LineSource& source)
{
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (quoted) source.fail("unterminated quoted field");
  return fields;
}

// Calls on_row(fields, source) for each data row of a CSV whose header must be `header`.
template <typename OnRow>
void read_csv_rows(const std::string& path, const std::vector<std::string>& header, OnRow on_row)
{
  LineSource source(path);
  std::string line;
  bool have_header = false;
  while (source.next(line)) {
    if (is_blank(line)) continue;
    const auto fields = csv_fields(line, source);
    if (!have_header) {
      if (fields != header) source.fail("expected the header " + join_names(header));
      have_header = true;
    } else if (fields.size() != header.size()) {
      source.fail("expected " + std::to_string(header.size()) + " fields (" + join_names(header) + "), found " +
                  std::to_string(fields.size()));
    } else {
      on_row(fields, source);
    }
  }
  if (!have_header) throw InputError(path, 0, "file is empty");
}

ResultTable read_results_csv(const std::string& path)
{
  ResultTable results;
  std::set<std::string> names;
  read_csv_rows(path, {"name", "value", "error", "unit", "description"},
                [&](const std::vector<std::string>& fields, const LineSource& source) {
                  if (fields[0].empty()) source.fail("a result without a name");
                  if (!names.insert(fields[0]).second) source.fail("result '" + fields[0] + "' is given twice");
                  const double value = parse_number(fields[1], source, fields[0]);
                  if (fields[2].empty()) results.add(fields[0], value, fields[3], fields[4]);
                  else
                    results.add(fields[0], Estimate{value, parse_number(fields[2], source, fields[0] + " error")},
                                fields[3], fields[4]);
                });
  return results;
}

std::vector<LayerSpectrum> read_layers_csv(const std::string& path)
{
  std::vector<LayerSpectrum> layers;
  read_csv_rows(path, {"z_d", "f_peak_Hz", "f_error_Hz", "A_peak_sqrt_gd", "A_at_f_sqrt_gd"},
                [&](const std::vector<std::string>& fields, const LineSource& source) {
                  LayerSpectrum layer;
                  layer.z_d = parse_number(fields[0], source, "z_d");
                  layer.peak.frequency_hz = parse_number(fields[1], source, "f_peak_Hz");
                  layer.peak.frequency_error_hz = parse_number(fields[2], source, "f_error_Hz");
                  layer.peak.amplitude = parse_number(fields[3], source, "A_peak_sqrt_gd");
                  layer.amplitude_at_f = parse_number(fields[4], source, "A_at_f_sqrt_gd");
                  layers.push_back(layer);
                });
  return layers;
}

}  // namespace

bool is_published_run(const std::string& directory)
{
  return std::filesystem::is_regular_file(std::filesystem::path(directory) / "results.csv");
}

RunAnalysis read_published_run(const std::string& directory)
{
  const auto folder = std::filesystem::path(directory);
  RunAnalysis run;
  run.settings.directory = directory;
  run.results = read_results_csv((folder / "results.csv").string());
  if (std::filesystem::exists(folder / "layers.csv")) run.layers = read_layers_csv((folder / "layers.csv").string());
  return run;
}

}  // namespace cdpost
