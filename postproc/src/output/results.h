// Every number cdpost prints, kept with its error, unit and meaning, and written as CSV,
// JSON and Markdown from the same table.
#pragma once

#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "signal/statistics.h"

namespace cdpost {

struct ResultRow {
  std::string name;
  double value = 0;
  std::optional<double> error;
  std::string unit;  // "" for dimensionless
  std::string description;
  // False for a quantity the run did not record: written "not recorded" (Markdown, text), an
  // empty value (CSV) or null (JSON), never as a number; find() does not return it.
  bool recorded = true;
};

class ResultTable {
 public:
  // Refuses non-finite values (AnalysisError naming the quantity): nothing is written as NaN.
  void add(const std::string& name, const Estimate& estimate, const std::string& unit, const std::string& description);
  void add(const std::string& name, double value, const std::string& unit, const std::string& description);
  // A quantity the reader must be told is missing (ResultRow::recorded).
  void add_not_recorded(const std::string& name, const std::string& unit, const std::string& description);
  // A copy of `row` as it is, recorded or not.
  void add_row(const ResultRow& row);
  void append(const ResultTable& other, const std::string& prefix);
  const std::vector<ResultRow>& rows() const { return rows_; }
  const ResultRow* find(const std::string& name) const;  // a recorded row, else nullptr

  void write_csv(const std::string& path) const;
  void write_json(const std::string& path, const std::vector<std::string>& warnings) const;
  std::string markdown() const;
  std::string text() const;  // aligned, for the terminal

 private:
  std::vector<ResultRow> rows_;
};

// A CSV of named numeric columns of equal length.
void write_columns_csv(const std::string& path, const std::vector<std::string>& names,
                       const std::vector<std::vector<double>>& columns);

// Opens `path` for writing or throws a one-line error naming it.
std::ofstream open_output(const std::string& path);

}  // namespace cdpost
