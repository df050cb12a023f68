#include "io/ave_time.h"

#include <algorithm>

#include "io/line_source.h"
#include "io/progress.h"
#include "io/tokens.h"

namespace cdpost {

bool ColumnTable::has(const std::string& name) const
{
  return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<double>& ColumnTable::column(const std::string& name) const
{
  auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end())
    throw InputError(source, 0, "no column '" + name + "' (columns: " + join_names(names) + ")");
  return columns[static_cast<size_t>(found - names.begin())];
}

std::vector<std::string> header_names(const std::string& comment_line)
{
  std::vector<std::string> names;
  for (auto token : split_whitespace(std::string_view(comment_line).substr(1))) names.emplace_back(token);
  return names;
}

std::string join_names(const std::vector<std::string>& names)
{
  std::string joined;
  for (const auto& name : names) joined += (joined.empty() ? "" : ", ") + name;
  return joined;
}

namespace {

void append_row(ColumnTable& table, const std::string& line, const LineSource& source)
{
  auto tokens = split_whitespace(line);
  if (tokens.size() != table.names.size())
    source.fail("expected " + std::to_string(table.names.size()) + " values (" + join_names(table.names) + "), found " +
                std::to_string(tokens.size()));
  for (size_t c = 0; c < tokens.size(); ++c)
    table.columns[c].push_back(parse_number(tokens[c], source, "column " + table.names[c]));
  table.row_lines.push_back(source.line_number());
}

void accept_header(ColumnTable& table, const std::vector<std::string>& names, const LineSource& source)
{
  if (table.names.empty()) {
    table.names = names;
    table.columns.assign(names.size(), {});
  } else {
    require_same_columns(source, table.names, names);
  }
}

void check_timesteps_increase(const ColumnTable& table)
{
  if (!table.has("TimeStep")) return;
  const auto& steps = table.column("TimeStep");
  for (size_t row = 1; row < steps.size(); ++row)
    if (steps[row] <= steps[row - 1])
      throw InputError(table.source, table.row_lines[row],
                       "TimeStep " + std::to_string(static_cast<long>(steps[row])) +
                           " does not increase (overlapping restart output?)");
}

}  // namespace

ColumnTable read_ave_time(const std::string& path)
{
  LineSource source(path);
  ColumnTable table;
  table.source = path;
  std::string line;
  std::vector<std::string> last_comment_names;
  bool expecting_header = true;
  Progress progress("reading " + path, true);
  while (source.next(line)) {
    if (source.line_number() % 4096 == 0) progress.update(source.fraction_read());
    if (is_blank(line)) continue;
    if (is_comment(line)) {
      last_comment_names = header_names(line.substr(line.find('#')));
      expecting_header = true;
      continue;
    }
    if (expecting_header) {
      if (last_comment_names.empty()) source.fail("data before any '#' header line naming the columns");
      accept_header(table, last_comment_names, source);
      expecting_header = false;
    }
    append_row(table, line, source);
  }
  if (source.line_number() == 0) throw InputError(path, 0, "file is empty");
  if (table.rows() == 0) source.fail("no data rows (only comments)");
  check_timesteps_increase(table);
  return table;
}

}  // namespace cdpost
