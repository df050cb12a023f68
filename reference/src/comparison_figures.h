// The comparison's figures (gnuplot, through cdpost's figure writer).
#pragma once

#include <vector>

#include "comparison.h"
#include "output/gnuplot.h"

namespace cdref {

// The spectra of every run, then of the rigid runs with each soft code's; the peaks, U, phi
// and h against k (when a run has k); U(t), u(z) and the cost of every run.
std::vector<cdpost::Figure> comparison_figures(const Comparison& comparison);

}  // namespace cdref
