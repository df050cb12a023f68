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

}  // namespace
