#include "analysis/published_run.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "analysis/creep_results.h"
#include "analysis/layer_geometry.h"
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
                  if (fields[1].empty() && fields[2].empty()) {  // ResultRow::recorded false
                    results.add_not_recorded(fields[0], fields[3], fields[4]);
                    return;
                  }
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

// The text of "key" in params.json (the campaign's record of a run's deck variables, flat
// "key": "value" pairs); none when it has no such key.
std::optional<std::string> json_text(const std::string& path, const std::string& key)
{
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open");
  std::stringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  std::smatch match;
  if (!std::regex_search(content, match, std::regex("\"" + key + "\"\\s*:\\s*\"?([^\",}\\s]+)"))) return std::nullopt;
  return match[1].str();
}

double json_number(const std::string& path, const std::string& key)
{
  const auto text = json_text(path, key);
  if (!text) throw InputError(path, 0, "no value for \"" + key + "\"");
  LineSource source(path);  // names the file in a malformed number's error
  return parse_number(*text, source, key);
}

// Narrowest spacing of the bins (profile.csv leaves out the empty bins above the surface).
double bin_width(const std::vector<double>& z_d)
{
  double width = INFINITY;
  for (size_t i = 1; i < z_d.size(); ++i) width = std::min(width, z_d[i] - z_d[i - 1]);
  return width;
}

// u(z) and phi(z) from profile.csv (its phi column, else its counts with L and the dispersity of
// params.json: phi left empty, with a warning, without them), then, when results.csv lacks them,
// phi_bulk, h_packing and I_packing.
void add_published_profile(const std::filesystem::path& folder, RunAnalysis& run)
{
  const auto profile_path = (folder / "profile.csv").string(), params_path = (folder / "params.json").string();
  const auto published = read_published_profile(profile_path);
  VelocityProfile profile{published.z_d, published.u, published.count, published.phi, bin_width(published.z_d)};
  std::string source = "profile.csv, phi";
  if (profile.phi.empty()) {
    if (!std::filesystem::exists(params_path)) {
      run.warnings.push_back(profile_path + " has no phi and " + params_path +
                             " is missing (L, dispersity): phi(z), phi_bulk and h_packing not estimated from the "
                             "counts");
      run.profile = profile;
      return;
    }
    const double length = json_number(params_path, "L"), dispersity = json_number(params_path, "dispersity");
    try {
      profile.phi = packing_from_counts(profile.count, length, profile.bin_width_d, dispersity);
    } catch (const AnalysisError& e) {
      throw InputError(params_path, 0, e.what());
    }
    source = "profile.csv, count x mean grain area / (L d), L and dispersity from params.json";
  }
  run.profile = profile;
  if (run.results.find("phi_bulk")) return;
  if (auto problem = add_layer_geometry(run.results, PackingProfile{profile.z_d, profile.phi}, source))
    run.warnings.push_back(profile_path + ": " + *problem);
}

// The strings of the "warnings" array of a results.json that ResultTable::write_json wrote.
std::vector<std::string> read_json_warnings(const std::string& path)
{
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open");
  std::stringstream content;
  content << in.rdbuf();
  const std::string text = content.str();
  size_t at = text.find("\"warnings\"");
  at = at == std::string::npos ? at : text.find('[', at);
  if (at == std::string::npos) throw InputError(path, 0, "no \"warnings\" array");
  std::vector<std::string> warnings;
  for (++at; at < text.size() && text[at] != ']'; ++at) {
    if (text[at] != '"') continue;
    std::string warning;
    for (++at; at < text.size() && text[at] != '"'; ++at) {
      if (text[at] == '\\' && ++at < text.size()) warning += text[at] == 'n' ? '\n' : text[at];
      else warning += text[at];
    }
    if (at >= text.size()) throw InputError(path, 0, "unterminated string in \"warnings\"");
    warnings.push_back(warning);
  }
  if (at >= text.size()) throw InputError(path, 0, "unterminated \"warnings\" array");
  return warnings;
}

// `results` with its creep_* rows replaced by `creep`'s, where the first of them stood.
ResultTable with_creep_rows(const ResultTable& results, const CreepMeasure& creep)
{
  ResultTable measured, updated;
  add_creep_results(measured, creep);
  bool placed = false;
  for (const auto& row : results.rows()) {
    if (!is_creep_result(row.name)) updated.add_row(row);
    else if (!placed) updated.append(measured, "");
    placed = placed || is_creep_result(row.name);
  }
  if (!placed) updated.append(measured, "");
  return updated;
}

}  // namespace

PublishedProfile read_published_profile(const std::string& path)
{
  const std::vector<std::string> with_phi{"z_d", "u_sqrt_gd", "count", "phi"};
  const std::vector<std::string> header(with_phi.begin(), with_phi.end() - 1);
  std::string first;
  LineSource peek(path);
  while (peek.next(first) && is_blank(first)) {
  }
  const bool has_phi = csv_fields(first, peek) == with_phi;
  PublishedProfile profile;
  read_csv_rows(path, has_phi ? with_phi : header,
                [&](const std::vector<std::string>& fields, const LineSource& source) {
                  profile.z_d.push_back(parse_number(fields[0], source, "z_d"));
                  profile.u.push_back(parse_number(fields[1], source, "u_sqrt_gd"));
                  profile.count.push_back(parse_number(fields[2], source, "count"));
                  if (has_phi) profile.phi.push_back(parse_number(fields[3], source, "phi"));
                });
  return profile;
}

void update_published_creep(const std::string& directory, const CreepMeasure& creep)
{
  const auto folder = std::filesystem::path(directory);
  const auto csv = (folder / "results.csv").string(), json = (folder / "results.json").string();
  const auto results = with_creep_rows(read_results_csv(csv), creep);
  std::vector<std::string> warnings;
  if (std::filesystem::exists(json))
    for (const auto& warning : read_json_warnings(json))
      if (warning.find(": creep ") == std::string::npos) warnings.push_back(warning);
  for (const auto& problem : creep_problems(creep)) warnings.push_back("profile.csv: creep " + problem);
  results.write_csv(csv);
  results.write_json(json, warnings);
}

std::optional<std::string> recorded_deck_variable(const std::string& directory, const std::string& name)
{
  const auto path = std::filesystem::path(directory) / "params.json";
  if (!std::filesystem::exists(path)) return std::nullopt;
  return json_text(path.string(), name);
}

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
  if (std::filesystem::exists(folder / "profile.csv")) add_published_profile(folder, run);
  return run;
}

}  // namespace cdpost
