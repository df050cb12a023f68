// The creep measure (fit/creep.h) as rows of a run's results, and those rows read back.
#pragma once

#include <optional>
#include <string>

#include "fit/creep.h"
#include "output/results.h"

namespace cdpost {

// The rows creep_floor, creep_points, creep_z_high, creep_z_low, creep_lambda, creep_u0 and
// creep_lambda_band_<top>_<bottom> (what the measure has) added to `results`.
void add_creep_results(ResultTable& results, const CreepMeasure& creep);

// The band of a creep_lambda_band_<top>_<bottom> result, as "<top>-<bottom> d"; none for
// another name.
std::optional<std::string> creep_band_of(const std::string& result_name);

// Whether a result row belongs to the creep measure (named creep_*).
bool is_creep_result(const std::string& name);

}  // namespace cdpost
