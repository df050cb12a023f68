// The layer measures that do not weigh the free surface (doc/scene.md): phi_bulk, h_packing
// and the inertial number I_packing built on h_packing, from a run's packing profile phi(z).
#pragma once

#include <optional>
#include <string>

#include "fit/packing_profile.h"
#include "output/results.h"

namespace cdpost {

// Adds phi_bulk, h_packing and I_packing to `results`, which must hold h (d: it places the
// bulk window) and U (sqrt(g d)). `source` says where phi(z) came from, for the descriptions.
// Returns why they cannot be measured instead (no h or U, phi(z) without a bulk or a surface).
std::optional<std::string> add_layer_geometry(ResultTable& results, const PackingProfile& profile,
                                              const std::string& source);

}  // namespace cdpost
