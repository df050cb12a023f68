// Wall geometry: lines, segment interiors and ends, across periodic boundaries.
#include <gtest/gtest.h>

#include <cmath>

#include "cd/walls.h"

namespace {

cd::Wall segment(double ax, double ay, double bx, double by)
{
  cd::Wall w;
  w.shape = cd::Wall::Shape::segment;
  w.ax = ax, w.ay = ay, w.bx = bx, w.by = by;
  return w;
}

TEST(Walls, LineGivesPerpendicularNormalAndGap)
{
  cd::Wall floor;  // y = 0
  floor.ax = 0, floor.ay = 0, floor.bx = 1, floor.by = 0;
  const auto touch = cd::wall_contact(floor, 1, {0.3, 0.45, 0.5}, 0.1, {});
  ASSERT_TRUE(touch);
  EXPECT_EQ(touch->part, cd::WallPart::interior);
  EXPECT_NEAR(touch->geometry.normal_y, 1.0, 1e-15);
  EXPECT_NEAR(touch->geometry.gap, -0.05, 1e-15);
  EXPECT_EQ(touch->geometry.body_b, cd::world_body);
  EXPECT_FALSE(cd::wall_contact(floor, 1, {0.3, 0.65, 0.5}, 0.1, {}));
}

TEST(Walls, SegmentEndIsAPointContact)
{
  const cd::Wall side = segment(0.0, 0.0, 0.0, 2.0);  // vertical, top end at (0, 2)
  const auto touch = cd::wall_contact(side, 1, {0.3, 2.4, 0.5}, 0.0, {});
  ASSERT_TRUE(touch);
  EXPECT_EQ(touch->part, cd::WallPart::end_b);
  EXPECT_NEAR(touch->geometry.normal_x, 0.6, 1e-15);
  EXPECT_NEAR(touch->geometry.normal_y, 0.8, 1e-15);
  EXPECT_NEAR(touch->geometry.gap, 0.0, 1e-15);
  const auto interior = cd::wall_contact(side, 1, {-0.4, 1.0, 0.5}, 0.0, {});
  ASSERT_TRUE(interior);
  EXPECT_EQ(interior->part, cd::WallPart::interior);
  EXPECT_NEAR(interior->geometry.normal_x, -1.0, 1e-15);
}

TEST(Walls, SegmentAtPeriodicBoundaryIsSeenFromBothSides)
{
  cd::PeriodicBox box;
  box.periodic_x = true;
  box.length_x = 10.0;
  const cd::Wall side = segment(0.0, 0.0, 0.0, 2.0);
  const auto from_right = cd::wall_contact(side, 1, {9.6, 1.0, 0.5}, 0.0, box);
  ASSERT_TRUE(from_right);
  EXPECT_NEAR(from_right->geometry.normal_x, -1.0, 1e-12);
  EXPECT_NEAR(from_right->geometry.gap, -0.1, 1e-12);
  EXPECT_FALSE(cd::wall_contact(side, 1, {9.6, 1.0, 0.5}, 0.0, {}));
}

// A y-periodic box tilted by half its length: the image of a segment across the bottom
// side lies half a length along x, under a disk the orthogonal image would miss.
TEST(Walls, TiltedBoxImagesTheSegmentAlongTheTilt)
{
  cd::PeriodicBox box;
  box.periodic_x = box.periodic_y = true;
  box.length_x = box.length_y = 10.0;
  box.tilt_xy = 5.0;
  const cd::Wall ledge = segment(1.0, 9.5, 4.0, 9.5);  // near the top; image at y = -0.5
  const auto under = cd::wall_contact(ledge, 1, {7.5, 0.4, 1.0}, 0.0, box);
  ASSERT_TRUE(under);
  EXPECT_EQ(under->part, cd::WallPart::interior);
  EXPECT_NEAR(under->geometry.normal_y, 1.0, 1e-12);
  EXPECT_NEAR(under->geometry.gap, -0.1, 1e-12);
  const cd::Point point = cd::contact_point(cd::contact_frame(under->geometry), under->geometry.gap, 7.5, 0.4);
  EXPECT_NEAR(point.x, 7.5, 1e-12);
  EXPECT_NEAR(point.y, -0.55, 1e-12) << "midway across the 0.1 overlap: the disk's lowest point -0.6, the image -0.5";
  EXPECT_FALSE(cd::wall_contact(ledge, 1, {2.5, 0.4, 1.0}, 0.0, box));
}

// A box sheared at rate_xy: the segment's image across the bottom side moves at -rate_xy
// along x (one edge vector down), the segment itself at rest.
TEST(Walls, ImageOfADeformingBoxMovesWithIt)
{
  cd::PeriodicBox box;
  box.periodic_x = box.periodic_y = true;
  box.length_x = box.length_y = 10.0;
  box.rate_xy = 0.3;
  box.rate_x = 0.02;
  const cd::Wall ledge = segment(1.0, 9.5, 4.0, 9.5);
  const auto below = cd::wall_contact(ledge, 1, {2.5, 0.4, 1.0}, 0.0, box);
  ASSERT_TRUE(below);
  EXPECT_DOUBLE_EQ(below->geometry.image_vx, -0.3);
  EXPECT_DOUBLE_EQ(below->geometry.image_vy, 0.0);
  const auto across_x = cd::wall_contact(segment(9.9, 1.0, 9.9, 3.0), 1, {0.5, 2.0, 1.0}, 0.0, box);
  ASSERT_TRUE(across_x);
  EXPECT_DOUBLE_EQ(across_x->geometry.image_vx, -0.02);
  const auto itself = cd::wall_contact(ledge, 1, {2.5, 8.6, 1.0}, 0.0, box);
  ASSERT_TRUE(itself);
  EXPECT_DOUBLE_EQ(itself->geometry.image_vx, 0.0);
  const cd::PeriodicBox later = box.advanced(2.0);
  EXPECT_DOUBLE_EQ(later.tilt_xy, 0.6);
  EXPECT_DOUBLE_EQ(later.length_x, 10.04);
}

}  // namespace

// A tilted box 10 x 10 m, tilt 5 m: (3, 12) from the lower corner lies one cell up and, measured
// along the tilted side (3 - 5 * 12/10 = -3), one cell left; the wrap adds (10, 0) - (5, 10),
// which lands at (8, 2), inside the box (x from 1 to 11 at y = 2). Without periodicity along x
// only the y cell is undone.
TEST(PeriodicBox, WrappingUndoesTheCellsAlongTheTiltedSides)
{
  cd::PeriodicBox box;
  box.periodic_x = box.periodic_y = true;
  box.length_x = box.length_y = 10.0;
  box.tilt_xy = 5.0;
  const cd::PeriodicBox::Shift shift = box.wrapping(3.0, 12.0);
  EXPECT_EQ(shift.x, 1);
  EXPECT_EQ(shift.y, -1);
  EXPECT_EQ(box.wrapping(4.0, 3.0).x, 0);
  EXPECT_EQ(box.wrapping(4.0, 3.0).y, 0);
  box.periodic_x = false;
  EXPECT_EQ(box.wrapping(3.0, 12.0).x, 0);
  EXPECT_EQ(box.wrapping(3.0, 12.0).y, -1);
}
