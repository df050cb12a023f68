// One step's contact problem as a solver meets it, saved to a file and read back: the corpus of
// hard steps that solvers are measured on (bench/solver_corpus). The contacts are prepared
// (frames, Delassus blocks, biases) and carry their starting impulses; the velocities are the
// free ones, before those impulses are applied. Pairs that might join during the solve are not
// kept: a saved problem is solved on its contacts alone.
#pragma once

#include <string>
#include <vector>

#include "cd/contact.h"

namespace cd {

struct ContactProblem {
  std::vector<Contact> contacts;
  std::vector<BodyVelocity> free_velocity;  // per body, the world body first
  std::vector<double> height;               // per body: y of its centre (m), 0 for the world
  std::string label;                        // one line: where the problem comes from
};

// Writes the problem (a binary file of this build's layout; Contact and BodyVelocity sizes are
// checked on reading). Throws std::runtime_error naming the file if it cannot be written.
void write_problem(const std::string& path, const ContactProblem& problem);

// Reads a problem written by write_problem. Throws std::runtime_error with one line naming the
// file and what is wrong (not a problem file, another layout, truncated, a body index out of
// range).
ContactProblem read_problem(const std::string& path);

}  // namespace cd
