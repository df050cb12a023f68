// Streaming reader for LAMMPS `dump custom` and `dump local` text files (plain or gzip): one
// frame in memory at a time, so dumps larger than memory can be scanned. A local dump's entries
// are read as its frame's rows ("atoms").
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
  std::optional<double> time;                 // "ITEM: TIME" (dump_modify time yes), input time units
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;  // box bounds, input length units
  double xy = 0;  // a triclinic box's tilt (x shift of the image across y); xlo..xhi is its cell's
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

// The periodicity of x and y: `given` (a command's --periodic), else the frame's box flags;
// InputError naming the frame when neither says.
std::array<bool, 2> periodic_xy(const DumpFrame& frame, const std::optional<std::array<bool, 2>>& given);

// The mean of the frame's diameters from its radius column, input length units; InputError
// (pointing to --d) when the frame has no grain or the mean is not positive.
double mean_diameter(const DumpFrame& frame, size_t radius);

class DumpReader {
 public:
  explicit DumpReader(const std::string& path);
  // Reads the next frame into `frame`; false at the end of the file.
  bool next(DumpFrame& frame);
  const LineSource& source() const { return source_; }

 private:
  std::string require_line(const std::string& what);
  void read_box(DumpFrame& frame, const std::string& flags);
  void read_atoms(DumpFrame& frame, const std::string& names);  // the item line after ATOMS/ENTRIES
  LineSource source_;
};

}  // namespace cdpost
