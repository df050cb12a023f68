// The solver's keywords (cd/solver_keywords.h).
#include "cd/solver_keywords.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace cd {

namespace {

bool is_digit(char c)
{
  return c >= '0' && c <= '9';
}

// Digits from `at`; returns where they end.
std::size_t digits_from(const std::string& text, std::size_t at)
{
  while (at < text.size() && is_digit(text[at])) ++at;
  return at;
}

// [+-] digits, as LAMMPS's utils::is_integer.
bool looks_integer(const std::string& text)
{
  const std::size_t start = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
  return digits_from(text, start) == text.size() && text.size() > start;
}

// [+-] digits [. digits] [e [+-] digits], with a digit before or after the point, as LAMMPS's
// utils::is_double.
bool looks_number(const std::string& text)
{
  std::size_t at = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
  const std::size_t integer_end = digits_from(text, at);
  bool any_digit = integer_end > at;
  at = integer_end;
  if (at < text.size() && text[at] == '.') {
    const std::size_t fraction_end = digits_from(text, at + 1);
    any_digit = any_digit || fraction_end > at + 1;
    at = fraction_end;
  }
  if (!any_digit) return false;
  if (at < text.size() && (text[at] == 'e' || text[at] == 'E')) {
    ++at;
    if (at < text.size() && (text[at] == '+' || text[at] == '-')) ++at;
    const std::size_t exponent_end = digits_from(text, at);
    if (exponent_end == at) return false;
    at = exponent_end;
  }
  return at == text.size();
}

// A value's reading: empty once `out` holds it, else the line naming the keyword.
std::string read_number(const std::string& keyword, const std::string& text, double& out)
{
  if (!looks_number(text)) return keyword + " expects a number, got '" + text + "'";
  errno = 0;
  out = std::strtod(text.c_str(), nullptr);
  if (errno == ERANGE || !std::isfinite(out)) return keyword + " '" + text + "' is outside the range of a double";
  return {};
}

std::string read_integer(const std::string& keyword, const std::string& text, int& out)
{
  if (!looks_integer(text)) return keyword + " expects an integer, got '" + text + "'";
  errno = 0;
  const long value = std::strtol(text.c_str(), nullptr, 10);
  if (errno == ERANGE || value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    return keyword + " must fit an int, got '" + text + "'";
  out = static_cast<int>(value);
  return {};
}

// One of two words: `first` sets `out` to a, `second` to b.
template <class Choice>
std::string read_choice(const std::string& keyword, const std::string& text, const char* first, Choice a,
                        const char* second, Choice b, Choice& out)
{
  if (text == first) out = a;
  else if (text == second) out = b;
  else return keyword + " must be " + first + " or " + second + ", got '" + text + "'";
  return {};
}

}  // namespace

std::optional<std::string> read_solver_keyword(SolverSettings& settings, const std::string& keyword,
                                               const std::string& value)
{
  GaussSeidelSettings& gs = settings.gauss_seidel;
  if (keyword == "solver") {
    settings.method = value;
    return std::string{};
  }
  if (keyword == "tolerance") return read_number(keyword, value, settings.tolerance);
  if (keyword == "max_iterations") return read_integer(keyword, value, settings.max_iterations);
  if (keyword == "norm")
    return read_choice(keyword, value, "quadratic", ConvergenceNorm::quadratic, "maximum", ConvergenceNorm::maximum,
                       settings.norm);
  if (keyword == "relaxation") return read_number(keyword, value, gs.relaxation);
  if (keyword == "over_relaxation") return read_number(keyword, value, gs.over_relaxation);
  if (keyword == "acceleration")
    return read_choice(keyword, value, "none", Acceleration::none, "conjugate", Acceleration::conjugate,
                       gs.acceleration);
  if (keyword == "full_sweep_every") return read_integer(keyword, value, gs.full_sweep_every);
  if (keyword == "stall_window") return read_integer(keyword, value, gs.stall_window);
  if (keyword == "stall_coherence") return read_number(keyword, value, gs.stall_coherence);
  if (keyword == "stall_relaxation") return read_number(keyword, value, gs.stall_relaxation);
  if (keyword == "stall_block") return read_integer(keyword, value, gs.stall_block);
  if (keyword == "stall_block_every") return read_integer(keyword, value, gs.stall_block_every);
  if (keyword == "newton_polish") return read_choice(keyword, value, "no", false, "yes", true, gs.newton_polish);
  return std::nullopt;
}

}  // namespace cd
