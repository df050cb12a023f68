// The flowing layer's bulk packing and thickness read from its packing profile phi(z)
// (doc/scene.md, "Measures of the layer's bulk"): unlike h = 2 <z> and phi = grain area/(L h),
// neither weighs the dilute grains at the free surface.
#pragma once

#include <vector>

namespace cdpost {

// phi(z) in bins of equal width: bin centres in d above the wall tops (ascending), area fraction.
struct PackingProfile {
  std::vector<double> z_d, phi;
};

// The bulk is the part of the layer between these fractions of its thickness: above the
// transition to the bed near the wall tops, below the dilute surface.
constexpr double kBulkBottom = 0.2, kBulkTop = 0.8;

// Mean phi of the bins whose centre lies in [0.2 h, 0.8 h], h in d. Needs 3 such bins.
double bulk_packing(const PackingProfile& profile, double h_d);

// The height (d) above the wall tops where phi(z) falls to half of `bulk`: the first bin above
// the bulk window below the half, interpolated linearly against the bin below it (bin centres).
// Throws when phi(z) does not fall that far inside the profile.
double half_packing_height(const PackingProfile& profile, double bulk, double h_d);

// Mean area of a disk whose diameter is uniform in [(1 − δ/2) d, (1 + δ/2) d], in d²:
// π/4 (1 + δ²/12).
double mean_grain_area_d2(double dispersity);

// phi of each bin from its mean grain count: count × mean grain area / (L × bin width), all in d.
// Exact only on average: a bin's grains are not all of mean size.
std::vector<double> packing_from_counts(const std::vector<double>& counts, double length_d, double bin_width_d,
                                        double dispersity);

}  // namespace cdpost
