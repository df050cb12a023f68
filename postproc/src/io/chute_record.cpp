#include "io/chute_record.h"

#include <filesystem>

#include "io/line_source.h"
#include "io/tokens.h"

namespace cdpost {

std::optional<double> ChuteRecord::find(const std::string& name) const
{
  auto found = values.find(name);
  if (found == values.end()) return std::nullopt;
  return found->second;
}

std::optional<ChuteRecord> read_chute_record(const std::string& directory)
{
  const auto path = (std::filesystem::path(directory) / kChuteRecordFile).string();
  if (!std::filesystem::exists(path)) return std::nullopt;
  ChuteRecord record;
  record.source = path;
  LineSource source(path);
  std::string line;
  while (source.next(line)) {
    if (is_blank(line) || is_comment(line)) continue;
    const auto tokens = split_whitespace(line);
    if (tokens.size() != 2)
      source.fail("expected a name and a value, found " + std::to_string(tokens.size()) + " fields");
    const std::string name(tokens[0]);
    if (record.values.count(name)) source.fail("'" + name + "' is given twice");
    record.values[name] = parse_number(tokens[1], source, name);
  }
  return record;
}

}  // namespace cdpost
