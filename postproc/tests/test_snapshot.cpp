// The snapshot figure: walls on the periodic boundary up to the wall tops, periodic images
// only where a grain can cross (centre above the wall tops) and only across periodic sides; the
// diameter and the periodicity read from the dump unless given.
#include <gtest/gtest.h>

#include <cmath>

#include "figures/snapshot.h"
#include "io/line_source.h"
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
SnapshotRequest cell_dump(std::optional<double> wall_tops = 8.0)
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
  request.wall_tops = wall_tops;
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
  const Figure figure = snapshot_figure(cell_dump(), unit_d()).figure;
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

// Atoms of an obstacle type (a ring moved by fix move, outside the fix's group) are no grains: drawn
// apart in grey with their images, off the colour scale, the grain count and the mean diameter.
TEST(Snapshot, ObstaclesAreDrawnApartFromGrains)
{
  auto request = cell_dump();
  const std::vector<testing::DumpAtom> atoms = {
      {1, 5.0, 12.0, 1, 0, 0.5},      // a grain
      {2, 10.0, 12.0, 3, 0, 0.5},     // a grain
      {3, 0.5, 15.0, 0, 0, 2.0, 2},   // an obstacle at x = 0, above the wall tops: imaged at x = L
      {4, 15.0, 15.0, 0, 0, 2.0, 2},  // an obstacle mid-cell
  };
  testing::write_file(request.dump_path, testing::dump_frame_text(100, 20, 30, atoms));
  request.obstacle_types = {2};
  request.diameter_from_dump = true;
  const auto snapshot = snapshot_figure(request, unit_d());
  const Figure& figure = snapshot.figure;
  ASSERT_NE(curve_named(figure, "obstacles"), nullptr);
  const Curve& obstacles = *curve_named(figure, "obstacles");
  EXPECT_EQ(obstacles.style, CurveStyle::Obstacles);
  ASSERT_EQ(obstacles.x.size(), 3u);  // two obstacles and the image of the one at x = 0
  EXPECT_DOUBLE_EQ(obstacles.x[0], 0.5);
  EXPECT_DOUBLE_EQ(obstacles.x[1], 20.5);
  EXPECT_DOUBLE_EQ(obstacles.x[2], 15.0);
  EXPECT_EQ(curve_named(figure, "grains")->x.size(), 2u);
  EXPECT_EQ(curve_named(figure, "periodic images"), nullptr);  // the grains are mid-cell
  EXPECT_NE(figure.panels[0].title.find("(2 grains, 2 obstacle atoms)"), std::string::npos);
  EXPECT_NE(figure.caption.find("obstacles (atom type 2) in grey"), std::string::npos);
  // d is the grains' mean diameter, 1, not the mean over every atom (2.5).
  EXPECT_NE(snapshot.parameters.find("d 1 input length units"), std::string::npos) << snapshot.parameters;
  // Without the option they are grains, as before.
  request.obstacle_types.clear();
  EXPECT_EQ(curve_named(snapshot_figure(request, unit_d()).figure, "obstacles"), nullptr);
  request.obstacle_types = {7};
  try {
    snapshot_figure(request, unit_d());
    ADD_FAILURE() << "no atom of type 7: refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no atom of the obstacle type(s) 7"), std::string::npos) << e.what();
  }
}

TEST(Snapshot, ImagesOnlyAboveTheWallTops)
{
  const Figure figure = snapshot_figure(cell_dump(), unit_d()).figure;
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
  const Figure figure = snapshot_figure(cell_dump(std::nullopt), unit_d()).figure;
  EXPECT_EQ(curve_named(figure, "walls"), nullptr);
  const Curve* images = curve_named(figure, "periodic images");
  ASSERT_NE(images, nullptr);
  EXPECT_EQ(images->x.size(), 4u);
}

TEST(Snapshot, GnuplotBreaksTheLineBetweenTheWalls)
{
  const std::string script = gnuplot_script(snapshot_figure(cell_dump(), unit_d()).figure);
  EXPECT_NE(script.find("0 -8\n0 0\n\n20 -8\n20 0\nEOD"), std::string::npos) << script;
  EXPECT_NE(script.find("with lines lw 3 lc rgb 'black'"), std::string::npos);
}

// One frame of a box 12 x 6 input units with the given boundary flags: grains of radius 0.25 and
// 0.5 (mean diameter 0.75), one near each side and one in the middle.
SnapshotRequest box_dump(const std::string& boundary)
{
  const std::vector<testing::DumpAtom> atoms = {
      {1, 0.5, 3.0, 0, 0, 0.25},  // near x = 0
      {2, 11.5, 3.0, 0, 0, 0.5},  // near x = 12
      {3, 6.0, 0.5, 0, 0, 0.25},  // near y = 0
      {4, 6.0, 3.0, 0, 0, 0.5},   // middle
      {5, 0.5, 5.5, 0, 0, 0.25},  // near the corner x = 0, y = 6
      {6, 6.0, 5.5, 0, 0, 0.5},   // near y = 6
  };
  SnapshotRequest request;
  request.dump_path = (testing::scratch_dir() / "dump.box").string();
  testing::write_file(request.dump_path, testing::dump_frame_text(7, 12, 6, atoms, boundary));
  return request;
}

TEST(Snapshot, DiameterFromTheDumpUnlessGiven)
{
  auto request = box_dump("ff fm pp");
  request.diameter_from_dump = true;
  const auto snapshot = snapshot_figure(request, Units{});  // the default d (5e-4 m) is not used
  const Curve* grains = curve_named(snapshot.figure, "grains");
  ASSERT_NE(grains, nullptr);
  // Lengths in the dump's mean diameter, 0.75 input units (SI: 0.75 m).
  EXPECT_NEAR(grains->x[1], 11.5 / 0.75, 1e-12);
  EXPECT_NEAR(grains->radius[1], 0.5 / 0.75, 1e-12);
  EXPECT_NE(snapshot.parameters.find("d 0.75 input length units (the dump's mean diameter)"), std::string::npos)
      << snapshot.parameters;
  request.diameter_from_dump = false;
  EXPECT_NEAR(curve_named(snapshot_figure(request, unit_d()).figure, "grains")->x[1], 11.5, 1e-12);
}

TEST(Snapshot, ImagesOnlyAcrossThePeriodicSidesOfTheBox)
{
  // The pour's box (f fm p): no periodic side in the plane, no image, no caption about them.
  auto closed = snapshot_figure(box_dump("ff fm pp"), unit_d());
  EXPECT_EQ(curve_named(closed.figure, "periodic images"), nullptr);
  EXPECT_EQ(closed.figure.caption.find("periodic images"), std::string::npos);
  EXPECT_NE(closed.parameters.find("not periodic (the dump's box bounds)"), std::string::npos) << closed.parameters;
  // Periodic in y only: grains 3, 5 and 6 (within 0.15 of the height of y = 0 or 6) get an image
  // 6 away along y, none along x.
  const auto along_y = snapshot_figure(box_dump("ff pp pp"), unit_d());
  const Curve* images = curve_named(along_y.figure, "periodic images");
  ASSERT_NE(images, nullptr);
  ASSERT_EQ(images->x.size(), 3u);
  EXPECT_DOUBLE_EQ(images->x[0], 6.0);
  EXPECT_DOUBLE_EQ(images->y[0], 6.5);
  EXPECT_DOUBLE_EQ(images->x[1], 0.5);
  EXPECT_DOUBLE_EQ(images->y[1], -0.5);
  EXPECT_DOUBLE_EQ(images->y[2], -0.5);
  // Periodic in both: grains 1, 2 across x, 3 and 6 across y, 5 across x, y and the corner.
  const auto both = snapshot_figure(box_dump("pp pp pp"), unit_d());
  EXPECT_EQ(curve_named(both.figure, "periodic images")->x.size(), 7u);
  EXPECT_NE(both.parameters.find("periodic in x and y"), std::string::npos);
}

TEST(Snapshot, PeriodicityGivenWinsAndNoFlagsAsksForIt)
{
  auto request = box_dump("pp pp pp");
  request.periodic = std::array<bool, 2>{false, false};
  const auto told = snapshot_figure(request, unit_d());
  EXPECT_EQ(curve_named(told.figure, "periodic images"), nullptr);
  EXPECT_NE(told.parameters.find("(from --periodic)"), std::string::npos);
  // A dump whose "ITEM: BOX BOUNDS" line has no flags (LAMMPS before 2010).
  auto bare = box_dump("");
  try {
    snapshot_figure(bare, unit_d());
    FAIL() << "a dump without boundary flags was drawn";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give --periodic"), std::string::npos) << e.what();
  }
  bare.periodic = std::array<bool, 2>{true, false};
  EXPECT_NE(curve_named(snapshot_figure(bare, unit_d()).figure, "periodic images"), nullptr);
}

// The canvas takes the cell's shape: a tall cell a tall picture, a flat pile a wide one; tick
// labels are far enough apart to be read (x: 70 px, y: 30 px at the plot's scale).
TEST(Snapshot, CanvasFollowsTheCellAndTicksStayApart)
{
  auto tall = cell_dump();  // 20 d wide (plus images), 30 d high, walls to 8 d: taller than wide
  tall.periodic = std::array<bool, 2>{true, true};
  const auto tall_figure = snapshot_figure(tall, unit_d()).figure;
  EXPECT_GT(tall_figure.height_px, tall_figure.width_px);

  const std::vector<testing::DumpAtom> pile = {{1, 1, 0.5, 0, 0, 0.5}, {2, 99, 0.5, 0, 0, 0.5}};
  SnapshotRequest flat;
  flat.dump_path = (testing::scratch_dir() / "dump.pile").string();
  testing::write_file(flat.dump_path, testing::dump_frame_text(100, 100, 50, pile, "ff fm pp"));
  const auto flat_figure = snapshot_figure(flat, unit_d()).figure;
  EXPECT_GT(flat_figure.width_px, 3 * flat_figure.height_px);
  const auto& panel = flat_figure.panels.at(0);
  // The box of a shrink-wrapped top stays where the pour started: the picture ends above the pile.
  ASSERT_TRUE(panel.y_range.has_value());
  EXPECT_DOUBLE_EQ(panel.y_range->second, 2.0);  // the grains' top (1 d) plus a diameter
  const double plot_width = 900;                 // the long side of the plot area
  ASSERT_TRUE(panel.x_tick_step.has_value());
  EXPECT_GE(*panel.x_tick_step / 100 * plot_width, 70);
  EXPECT_LT(*panel.x_tick_step / 100 * plot_width, 3 * 70);  // not so sparse that one tick is left
}

}  // namespace
}  // namespace cdpost
