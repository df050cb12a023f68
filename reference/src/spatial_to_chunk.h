// LIGGGHTS 3.8 has no compute chunk/atom / fix ave/chunk, only the older fix ave/spatial.
// Its output differs from ave/chunk's in the header names ("# Bin Coord Ncount ..." for
// "# Chunk Coord1 Ncount ...") and in the block lines ("Timestep Number-of-bins" without the
// total count). The conversion makes the profile.chunk / layers.chunk that cdpost reads.
#pragma once

#include <string>

namespace cdref {

struct SpatialConversion {
  long blocks = 0;
  long bins = 0;
};

// Converts the 1D fix ave/spatial file `input` into fix ave/chunk format in `output`.
// Strict: every block must hold the announced bins numbered 1..N with the header's columns,
// and N must not change (cdpost needs fixed bins); errors name the file and line.
SpatialConversion spatial_to_chunk(const std::string& input, const std::string& output);

}  // namespace cdref
