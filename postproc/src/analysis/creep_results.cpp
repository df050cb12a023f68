#include "analysis/creep_results.h"

namespace cdpost {

namespace {

const std::string kBandPrefix = "creep_lambda_band_";

std::string text(double value)
{
  return format_estimate(value, std::nullopt);
}

}  // namespace

void add_creep_results(ResultTable& results, const CreepMeasure& creep)
{
  if (!creep.floor) return;
  const std::string multiple = text(kFloorMultiple);
  results.add("creep_floor", creep.floor->value, "sqrt(g d)",
              "noise floor of u below the wall tops, " + creep.floor->source());
  results.add("creep_points", creep.points, "",
              "profile bins of the creep fit range: from the highest below z = 0 down to the last before u first falls "
              "below " +
                  multiple + " x creep_floor");
  if (creep.points == 0) return;
  results.add("creep_z_high", creep.z_high, "d", "centre of the highest bin of the creep fit range");
  results.add("creep_z_low", creep.z_low, "d", "centre of the deepest bin of the creep fit range");
  if (!creep.lambda) return;
  results.add("creep_lambda", *creep.lambda, "d", "decay length of u(z) = u0 exp(z/lambda) over the creep fit range");
  results.add("creep_u0", *creep.u0, "sqrt(g d)", "u0 of the creep fit");
  for (const auto& band : creep.bands)
    results.add(kBandPrefix + text(band.depth_top_d) + "_" + text(band.depth_bottom_d), band.lambda, "d",
                "local decay length of u(z) over " + band_label(band) + " below the wall tops (" +
                    std::to_string(band.points) + " bins of the fit range)");
}

std::optional<std::string> creep_band_of(const std::string& result_name)
{
  if (result_name.rfind(kBandPrefix, 0) != 0) return std::nullopt;
  auto band = result_name.substr(kBandPrefix.size());
  const auto separator = band.find('_');
  if (separator == std::string::npos) return std::nullopt;
  return band.replace(separator, 1, "-") + " d";
}

bool is_creep_result(const std::string& name)
{
  return name.rfind("creep_", 0) == 0;
}

}  // namespace cdpost
