// A step's contact problem in the field's form: the local problem u = W r + q with Coulomb's law
// per contact (Siconos and FCLIB's convention: per contact [normal, tangent]), built from a saved
// problem of the core (cd/problem_file.h), and written to or read from an FCLIB file.
//
// Units: the impulses are scaled by s, the mean W_nn of the contacts (r = s p, W = W_SI / s), so
// that r and u are both velocities (m/s) and an error that mixes them is balanced. The core's
// warm start is kept as r0 = s p0, in FCLIB's guess slot (one guess: r0 and u0 = W r0 + q).
#pragma once

#include <string>
#include <vector>

#include "cd/problem_file.h"

namespace peers {

struct LocalProblem {
  int contacts = 0;
  // W, 2m x 2m, compressed by columns: the rows and values of column j are at
  // [column_start[j], column_start[j + 1]).
  std::vector<int> column_start;
  std::vector<int> row;
  std::vector<double> value;
  std::vector<double> q;           // m/s
  std::vector<double> mu;          // per contact
  std::vector<double> warm_start;  // r0 = s p0 (m/s)
  double impulse_scale = 1.0;      // s (m/s per N s)
  std::string label;               // where the problem comes from

  int size() const { return 2 * contacts; }
  std::vector<double> velocity(const std::vector<double>& reaction) const;  // W r + q
};

// The local problem of a saved step: W from the contacts' frames, masses and levers (the same
// operator the core's sweep applies), q the law velocity at the free velocities (bias included).
LocalProblem local_problem(const cd::ContactProblem& problem);

// The same W, q, mu and warm start, bit for bit (a FCLIB file against the saved step beside it).
bool same_problem(const LocalProblem& a, const LocalProblem& b);

// The core's impulses p (N s) of its contacts as r (m/s), and back.
std::vector<double> reaction_of(const LocalProblem& local, const std::vector<cd::Contact>& contacts);

// Throws std::runtime_error naming the file if it cannot be written.
void write_fclib(const std::string& path, const LocalProblem& problem);

// Reads a problem written by write_fclib (or any 2D FCLIB local problem without V, R, s; a
// problem without a guess starts from zero). Throws std::runtime_error with one line naming the
// file and what is wrong.
LocalProblem read_fclib(const std::string& path);

}  // namespace peers
