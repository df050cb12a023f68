// The snapshot figure: walls on the periodic boundary up to the wall tops, periodic images
// only where a grain can cross (centre above the wall tops).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/snapshot.h"
#include "lammps_text.h"
#include "temp_files.h"

namespace cdpost {
namespace {

const Curve* curve_named(const Figure& figure, const std::string& title)
{
  for (const auto& curve : figure.panels.at(0).curves)
    if (curve.title == title) return &curve;
  return nullptr;
}

// A 20 d cell (d = 1 input unit), wall tops at y = 8: grains next to both boundaries below
// and above the wall tops, and one in the middle.
SnapshotRequest cell_dump()
{
  const std::vector<testing::DumpAtom> atoms = {
      {1, 0.6, 3.0, 0, 0, 0.5},    // in the bed, at x = 0
      {2, 19.4, 7.4, 0, 0, 0.5},   // in the bed, at x = L, centre just below the wall tops
      {3, 0.6, 9.0, 0, 0, 0.5},    // flowing, at x = 0
      {4, 19.4, 12.0, 0, 0, 0.5},  // flowing, at x = L
      {5, 10.0, 9.0, 0, 0, 0.5},   // flowing, mid-cell
  };
  SnapshotRequest request;
  request.dump_path = (testing::scratch_dir() / "dump.cell").string();
  testing::write_file(request.dump_path, testing::dump_frame_text(100, 20, 30, atoms));
  return request;
}

Units unit_d()
{
  Units units;
  units.d_m = 1;
  return units;
}

TEST(Snapshot, WallsStandOnTheBoundaryUpToTheWallTops)
{
  const Figure figure = snapshot_figure(cell_dump(), unit_d(), 8.0);
  const Curve* walls = curve_named(figure, "walls");
  ASSERT_NE(walls, nullptr);
  ASSERT_EQ(walls->x.size(), 5u);
  // x = 0 and x = L, each from the floor (box bottom, z = -8) to the wall tops (z = 0).
  EXPECT_EQ(walls->x[0], 0.0);
  EXPECT_EQ(walls->x[1], 0.0);
  EXPECT_EQ(walls->y[0], -8.0);
  EXPECT_EQ(walls->y[1], 0.0);
  EXPECT_TRUE(std::isnan(walls->x[2]));
  EXPECT_EQ(walls->x[3], 20.0);
  EXPECT_EQ(walls->x[4], 20.0);
  EXPECT_EQ(walls->y[3], -8.0);
  EXPECT_EQ(walls->y[4], 0.0);
  EXPECT_NE(figure.caption.find("above the wall tops"), std::string::npos);
}

TEST(Snapshot, ImagesOnlyAboveTheWallTops)
{
  const Figure figure = snapshot_figure(cell_dump(), unit_d(), 8.0);
  ASSERT_NE(curve_named(figure, "grains"), nullptr);
  EXPECT_EQ(curve_named(figure, "grains")->x.size(), 5u);
  const Curve* images = curve_named(figure, "periodic images");
  ASSERT_NE(images, nullptr);
  // Grains 3 and 4 (centres above the wall tops) have an image across the boundary; grains 1
  // and 2 (in the bed) and 5 (mid-cell) have none.
  ASSERT_EQ(images->x.size(), 2u);
  EXPECT_NEAR(images->x[0], 20.6, 1e-12);
  EXPECT_DOUBLE_EQ(images->y[0], 1.0);
  EXPECT_NEAR(images->x[1], -0.6, 1e-12);
  EXPECT_DOUBLE_EQ(images->y[1], 4.0);
}

TEST(Snapshot, WithoutWallsEveryGrainNearTheBoundaryHasAnImage)
{
  const Figure figure = snapshot_figure(cell_dump(), unit_d(), 0.0);
  EXPECT_EQ(curve_named(figure, "walls"), nullptr);
  const Curve* images = curve_named(figure, "periodic images");
  ASSERT_NE(images, nullptr);
  EXPECT_EQ(images->x.size(), 4u);
}

TEST(Snapshot, GnuplotBreaksTheLineBetweenTheWalls)
{
  const std::string script = gnuplot_script(snapshot_figure(cell_dump(), unit_d(), 8.0));
  EXPECT_NE(script.find("0 -8\n0 0\n\n20 -8\n20 0\nEOD"), std::string::npos) << script;
  EXPECT_NE(script.find("with lines lw 3 lc rgb 'black'"), std::string::npos);
}

}  // namespace
}  // namespace cdpost
