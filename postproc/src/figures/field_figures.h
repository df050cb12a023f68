// Figures of coarse-grained fields (analysis/fields.h): a map's packing fraction with velocity
// arrows, its pressure and friction; a profile's packing, velocity and stresses; mu(I) and phi(I)
// of the dense nodes (not drawn when no dense node has a shear rate).
#pragma once

#include <vector>

#include "analysis/fields.h"
#include "output/gnuplot.h"

namespace cdpost {

std::vector<Figure> field_figures(const Fields& fields);

}  // namespace cdpost
