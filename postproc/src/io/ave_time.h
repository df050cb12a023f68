// Reader for LAMMPS `fix ave/time` output in scalar mode: '#' comment lines, the last of
// which before the data names the columns ("# TimeStep v_u v_v"), then one row per output.
#pragma once

#include <string>
#include <vector>

namespace cdpost {

// Named columns of numbers read from one file; every row keeps its line number so that
// later checks (e.g. irregular sampling) can still point at the file and line.
struct ColumnTable {
  std::string source;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[c][row]
  std::vector<long> row_lines;

  size_t rows() const { return row_lines.size(); }
  bool has(const std::string& name) const;
  // The column called `name`; fails naming the file and the available columns if absent.
  const std::vector<double>& column(const std::string& name) const;
};

ColumnTable read_ave_time(const std::string& path);

// The names in a '#' comment line ("# TimeStep v_u" gives TimeStep, v_u).
std::vector<std::string> header_names(const std::string& comment_line);

// "a, b, c" for messages.
std::string join_names(const std::vector<std::string>& names);

}  // namespace cdpost
