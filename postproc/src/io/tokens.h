// Splitting lines into whitespace-separated tokens and reading numbers from them strictly.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cdpost {

class LineSource;

// The tokens view `line`, which must outlive them (hence no temporaries).
std::vector<std::string_view> split_whitespace(std::string_view line);
std::vector<std::string_view> split_whitespace(std::string&& line) = delete;

// The finite number written in `token`; anything else (garbage, "nan", "inf", trailing
// characters) fails with the source's file and line and `what` names the quantity.
double parse_number(std::string_view token, const LineSource& source, const std::string& what);
long parse_integer(std::string_view token, const LineSource& source, const std::string& what);

}  // namespace cdpost
