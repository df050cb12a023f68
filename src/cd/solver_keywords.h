// The solver's keywords read from text, once for every host: the fix's command line
// (src/fix_contact_dynamics_settings.cpp) and the corpus bench's settings (bench/solver_corpus.cpp).
//   solver NAME (cd::make_solver, cd/solver_registry.h), tolerance, max_iterations, norm (quadratic|maximum),
//   and Gauss–Seidel's: relaxation, over_relaxation, acceleration (none|conjugate), full_sweep_every,
//   stall_window, stall_coherence, stall_relaxation, stall_block, stall_block_every, newton_polish.
#pragma once

#include <optional>
#include <string>

#include "cd/solver.h"

namespace cd {

// Sets `keyword` from its value's text: nullopt if the keyword is none of the solver's; else
// empty once set, or one line naming the keyword, e.g. "tolerance expects a number, got 'e'".
// Values are read whole (no trailing characters, no hexadecimal, inf or nan); ranges are
// cd::check's.
std::optional<std::string> read_solver_keyword(SolverSettings& settings, const std::string& keyword,
                                               const std::string& value);

}  // namespace cd
