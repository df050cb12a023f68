// Reading the values of fix contact/dynamics's keywords: each whole value or an error naming
// the keyword (fix_contact_dynamics_keywords.h).
#include "fix_contact_dynamics_keywords.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "error.h"
#include "utils.h"

namespace LAMMPS_NS::fix_keywords {

// The whole of `text` as a finite number; anything else (trailing characters, overflow,
// underflow) is refused naming the keyword.
double number_for(const char* keyword, const char* text, Error* error)
{
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !utils::is_double(text))
    error->all(FLERR, "Fix contact/dynamics: {} expects a number, got '{}'", keyword, text);
  if (errno == ERANGE || !std::isfinite(value))
    error->all(FLERR, "Fix contact/dynamics: {} '{}' is outside the range of a double", keyword, text);
  return value;
}

// The whole of `text` as an int.
int integer_for(const char* keyword, const char* text, Error* error)
{
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || !utils::is_integer(text))
    error->all(FLERR, "Fix contact/dynamics: {} expects an integer, got '{}'", keyword, text);
  if (errno == ERANGE || value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    error->all(FLERR, "Fix contact/dynamics: {} must fit an int, got '{}'", keyword, text);
  return static_cast<int>(value);
}

// An atom type or a range of them, as LAMMPS writes it (N, *, *N, N*, M*N), within 1..ntypes.
std::pair<int, int> type_range_for(const char* keyword, const std::string& text, int ntypes, Error* error)
{
  const std::size_t star = text.find('*');
  auto bound = [&](const std::string& part, int open_end) {
    return part.empty() ? open_end : integer_for(keyword, part.c_str(), error);
  };
  int low, high;
  if (star == std::string::npos) {
    low = high = integer_for(keyword, text.c_str(), error);
  } else {
    low = bound(text.substr(0, star), 1);
    high = bound(text.substr(star + 1), ntypes);
  }
  if (low < 1 || high > ntypes || low > high)
    error->all(FLERR, "Fix contact/dynamics: {} type '{}' is not a type or range of types within 1-{}", keyword, text,
               ntypes);
  return {low, high};
}

void require_values(const char* keyword, int iarg, int count, int narg, Error* error, const char* names)
{
  if (iarg + count < narg) return;
  const char* plural = count == 1 ? "" : "s";
  if (names) error->all(FLERR, "Fix contact/dynamics: {} needs {} value{}: {}", keyword, count, plural, names);
  error->all(FLERR, "Fix contact/dynamics: {} needs {} value{}", keyword, count, plural);
}

bool yes_or_no(const char* keyword, const std::string& value, Error* error)
{
  if (value != "yes" && value != "no")
    error->all(FLERR, "Fix contact/dynamics: {} must be yes or no, got '{}'", keyword, value);
  return value == "yes";
}

void check_friction(const char* keyword, double mu, Error* error)
{
  if (mu < 0.0) error->all(FLERR, "Fix contact/dynamics: {} must be >= 0, got {}", keyword, mu);
}

void check_restitution(const char* keyword, double e, Error* error)
{
  if (e < 0.0 || e > 1.0) error->all(FLERR, "Fix contact/dynamics: {} must be in [0,1], got {}", keyword, e);
}

}  // namespace LAMMPS_NS::fix_keywords
