#include "spatial_to_chunk.h"

#include <fstream>
#include <sstream>

#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/tokens.h"
#include "output/results.h"

namespace cdref {

namespace {

struct Header {
  std::string title;               // "# Spatial-averaged data for fix ... and group ..."
  std::vector<std::string> names;  // value columns after "Bin"
};

// Reads the comment lines; leaves `line` holding the first data line and sets `data` if
// there is one.
Header read_header(cdpost::LineSource& source, std::string& line, bool& data)
{
  Header header;
  data = false;
  while (source.next(line)) {
    if (cdpost::is_blank(line)) continue;
    if (!cdpost::is_comment(line)) {
      data = true;
      break;
    }
    const std::string comment = line.substr(line.find('#'));
    auto names = cdpost::header_names(comment);
    if (!names.empty() && names.front() == "Bin") header.names.assign(names.begin() + 1, names.end());
    else if (header.title.empty()) header.title = comment;
  }
  if (source.line_number() == 0) throw cdpost::InputError(source.path(), 0, "file is empty");
  if (header.names.empty()) source.fail("no '# Bin ...' header line naming the columns (not a fix ave/spatial file?)");
  if (header.names.size() < 3 || header.names[0] != "Coord" || header.names[1] != "Ncount")
    source.fail("expected the columns 'Bin Coord Ncount ...' of a 1D fix ave/spatial, found '" +
                cdpost::join_names(header.names) + "'");
  return header;
}

}  // namespace

SpatialConversion spatial_to_chunk(const std::string& input, const std::string& output)
{
  cdpost::LineSource source(input);
  std::string line;
  bool have_line = false;
  const Header header = read_header(source, line, have_line);
  const size_t width = header.names.size() + 1;  // Bin + values

  std::ostringstream out;
  out << "# Chunk-averaged data converted by cdref from fix ave/spatial: "
      << (header.title.empty() ? std::string("# (no title)") : header.title).substr(2) << "\n";
  out << "# Timestep Number-of-chunks Total-count\n# Chunk Coord1";
  for (size_t c = 1; c < header.names.size(); ++c) out << ' ' << header.names[c];
  out << '\n';

  SpatialConversion result;
  std::vector<std::string> rows;
  for (; have_line; have_line = source.next(line)) {
    if (cdpost::is_blank(line) || cdpost::is_comment(line)) continue;
    auto block = cdpost::split_whitespace(line);
    if (block.size() != 2)
      source.fail("expected a block line 'Timestep Number-of-bins', found " + std::to_string(block.size()) + " values");
    const long timestep = cdpost::parse_integer(block[0], source, "Timestep");
    const long bins = cdpost::parse_integer(block[1], source, "Number-of-bins");
    if (bins <= 0) source.fail("Number-of-bins must be positive");
    if (result.blocks > 0 && bins != result.bins)
      source.fail("the number of bins changed from " + std::to_string(result.bins) + " to " + std::to_string(bins) +
                  " (the box changed size; cdpost needs fixed bins)");
    result.bins = bins;
    rows.clear();
    double total = 0;
    for (long bin = 1; bin <= bins; ++bin) {
      if (!source.next(line))
        source.fail("file ends inside the block of timestep " + std::to_string(timestep) + " (" +
                    std::to_string(bin - 1) + " of " + std::to_string(bins) + " bin rows)");
      auto tokens = cdpost::split_whitespace(line);
      if (tokens.size() != width)
        source.fail("expected " + std::to_string(width) + " values (Bin, " + cdpost::join_names(header.names) +
                    "), found " + std::to_string(tokens.size()));
      if (cdpost::parse_integer(tokens[0], source, "Bin") != bin)
        source.fail("expected bin " + std::to_string(bin) + ", found '" + std::string(tokens[0]) + "'");
      std::string row = "  " + std::to_string(bin);
      for (size_t c = 1; c < width; ++c) {
        const double value = cdpost::parse_number(tokens[c], source, "column " + header.names[c - 1]);
        if (c == 2) total += value;
        row += ' ';
        row += tokens[c];
      }
      rows.push_back(row);
    }
    char total_text[32];
    std::snprintf(total_text, sizeof total_text, "%.10g", total);
    out << timestep << ' ' << bins << ' ' << total_text << '\n';
    for (const auto& row : rows) out << row << '\n';
    ++result.blocks;
  }
  if (result.blocks == 0) source.fail("no data block");
  cdpost::open_output(output) << out.str();
  return result;
}

}  // namespace cdref
