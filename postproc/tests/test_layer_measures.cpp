// The layer measures that do not weigh the free surface (fit/packing_profile.h): phi_bulk and
// h_packing of analytic packing profiles.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/published_run.h"
#include "fit/packing_profile.h"
#include "io/line_source.h"
#include "signal/statistics.h"
#include "temp_files.h"

namespace cdpost {
namespace {

// A bed of 0.83 below the wall tops, a 3 d transition to the bulk phi_b, and a dilute surface
// phi_b erfc((z - H)/w)/2 about H: phi(z) in 1 d bins from z = -20 d to 80 d.
struct Layer {
  double phi_bed = 0.83, phi_bulk = 0.78, top = 47.3, width = 3;
  double phi(double z) const
  {
    const double core = z < 0 ? phi_bed : z < 3 ? phi_bed + (phi_bulk - phi_bed) * z / 3 : phi_bulk;
    return z < 0 ? core : core * 0.5 * std::erfc((z - top) / width);
  }
  PackingProfile profile() const
  {
    PackingProfile p;
    for (double z = -19.5; z < 80; z += 1) p.z_d.push_back(z), p.phi.push_back(phi(z));
    return p;
  }
  // The surface definition of the same profile: h = 2 <z> over the grain area above z = 0 and
  // phi = that area / h (per unit length).
  std::pair<double, double> surface_definition() const
  {
    double area = 0, moment = 0;
    for (double z = 0.5; z < 80; z += 1) area += phi(z), moment += z * phi(z);
    const double h = 2 * moment / area;
    return {h, area / h};
  }
};

TEST(LayerMeasures, BulkPackingAndHalfHeightOfALayerWithADiluteSurface)
{
  const Layer layer;
  const auto profile = layer.profile();
  const auto [h, phi_surface] = layer.surface_definition();
  // The surface definition weighs the denser transition to the bed: phi is 0.0015 above the bulk's.
  EXPECT_GT(phi_surface - layer.phi_bulk, 1e-3);
  // Over 0.2 h-0.8 h (9.8-39.2 d) the tail departs from phi_b by phi_b erfc(8.1/3)/2 < 1e-4
  // relatively, the transition not at all.
  const double bulk = bulk_packing(profile, h);
  EXPECT_NEAR(bulk, layer.phi_bulk, 1e-4 * layer.phi_bulk);
  // The window moves with h, the bulk hardly: 2 d either way.
  EXPECT_NEAR(bulk_packing(profile, h - 2), bulk, 1e-4);
  EXPECT_NEAR(bulk_packing(profile, h + 2), bulk, 1e-4);
  // The tail is antisymmetric about H, its inflection: interpolating linearly between the bin
  // centres 46.5 and 47.5 d errs at third order in the bin over w, below 0.01 d for w = 3 d.
  EXPECT_NEAR(half_packing_height(profile, bulk, h), layer.top, 0.01);
}

TEST(LayerMeasures, TheWidthOfTheSurfaceMovesTheSurfaceDefinitionOnly)
{
  // From a 1 d to a 6 d dilute surface about the same H: h = 2 <z> rises by 0.37 d and
  // phi = area/h falls by 0.006 (computed from the profiles), h_packing and phi_bulk stay.
  Layer narrow, wide;
  narrow.width = 1;
  wide.width = 6;
  const auto [h_narrow, phi_narrow] = narrow.surface_definition();
  const auto [h_wide, phi_wide] = wide.surface_definition();
  EXPECT_GT(h_wide - h_narrow, 0.3);
  EXPECT_GT(phi_narrow - phi_wide, 5e-3);
  const double bulk_narrow = bulk_packing(narrow.profile(), h_narrow), bulk_wide = bulk_packing(wide.profile(), h_wide);
  EXPECT_NEAR(bulk_narrow, narrow.phi_bulk, 1e-4 * narrow.phi_bulk);
  EXPECT_NEAR(bulk_wide, wide.phi_bulk, 1e-3 * wide.phi_bulk);  // erfc(4.1/6)/2 reaches the window's top
  const double top_narrow = half_packing_height(narrow.profile(), bulk_narrow, h_narrow);
  const double top_wide = half_packing_height(wide.profile(), bulk_wide, h_wide);
  EXPECT_NEAR(top_narrow, narrow.top, 0.05);  // a 1 d surface is barely resolved by 1 d bins
  EXPECT_NEAR(top_wide, wide.top, 0.05);
}

TEST(LayerMeasures, ProfilesWithoutABulkOrASurfaceAreRefused)
{
  const Layer layer;
  auto profile = layer.profile();
  // A profile cut below the surface never falls to half its bulk.
  PackingProfile cut;
  for (size_t i = 0; i < profile.z_d.size(); ++i)
    if (profile.z_d[i] < 44) cut.z_d.push_back(profile.z_d[i]), cut.phi.push_back(profile.phi[i]);
  EXPECT_THROW(half_packing_height(cut, layer.phi_bulk, 47), AnalysisError);
  // h = 4 d puts 2 bins (1.5, 2.5 d) in the window 0.8-3.2 d.
  EXPECT_THROW(bulk_packing(profile, 4), AnalysisError);
  EXPECT_THROW(bulk_packing(profile, 0), AnalysisError);
  auto descending = profile;
  std::swap(descending.z_d[3], descending.z_d[4]);
  EXPECT_THROW(bulk_packing(descending, 47), AnalysisError);
}

TEST(LayerMeasures, PackingFromCountsUsesTheMeanGrainArea)
{
  // <D²> of D uniform in [1 - δ/2, 1 + δ/2] by the midpoint rule (error ~ 1e-12 with 1e5 points).
  const double dispersity = 0.4;
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double diameter = 1 - dispersity / 2 + dispersity * (i + 0.5) / n;
    sum += M_PI / 4 * diameter * diameter;
  }
  EXPECT_NEAR(mean_grain_area_d2(dispersity), sum / n, 1e-9);
  // 43.5 grains of that mean area in a 45 d x 1 d bin.
  const auto phi = packing_from_counts({43.5, 0}, 45, 1, dispersity);
  EXPECT_NEAR(phi[0], 43.5 * sum / n / 45, 1e-9);
  EXPECT_EQ(phi[1], 0);
  EXPECT_THROW(packing_from_counts({1}, 0, 1, dispersity), AnalysisError);
  EXPECT_THROW(packing_from_counts({1}, 45, 1, 1.2), AnalysisError);
}

// A published run without phi in profile.csv (as results/runs/<name> before the packing
// definition): phi(z) from its counts with L and the dispersity of params.json.
TEST(LayerMeasures, PublishedRunsEstimatePhiFromTheirCounts)
{
  const auto dir = testing::scratch_dir();
  testing::write_file(dir / "results.csv",
                      "name,value,error,unit,description\nU,20,0.1,sqrt(g d),\nh,40,0.02,d,\"2 <z>\"\n");
  std::string profile = "z_d,u_sqrt_gd,count\n";
  const double area = mean_grain_area_d2(0.4), length = 45;
  const Layer layer;  // its phi(z) as counts: count = phi L / area
  for (double z = -9.5; z < 60; z += 1)
    if (layer.phi(z) > 1e-6) profile += std::to_string(z) + ",1," + std::to_string(layer.phi(z) * length / area) + "\n";
  testing::write_file(dir / "profile.csv", profile);
  // Without params.json: a warning, no packing definition.
  auto run = read_published_run(dir.string());
  EXPECT_FALSE(run.results.find("phi_bulk"));
  ASSERT_EQ(run.warnings.size(), 1u);
  EXPECT_NE(run.warnings[0].find("params.json is missing (L, dispersity)"), std::string::npos) << run.warnings[0];
  testing::write_file(dir / "params.json",
                      "{\n  \"vars\": {\n    \"L\": \"45\",\n    \"dispersity\": \"0.4\"\n  }\n}\n");
  run = read_published_run(dir.string());
  ASSERT_TRUE(run.results.find("phi_bulk"));
  EXPECT_NEAR(run.results.find("phi_bulk")->value, layer.phi_bulk, 1e-4);  // counts written to 6 decimals
  EXPECT_NEAR(run.results.find("h_packing")->value, layer.top, 0.01);
  EXPECT_NEAR(run.results.find("I_packing")->value, 20 / std::pow(run.results.find("h_packing")->value, 1.5), 1e-12);
  // The profiles a series reads (the local inertial number): u(z) and phi(z) per bin.
  ASSERT_TRUE(run.profile);
  ASSERT_EQ(run.profile->phi.size(), run.profile->z_d.size());
  for (size_t i = 0; i < run.profile->z_d.size(); ++i)
    EXPECT_NEAR(run.profile->phi[i], layer.phi(run.profile->z_d[i]), 1e-4) << run.profile->z_d[i];
  EXPECT_EQ(run.profile->bin_width_d, 1);
  EXPECT_EQ(recorded_deck_variable(dir.string(), "reading"), std::nullopt);
  testing::write_file(dir / "params.json",
                      "{\n  \"vars\": {\n    \"L\": \"45\",\n    \"dispersity\": \"0.4\",\n    \"reading\": "
                      "\"layer\"\n  }\n}\n");
  EXPECT_EQ(recorded_deck_variable(dir.string(), "reading"), "layer");
  // A params.json without L fails naming the file.
  testing::write_file(dir / "params.json", "{\"vars\": {\"dispersity\": \"0.4\"}}\n");
  try {
    read_published_run(dir.string());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("params.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no value for \"L\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cdpost
