#include "output/results.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace cdpost {

namespace {

std::string number(double value, int digits = 10)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string csv_field(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string json_string(const std::string& text)
{
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string shown_value(const ResultRow& row)
{
  return row.recorded ? format_estimate(row.value, row.error) : "not recorded";
}

}  // namespace

std::ofstream open_output(const std::string& path)
{
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  return out;
}

void ResultTable::add(const std::string& name, const Estimate& estimate, const std::string& unit,
                      const std::string& description)
{
  if (!std::isfinite(estimate.value) || (estimate.error && !std::isfinite(*estimate.error)))
    throw AnalysisError("the result '" + name + "' is not a finite number");
  rows_.push_back({name, estimate.value, estimate.error, unit, description});
}

void ResultTable::add(const std::string& name, double value, const std::string& unit, const std::string& description)
{
  add(name, Estimate{value, std::nullopt}, unit, description);
}

void ResultTable::add_not_recorded(const std::string& name, const std::string& unit, const std::string& description)
{
  rows_.push_back({name, 0.0, std::nullopt, unit, description, false});
}

void ResultTable::add_row(const ResultRow& row)
{
  if (row.recorded) add(row.name, Estimate{row.value, row.error}, row.unit, row.description);
  else add_not_recorded(row.name, row.unit, row.description);
}

void ResultTable::append(const ResultTable& other, const std::string& prefix)
{
  for (auto row : other.rows_) {
    row.name = prefix + row.name;
    rows_.push_back(row);
  }
}

const ResultRow* ResultTable::find(const std::string& name) const
{
  for (const auto& row : rows_)
    if (row.name == name && row.recorded) return &row;
  return nullptr;
}

void ResultTable::write_csv(const std::string& path) const
{
  auto out = open_output(path);
  out << "name,value,error,unit,description\n";
  for (const auto& row : rows_)
    out << row.name << ',' << (row.recorded ? number(row.value) : "") << ',' << (row.error ? number(*row.error) : "")
        << ',' << csv_field(row.unit) << ',' << csv_field(row.description) << '\n';
}

void ResultTable::write_json(const std::string& path, const std::vector<std::string>& warnings) const
{
  auto out = open_output(path);
  out << "{\n  \"results\": [\n";
  for (size_t i = 0; i < rows_.size(); ++i) {
    const auto& row = rows_[i];
    out << "    {\"name\": " << json_string(row.name) << ", \"value\": " << (row.recorded ? number(row.value) : "null")
        << ", \"error\": " << (row.error ? number(*row.error) : "null") << ", \"unit\": " << json_string(row.unit)
        << ", \"description\": " << json_string(row.description) << "}" << (i + 1 < rows_.size() ? "," : "") << "\n";
  }
  out << "  ],\n  \"warnings\": [";
  for (size_t i = 0; i < warnings.size(); ++i) out << (i ? ", " : "") << json_string(warnings[i]);
  out << "]\n}\n";
}

std::string ResultTable::markdown() const
{
  std::ostringstream out;
  out << "| quantity | value | unit | meaning |\n|---|---|---|---|\n";
  for (const auto& row : rows_)
    out << "| `" << row.name << "` | " << shown_value(row) << " | " << row.unit << " | " << row.description << " |\n";
  return out.str();
}

std::string ResultTable::text() const
{
  size_t width = 0;
  for (const auto& row : rows_) width = std::max(width, row.name.size());
  std::ostringstream out;
  for (const auto& row : rows_)
    out << row.name << std::string(width + 2 - row.name.size(), ' ') << shown_value(row)
        << (row.recorded ? " " + row.unit : std::string()) << '\n';
  return out.str();
}

void write_columns_csv(const std::string& path, const std::vector<std::string>& names,
                       const std::vector<std::vector<double>>& columns)
{
  auto out = open_output(path);
  for (size_t c = 0; c < names.size(); ++c) out << (c ? "," : "") << names[c];
  out << '\n';
  const size_t rows = columns.empty() ? 0 : columns[0].size();
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << number(columns[c][r]);
    out << '\n';
  }
}

}  // namespace cdpost
