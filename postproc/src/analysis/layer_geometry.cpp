#include "analysis/layer_geometry.h"

#include <cmath>

namespace cdpost {

std::optional<std::string> add_layer_geometry(ResultTable& results, const PackingProfile& profile,
                                              const std::string& source)
{
  const auto* h = results.find("h");
  const auto* u = results.find("U");
  if (!h || !u) return "no h or U: phi_bulk, h_packing and I_packing not measured";
  double bulk = 0, top = 0;
  try {
    bulk = bulk_packing(profile, h->value);
    top = half_packing_height(profile, bulk, h->value);
  } catch (const AnalysisError& e) {
    return std::string("phi_bulk, h_packing and I_packing not measured: ") + e.what();
  }
  results.add("phi_bulk", bulk, "",
              "mean area fraction of the bins of phi(z) centred in 0.2 h <= z <= 0.8 h (" + source + ")");
  results.add("h_packing", top, "d", "height above the wall tops where phi(z) falls to half phi_bulk (" + source + ")");
  const double inertial = u->value / std::pow(top, 1.5);
  Estimate i{inertial, std::nullopt};
  if (u->error) i.error = inertial * *u->error / u->value;
  results.add("I_packing", i, "", "inertial number d U / (sqrt(g) h_packing^1.5); error from U alone");
  return std::nullopt;
}

}  // namespace cdpost
