// The comparison as text: tables (CSV, Markdown), long CSV files, formatting helpers.
#include "comparison_tables.h"

#include <cstdio>
#include <functional>
#include <sstream>
#include <vector>

#include "output/results.h"

namespace cdref {

using cdpost::format_estimate;

std::string short_number(double x)
{
  return format_estimate(x, std::nullopt);
}

std::string code_name(const std::string& code)
{
  if (code == "lammps-granular") return "LAMMPS GRANULAR";
  if (code == "liggghts") return "LIGGGHTS";
  if (code == "lmp_cd") return "lmp_cd";
  return code;
}

std::optional<double> result_value(const ComparedRun& r, const std::string& name)
{
  if (const auto* row = r.analysis.results.find(name)) return row->value;
  return std::nullopt;
}
std::optional<double> result_error(const ComparedRun& r, const std::string& name)
{
  if (const auto* row = r.analysis.results.find(name)) return row->error;
  return std::nullopt;
}

namespace {

std::string cell(const std::optional<double>& value, const std::optional<double>& error = std::nullopt)
{
  return value ? format_estimate(*value, error) : std::string("-");
}

struct Column {
  std::string name, unit;
  std::function<std::optional<double>(const ComparedRun&)> value;
  std::function<std::optional<double>(const ComparedRun&)> error;
};

std::vector<Column> table_columns()
{
  auto none = [](const ComparedRun&) -> std::optional<double> { return std::nullopt; };
  auto result = [](const std::string& name) { return [name](const ComparedRun& r) { return result_value(r, name); }; };
  auto result_err = [](const std::string& name) {
    return [name](const ComparedRun& r) { return result_error(r, name); };
  };
  return {
      {"k", "m g/d", [](const ComparedRun& r) { return r.k_reduced; }, none},
      {"f_contact", "Hz", [](const ComparedRun& r) { return r.f_contact_hz; }, none},
      {"overlap_target", "d", [](const ComparedRun& r) { return r.overlap_target; }, none},
      {"overlap_mean", "d",
       [](const ComparedRun& r) { return r.overlaps ? std::optional<double>(r.overlaps->mean) : std::nullopt; }, none},
      {"overlap_max", "d",
       [](const ComparedRun& r) { return r.overlaps ? std::optional<double>(r.overlaps->max) : std::nullopt; }, none},
      {"U", "sqrt(g d)", result("U"), result_err("U")},
      {"phi", "", result("phi"), result_err("phi")},
      {"h", "d", result("h"), result_err("h")},
      {"f", "Hz", result("f"), result_err("f")},
      {"A", "sqrt(g d)", result("A"), none},
      {"f_flow", "Hz",
       [](const ComparedRun& r) {
         return r.flow_peak ? std::optional<double>(r.flow_peak->frequency_hz) : std::nullopt;
       },
       [](const ComparedRun& r) {
         return r.flow_peak ? std::optional<double>(r.flow_peak->frequency_error_hz) : std::nullopt;
       }},
      {"A_flow", "sqrt(g d)",
       [](const ComparedRun& r) { return r.flow_peak ? std::optional<double>(r.flow_peak->amplitude) : std::nullopt; },
       none},
      {"f_contact_band", "Hz",
       [](const ComparedRun& r) {
         return r.contact_peak ? std::optional<double>(r.contact_peak->frequency_hz) : std::nullopt;
       },
       [](const ComparedRun& r) {
         return r.contact_peak ? std::optional<double>(r.contact_peak->frequency_error_hz) : std::nullopt;
       }},
      {"A_contact_band", "sqrt(g d)",
       [](const ComparedRun& r) {
         return r.contact_peak ? std::optional<double>(r.contact_peak->amplitude) : std::nullopt;
       },
       none},
      {"contact_excess", "", [](const ComparedRun& r) { return r.contact_excess; }, none},
      {"A_mean", "sqrt(g d)", result("A_mean"), none},
      {"wall_per_physical_s", "s/s", [](const ComparedRun& r) { return r.wall_per_physical_second(); }, none},
      {"cpu_per_physical_s", "s/s", [](const ComparedRun& r) { return r.cpu_per_physical_second(); }, none},
  };
}

std::string csv_text(const std::optional<double>& x)
{
  if (!x) return "";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.8g", *x);
  return buffer;
}

}  // namespace

void write_table_csv(const Comparison& c, const std::string& path)
{
  auto out = cdpost::open_output(path);
  const auto columns = table_columns();
  out << "run,label,code,model,stationary";
  for (const auto& col : columns) out << ',' << col.name << (col.unit.empty() ? "" : "_" + col.unit) << ",error";
  out << '\n';
  for (const auto& r : c.runs) {
    out << '"' << r.directory << "\",\"" << r.label << "\"," << r.code << ',' << r.model << ','
        << (r.stationary ? 1 : 0);
    for (const auto& col : columns) out << ',' << csv_text(col.value(r)) << ',' << csv_text(col.error(r));
    out << '\n';
  }
}

std::string markdown_table(const Comparison& c)
{
  const auto columns = table_columns();
  std::ostringstream out;
  out << "| run | model |";
  for (const auto& col : columns) out << ' ' << col.name << (col.unit.empty() ? "" : " (" + col.unit + ")") << " |";
  out << "\n|---|---|";
  for (size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << '\n';
  for (const auto& r : c.runs) {
    out << "| " << r.label << (r.stationary ? "" : " (not stationary)") << " | " << code_name(r.code) << ' ' << r.model
        << " |";
    for (const auto& col : columns) out << ' ' << cell(col.value(r), col.error(r)) << " |";
    out << '\n';
  }
  return out.str();
}

void write_long_csvs(const Comparison& c, const std::string& out)
{
  auto spectra = cdpost::open_output(out + "/spectra.csv");
  spectra << "label,f_Hz,A_sqrt_gd\n";
  for (const auto& r : c.runs) {
    const auto& s = r.analysis.spectrum;
    for (size_t k = 0; k < s.frequency_hz.size(); ++k)
      spectra << '"' << r.label << "\"," << csv_text(s.frequency_hz[k]) << ',' << csv_text(s.amplitude[k]) << '\n';
  }
  auto profiles = cdpost::open_output(out + "/profiles.csv");
  profiles << "label,z_d,u_sqrt_gd,count\n";
  for (const auto& r : c.runs)
    if (r.analysis.profile) {
      const auto& p = *r.analysis.profile;
      for (size_t i = 0; i < p.z_d.size(); ++i)
        profiles << '"' << r.label << "\"," << csv_text(p.z_d[i]) << ',' << csv_text(p.u_reduced[i]) << ','
                 << csv_text(p.count[i]) << '\n';
    }
}

}  // namespace cdref
