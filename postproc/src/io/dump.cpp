#include "io/dump.h"

#include <algorithm>

#include "io/ave_time.h"
#include "io/tokens.h"

namespace cdpost {

namespace {
bool starts_with(const std::string& text, const std::string& prefix)
{
  return text.compare(0, prefix.size(), prefix) == 0;
}
const std::string item_prefix = "ITEM: ";
}  // namespace

std::array<bool, 2> periodic_xy(const DumpFrame& frame, const std::optional<std::array<bool, 2>>& given)
{
  if (given) return *given;
  if (!frame.periodic)
    throw InputError(frame.source, frame.line,
                     "the 'ITEM: BOX BOUNDS' line names no boundary flags: give --periodic x, y, xy or none");
  return {(*frame.periodic)[0], (*frame.periodic)[1]};
}

double mean_diameter(const DumpFrame& frame, size_t radius)
{
  if (frame.atoms == 0)
    throw InputError(frame.source, frame.line, "no grain in the frame to take the mean diameter from: give --d");
  double sum = 0;
  for (size_t atom = 0; atom < frame.atoms; ++atom) sum += 2 * frame.value(atom, radius);
  if (!(sum > 0)) throw InputError(frame.source, frame.line, "the radius column's mean is not positive: give --d");
  return sum / double(frame.atoms);
}

DumpReader::DumpReader(const std::string& path) : source_(path) {}

std::string DumpReader::require_line(const std::string& what)
{
  std::string line;
  if (!source_.next(line)) source_.fail("file ends where " + what + " was expected (truncated dump?)");
  return line;
}

size_t DumpFrame::column_index(const std::string& name) const
{
  auto found = std::find(columns.begin(), columns.end(), name);
  if (found == columns.end())
    throw InputError(source, line, "no per-atom column '" + name + "' (columns: " + join_names(columns) + ")");
  return static_cast<size_t>(found - columns.begin());
}

void DumpReader::read_box(DumpFrame& frame, const std::string& flags)
{
  auto named = split_whitespace(flags);  // "xy xz yz" first in a triclinic box
  const bool triclinic = !named.empty() && named[0] == "xy";
  if (triclinic) named.erase(named.begin(), named.begin() + std::min<size_t>(3, named.size()));
  frame.periodic.reset();
  if (!named.empty()) {
    const auto boundary_flag = [](std::string_view t) {
      return t.size() == 2 && t.find_first_not_of("pfsm") == std::string_view::npos;
    };
    if (named.size() != 3 || !std::all_of(named.begin(), named.end(), boundary_flag))
      source_.fail("expected three boundary flags (e.g. 'pp fm pp') after 'ITEM: BOX BOUNDS', found " +
                   quoted_excerpt(flags));
    frame.periodic = std::array<bool, 3>{named[0] == "pp", named[1] == "pp", named[2] == "pp"};
  }
  double* bounds[2][2] = {{&frame.xlo, &frame.xhi}, {&frame.ylo, &frame.yhi}};
  double tilt[3] = {0, 0, 0};  // xy, xz, yz
  for (int dim = 0; dim < 3; ++dim) {
    auto line = require_line("a box bounds line");
    auto tokens = split_whitespace(line);
    if (tokens.size() < 2) source_.fail("expected 'low high' box bounds");
    double low = parse_number(tokens[0], source_, "box low bound");
    double high = parse_number(tokens[1], source_, "box high bound");
    if (high <= low) source_.fail("box high bound not above the low bound");
    if (triclinic && tokens.size() > 2) tilt[dim] = parse_number(tokens[2], source_, "box tilt");
    if (dim < 2) {
      *bounds[dim][0] = low;
      *bounds[dim][1] = high;
    }
  }
  // A triclinic box's bounds hold its tilted cell (LAMMPS's Howto triclinic): back to the cell's own.
  frame.xy = tilt[0];
  frame.xlo -= std::min({0.0, tilt[0], tilt[1], tilt[0] + tilt[1]});
  frame.xhi -= std::max({0.0, tilt[0], tilt[1], tilt[0] + tilt[1]});
  frame.ylo -= std::min(0.0, tilt[2]);
  frame.yhi -= std::max(0.0, tilt[2]);
}

void DumpReader::read_atoms(DumpFrame& frame, const std::string& names)
{
  frame.columns.clear();
  for (auto token : split_whitespace(names)) frame.columns.emplace_back(token);
  if (frame.columns.empty()) source_.fail("'ITEM: ATOMS' names no columns");
  frame.values.clear();
  frame.values.reserve(frame.atoms * frame.columns.size());
  for (size_t atom = 0; atom < frame.atoms; ++atom) {
    auto line = require_line("atom " + std::to_string(atom + 1) + " of " + std::to_string(frame.atoms));
    auto tokens = split_whitespace(line);
    if (tokens.size() != frame.columns.size())
      source_.fail("expected " + std::to_string(frame.columns.size()) + " values (" + join_names(frame.columns) +
                   "), found " + std::to_string(tokens.size()));
    for (size_t c = 0; c < tokens.size(); ++c)
      frame.values.push_back(parse_number(tokens[c], source_, frame.columns[c]));
  }
}

bool DumpReader::next(DumpFrame& frame)
{
  std::string line;
  do {
    if (!source_.next(line)) return false;
  } while (line.find_first_not_of(" \t") == std::string::npos);
  if (line != item_prefix + "TIMESTEP") source_.fail("expected 'ITEM: TIMESTEP', found " + quoted_excerpt(line));
  frame.line = source_.line_number();
  frame.source = source_.path();
  auto step_line = require_line("the timestep");
  auto step = split_whitespace(step_line);
  if (step.size() != 1) source_.fail("expected one timestep value");
  frame.timestep = parse_integer(step[0], source_, "timestep");
  frame.time.reset();
  bool have_atom_count = false, have_box = false;
  while (true) {
    line = require_line("an 'ITEM:' line");
    if (!starts_with(line, item_prefix)) source_.fail("expected an 'ITEM:' line, found " + quoted_excerpt(line));
    std::string item = line.substr(item_prefix.size());
    if (starts_with(item, "NUMBER OF ATOMS") || starts_with(item, "NUMBER OF ENTRIES")) {
      auto count_line = require_line("the number of atoms");
      auto count = split_whitespace(count_line);
      if (count.size() != 1) source_.fail("expected one atom count");
      long atoms = parse_integer(count[0], source_, "number of atoms");
      if (atoms < 0) source_.fail("negative number of atoms");
      frame.atoms = static_cast<size_t>(atoms);
      have_atom_count = true;
    } else if (starts_with(item, "BOX BOUNDS")) {
      read_box(frame, item.substr(std::string("BOX BOUNDS").size()));
      have_box = true;
    } else if (item == "TIME") {
      auto time_line = require_line("the time");
      auto time = split_whitespace(time_line);
      if (time.size() != 1) source_.fail("expected one time value");
      frame.time = parse_number(time[0], source_, "time");
    } else if (starts_with(item, "UNITS") || starts_with(item, "TIME")) {
      require_line(item);
    } else if (starts_with(item, "ATOMS") || starts_with(item, "ENTRIES")) {
      const size_t names = std::min(item.find(' '), item.size());  // after "ATOMS" or "ENTRIES"
      if (!have_atom_count || !have_box) source_.fail("'ITEM: " + item.substr(0, names) + "' before the count and box");
      read_atoms(frame, item.substr(names));
      return true;
    } else {
      source_.fail("unknown dump item " + quoted_excerpt(item));
    }
  }
}

}  // namespace cdpost
