#include "io/ave_chunk.h"

#include <algorithm>

#include "io/ave_time.h"
#include "io/line_source.h"
#include "io/progress.h"
#include "io/tokens.h"

namespace cdpost {

size_t ChunkSeries::column_index(const std::string& name) const
{
  auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end())
    throw InputError(source, 0, "no column '" + name + "' (columns: " + join_names(names) + ")");
  return static_cast<size_t>(found - names.begin());
}

bool ChunkSeries::has(const std::string& name) const
{
  return std::find(names.begin(), names.end(), name) != names.end();
}

namespace {

// Reads the '#' lines; returns the value column names from the "# Chunk ..." line and
// leaves `line` holding the first data line.
std::vector<std::string> read_header(LineSource& source, std::string& line)
{
  std::vector<std::string> names;
  while (source.next(line)) {
    if (is_blank(line)) continue;
    if (!is_comment(line)) break;
    auto comment_names = header_names(line.substr(line.find('#')));
    if (!comment_names.empty() && comment_names.front() == "Chunk")
      names.assign(comment_names.begin() + 1, comment_names.end());
  }
  if (source.line_number() == 0) throw InputError(source.path(), 0, "file is empty");
  if (names.empty()) source.fail("no '# Chunk ...' header line naming the columns");
  return names;
}

void read_block_rows(LineSource& source, ChunkSeries& series, long timestep)
{
  std::string line;
  const size_t width = series.names.size() + 1;
  for (size_t chunk = 0; chunk < series.chunks; ++chunk) {
    if (!source.next(line))
      source.fail("file ends inside the block of timestep " + std::to_string(timestep) + " (" + std::to_string(chunk) +
                  " of " + std::to_string(series.chunks) + " chunk rows)");
    auto tokens = split_whitespace(line);
    if (tokens.size() != width)
      source.fail("expected " + std::to_string(width) + " values (Chunk, " + join_names(series.names) + "), found " +
                  std::to_string(tokens.size()));
    if (parse_integer(tokens[0], source, "Chunk") != static_cast<long>(chunk + 1))
      source.fail("expected chunk " + std::to_string(chunk + 1) + ", found " + quoted_excerpt(tokens[0]));
    for (size_t c = 1; c < width; ++c)
      series.values.push_back(parse_number(tokens[c], source, "column " + series.names[c - 1]));
  }
}

void read_block(LineSource& source, const std::string& line, ChunkSeries& series)
{
  auto tokens = split_whitespace(line);
  if (tokens.size() != 3)
    source.fail("expected a block header 'Timestep Number-of-chunks Total-count', found " +
                std::to_string(tokens.size()) + " values");
  long timestep = parse_integer(tokens[0], source, "Timestep");
  long chunks = parse_integer(tokens[1], source, "Number-of-chunks");
  parse_number(tokens[2], source, "Total-count");
  if (chunks <= 0) source.fail("Number-of-chunks must be positive");
  if (series.blocks() == 0) series.chunks = static_cast<size_t>(chunks);
  if (static_cast<size_t>(chunks) != series.chunks)
    source.fail("number of chunks changed from " + std::to_string(series.chunks) + " to " + std::to_string(chunks) +
                " (fix the bin bounds in the deck)");
  if (series.blocks() > 0 && timestep <= series.timesteps.back())
    source.fail("Timestep " + std::to_string(timestep) + " does not increase");
  series.timesteps.push_back(static_cast<double>(timestep));
  series.block_lines.push_back(source.line_number());
  read_block_rows(source, series, timestep);
}

void check_repeated_header(const LineSource& source, const std::string& line, const ChunkSeries& series)
{
  auto names = header_names(line.substr(line.find('#')));
  if (names.empty() || names.front() != "Chunk") return;
  names.erase(names.begin());
  require_same_columns(source, series.names, names);
}

}  // namespace

ChunkSeries read_ave_chunk(const std::string& path)
{
  LineSource source(path);
  ChunkSeries series;
  series.source = path;
  std::string line;
  series.names = read_header(source, line);
  bool have_line = !is_blank(line) && !is_comment(line);
  if (!have_line) source.fail("no data blocks (only comments)");
  Progress progress("reading " + path, true);
  do {
    progress.update(source.fraction_read());
    if (is_blank(line)) continue;
    if (is_comment(line)) check_repeated_header(source, line, series);
    else read_block(source, line, series);
  } while (source.next(line));
  return series;
}

}  // namespace cdpost
