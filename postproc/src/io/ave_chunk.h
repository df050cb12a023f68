// Reader for LAMMPS `fix ave/chunk` output: a '#' header whose last line names the columns
// ("# Chunk Coord1 Ncount vx"), then per output a line "Timestep Number-of-chunks
// Total-count" followed by one row per chunk.
#pragma once

#include <string>
#include <vector>

namespace cdpost {

struct ChunkSeries {
  std::string source;
  std::vector<std::string> names;  // the value columns, without the leading "Chunk"
  size_t chunks = 0;               // the same in every block
  std::vector<double> timesteps;
  std::vector<long> block_lines;  // line of each block's "Timestep ..." line
  std::vector<double> values;     // values[(block * chunks + chunk) * names.size() + column]

  size_t blocks() const { return timesteps.size(); }
  // Index of the column called `name`; fails naming the file and the available columns.
  size_t column_index(const std::string& name) const;
  bool has(const std::string& name) const;
  double value(size_t block, size_t chunk, size_t column) const
  {
    return values[(block * chunks + chunk) * names.size() + column];
  }
};

ChunkSeries read_ave_chunk(const std::string& path);

}  // namespace cdpost
