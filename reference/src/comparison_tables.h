// The comparison as text: its table (CSV and Markdown), the long CSV files of every spectrum and
// profile, and the small formatting helpers the figures and the report share.
#pragma once

#include <optional>
#include <string>

#include "comparison.h"

namespace cdref {

// A number as the report writes it: cdpost::format_estimate without an error.
std::string short_number(double x);
// A run.info code as tables and figures name it ("LAMMPS GRANULAR", "LIGGGHTS", "lmp_cd").
std::string code_name(const std::string& code);
// cdpost's result of that name for the run, if it has one.
std::optional<double> result_value(const ComparedRun& r, const std::string& name);
std::optional<double> result_error(const ComparedRun& r, const std::string& name);

// OUT/table.csv: one row per run, every column of the table with its error.
void write_table_csv(const Comparison& c, const std::string& path);
// The same table in Markdown, for the report.
std::string markdown_table(const Comparison& c);
// OUT/spectra.csv and OUT/profiles.csv: every run's spectrum and velocity profile, one row per point.
void write_long_csvs(const Comparison& c, const std::string& out);

}  // namespace cdref
