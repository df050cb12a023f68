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
bool is_blank(std::string_view line);
// `text` in quotes for an error message, cut to its first 40 characters and "..." if longer.
std::string quoted_excerpt(std::string_view text);
bool is_comment(std::string_view line);  // first non-blank character is '#'

// A repeated column header (LAMMPS writes one again when a restarted run appends) must
// name the same columns as the first.
void require_same_columns(const LineSource& source, const std::vector<std::string>& first,
                          const std::vector<std::string>& repeated);

double parse_number(std::string_view token, const LineSource& source, const std::string& what);
long parse_integer(std::string_view token, const LineSource& source, const std::string& what);

}  // namespace cdpost
