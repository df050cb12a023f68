// Reading the values of fix contact/dynamics's keywords: each takes the whole text or stops
// the run with one error line naming the keyword (LAMMPS's Error::all).
#pragma once

#include <string>
#include <utility>

namespace LAMMPS_NS {
class Error;

namespace fix_keywords {

// The whole of `text` as a finite double.
double number_for(const char* keyword, const char* text, Error* error);
// The whole of `text` as an int.
int integer_for(const char* keyword, const char* text, Error* error);
// An atom type or a range of them, as LAMMPS writes it (N, *, *N, N*, M*N), within 1..ntypes.
std::pair<int, int> type_range_for(const char* keyword, const std::string& text, int ntypes, Error* error);
// Stops unless `count` values follow the keyword at iarg, naming them if `names` says what they
// are ("wall yplane needs 3 values: position mu e").
void require_values(const char* keyword, int iarg, int count, int narg, Error* error, const char* names = nullptr);
bool yes_or_no(const char* keyword, const std::string& value, Error* error);
void check_friction(const char* keyword, double mu, Error* error);    // mu >= 0
void check_restitution(const char* keyword, double e, Error* error);  // 0 <= e <= 1

}  // namespace fix_keywords
}  // namespace LAMMPS_NS
