#include "io/tokens.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "io/line_source.h"

namespace cdpost {

std::vector<std::string_view> split_whitespace(std::string_view line) {
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

double parse_number(std::string_view token, const LineSource& source, const std::string& what) {
  double value = 0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (!token.empty() && *first == '+') ++first;
  auto [end, error] = std::from_chars(first, last, value);
  if (error != std::errc() || end != last || token.empty())
    source.fail("bad number '" + std::string(token) + "' for " + what);
  if (!std::isfinite(value))
    source.fail("non-finite value '" + std::string(token) + "' for " + what);
  return value;
}

long parse_integer(std::string_view token, const LineSource& source, const std::string& what) {
  long value = 0;
  auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || token.empty())
    source.fail("bad integer '" + std::string(token) + "' for " + what);
  return value;
}

}  // namespace cdpost
