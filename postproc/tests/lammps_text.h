// Writers of small LAMMPS-format texts (fix ave/time, fix ave/chunk, dump custom) for tests.
#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace cdpost::testing {

// "# Time-averaged data ..." header, the column names, one line per row.
inline std::string ave_time_text(const std::vector<std::string>& names, const std::vector<std::vector<double>>& rows)
{
  std::ostringstream out;
  out.precision(10);
  out << "# Time-averaged data for fix flow\n#";
  for (const auto& name : names) out << ' ' << name;
  out << '\n';
  for (const auto& row : rows) {
    for (size_t c = 0; c < row.size(); ++c) out << (c ? " " : "") << row[c];
    out << '\n';
  }
  return out.str();
}

// value(block, chunk, column) gives the value columns after "Chunk".
inline std::string ave_chunk_text(const std::vector<std::string>& names, const std::vector<long>& timesteps,
                                  size_t chunks, const std::function<double(size_t, size_t, size_t)>& value)
{
  std::ostringstream out;
  out.precision(10);
  out << "# Chunk-averaged data for fix profile and group all\n"
      << "# Timestep Number-of-chunks Total-count\n# Chunk";
  for (const auto& name : names) out << ' ' << name;
  out << '\n';
  for (size_t b = 0; b < timesteps.size(); ++b) {
    out << timesteps[b] << ' ' << chunks << ' ' << 100 << '\n';
    for (size_t c = 0; c < chunks; ++c) {
      out << "  " << c + 1;
      for (size_t k = 0; k < names.size(); ++k) out << ' ' << value(b, c, k);
      out << '\n';
    }
  }
  return out.str();
}

struct DumpAtom {
  long id;
  double x, y, vx, vy, radius;
  long type = 1;
};

// boundary: the flags of the "ITEM: BOX BOUNDS" line (x y z), as LAMMPS writes them.
inline std::string dump_frame_text(long timestep, double lx, double ly, const std::vector<DumpAtom>& atoms,
                                   const std::string& boundary = "pp ff pp")
{
  std::ostringstream out;
  out.precision(10);
  out << "ITEM: TIMESTEP\n"
      << timestep << "\nITEM: NUMBER OF ATOMS\n"
      << atoms.size() << "\nITEM: BOX BOUNDS " << boundary << "\n0 " << lx << "\n0 " << ly << "\n-0.5 0.5\n"
      << "ITEM: ATOMS id type x y vx vy radius\n";
  for (const auto& a : atoms)
    out << a.id << ' ' << a.type << ' ' << a.x << ' ' << a.y << ' ' << a.vx << ' ' << a.vy << ' ' << a.radius << '\n';
  return out.str();
}

}  // namespace cdpost::testing
