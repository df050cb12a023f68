#include "io/tokens.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "io/line_source.h"

namespace cdpost {

std::vector<std::string_view> split_whitespace(std::string_view line)
{
  std::vector<std::string_view> tokens;
  size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && std::isspace(static_cast<unsigned char>(line[pos]))) ++pos;
    size_t end = pos;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end]))) ++end;
    if (end > pos) tokens.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return tokens;
}

bool is_blank(std::string_view line)
{
  return line.find_first_not_of(" \t") == std::string_view::npos;
}

std::string quoted_excerpt(std::string_view text)
{
  constexpr size_t kShown = 40;
  return "'" + std::string(text.substr(0, kShown)) + (text.size() > kShown ? "...'" : "'");
}

bool is_comment(std::string_view line)
{
  auto first = line.find_first_not_of(" \t");
  return first != std::string_view::npos && line[first] == '#';
}

void require_same_columns(const LineSource& source, const std::vector<std::string>& first,
                          const std::vector<std::string>& repeated)
{
  auto joined = [](const std::vector<std::string>& names) {
    std::string text;
    for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
  };
  if (repeated != first)
    source.fail("column header changed from (" + joined(first) + ") to (" + joined(repeated) + ")");
}

double parse_number(std::string_view token, const LineSource& source, const std::string& what)
{
  double value = 0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (!token.empty() && *first == '+') ++first;
  auto [end, error] = std::from_chars(first, last, value);
  if (error != std::errc() || end != last || token.empty())
    source.fail("bad number " + quoted_excerpt(token) + " for " + what);
  if (!std::isfinite(value)) source.fail("non-finite value " + quoted_excerpt(token) + " for " + what);
  return value;
}

long parse_integer(std::string_view token, const LineSource& source, const std::string& what)
{
  long value = 0;
  auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || token.empty())
    source.fail("bad integer " + quoted_excerpt(token) + " for " + what);
  return value;
}

}  // namespace cdpost
