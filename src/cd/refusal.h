// The one-line refusal of a setting, as the fix's error lines write it:
// "<keyword> must be <range>, got <value>".
#pragma once

#include <charconv>
#include <string>

namespace cd {

// A number as the fix's error lines write it: the shortest text that reads back the same.
inline std::string text_of(double value)
{
  char text[32];
  const auto written = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, written.ptr);
}

inline std::string refusal(const char* keyword, const char* range, double value)
{
  return std::string(keyword) + " must be " + range + ", got " + text_of(value);
}

}  // namespace cd
