// Streaming reader for LAMMPS `dump custom` text files (plain or gzip): one frame in memory
// at a time, so dumps larger than memory can be scanned.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/line_source.h"

namespace cdpost {

struct DumpFrame {
  long timestep = 0;
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;  // box bounds, input length units
  // Whether x, y, z are periodic, from the flags of "ITEM: BOX BOUNDS" ("pp fm pp": x and z);
  // nothing when the line has no flags (dumps of LAMMPS before 2010).
  std::optional<std::array<bool, 3>> periodic;
  std::vector<std::string> columns;  // as named on the "ITEM: ATOMS" line
  size_t atoms = 0;
  std::vector<double> values;  // values[atom * columns.size() + column]
  std::string source;          // the dump file
  long line = 0;               // line of the frame's "ITEM: TIMESTEP"

  double value(size_t atom, size_t column) const { return values[atom * columns.size() + column]; }
  // Index of column `name`; fails naming the file, the frame's line and the columns.
  size_t column_index(const std::string& name) const;
};

class DumpReader {
 public:
  explicit DumpReader(const std::string& path);
  // Reads the next frame into `frame`; false at the end of the file.
  bool next(DumpFrame& frame);
  const LineSource& source() const { return source_; }

 private:
  std::string require_line(const std::string& what);
  void read_box(DumpFrame& frame, const std::string& flags);
  void read_atoms(DumpFrame& frame, const std::string& item);
  LineSource source_;
};

}  // namespace cdpost
