// Where a step meets what it does not integrate (cd/kinematics.h, cd/periodic_box.h, cd/walls.h), against the kinematics of one
// step by hand: theta 0.6, dt 0.01 s, so lead (1 - theta) dt = 0.004 s and advance theta dt = 0.006 s.
#include <gtest/gtest.h>

#include "cd/kinematics.h"
#include "cd/periodic_box.h"
#include "cd/walls.h"

namespace {

const cd::StepParameters step{0.01, 0.6};

// An obstacle moved by s = (0.5, -0.25) m over the step is met at now - theta s, moving at s / dt;
// the corrector's theta dt (s / dt) then ends it where it stands now.
TEST(AtSolve, AMovedObstacleIsMetAtTheGrainsFractionOfItsStep)
{
  const cd::Displacement travel{0.5, -0.25};
  const cd::Disk met = cd::obstacle_at_solve({2.0, 1.0, 0.1}, travel, step);
  EXPECT_DOUBLE_EQ(met.x, 2.0 - 0.3);
  EXPECT_DOUBLE_EQ(met.y, 1.0 + 0.15);
  EXPECT_EQ(met.radius, 0.1);
  const cd::BodyVelocity v = cd::obstacle_velocity(travel, {7.0, 7.0, 3.0}, step.dt);
  EXPECT_DOUBLE_EQ(v.vx, 50.0);
  EXPECT_DOUBLE_EQ(v.vy, -25.0);
  EXPECT_EQ(v.spin, 3.0) << "the spin is the obstacle's own";
  EXPECT_DOUBLE_EQ(met.x + step.advance() * v.vx, 2.0) << "the corrector ends it where it stands";
}

TEST(AtSolve, AnObstacleNothingMovedKeepsItsPlaceAndVelocity)
{
  const cd::Disk met = cd::obstacle_at_solve({2.0, 1.0, 0.1}, {}, step);
  EXPECT_EQ(met.x, 2.0);
  EXPECT_EQ(met.y, 1.0);
  const cd::BodyVelocity v = cd::obstacle_velocity({}, {0.3, -0.2, 5.0}, step.dt);
  EXPECT_EQ(v.vx, 0.3) << "a surface velocity of its contacts";
  EXPECT_EQ(v.vy, -0.2);
}

// An image moving at (3, 4) m/s relative to its body is led by lead v = (0.012, 0.016) m and
// may come advance |v| = 0.03 m closer within the rest of the step.
TEST(AtSolve, AnImageOfADeformingBoxLeadsByItsVelocity)
{
  const cd::Displacement lead = cd::image_lead(3.0, 4.0, step);
  EXPECT_DOUBLE_EQ(lead.dx, 0.012);
  EXPECT_DOUBLE_EQ(lead.dy, 0.016);
  EXPECT_DOUBLE_EQ(cd::image_reach(3.0, 4.0, step), 0.03);
  EXPECT_EQ(cd::image_reach(0.0, 0.0, step), 0.0);
}

// A wall's images move one edge vector at each rate at most: |rate_x| + |rate_y| + |rate_xy|.
TEST(AtSolve, AWallsImagesReachAtMostOneEdgeVectorAtEachRate)
{
  cd::PeriodicBox box;
  box.rate_x = -1.0;
  box.rate_y = 0.5;
  box.rate_xy = 2.0;
  EXPECT_DOUBLE_EQ(cd::wall_image_reach(box, step), 0.006 * 3.5);
  EXPECT_EQ(cd::wall_image_reach(cd::PeriodicBox{}, step), 0.0) << "a box at rest";
}

}  // namespace

// A wall carried from (0, 0) to (0.1, 0) m and turned from 0 to 0.02 rad about the pivot (1, 2)
// over the step stands at end - theta (end - start) at x_m; its surface moves as a rigid body at
// the chords' rates, turning about the pivot where the displacement has carried it by then.
TEST(AtSolve, AMovingWallIsMetAtTheGrainsFractionOfItsTravel)
{
  const cd::WallPose start{0.0, 0.0, 0.0}, end{0.1, 0.0, 0.02};
  const cd::WallPose met = cd::wall_at_solve(start, end, step);
  EXPECT_DOUBLE_EQ(met.dx, 0.1 - 0.06);
  EXPECT_DOUBLE_EQ(met.dy, 0.0);
  EXPECT_DOUBLE_EQ(met.angle, 0.02 - 0.012);
  const cd::SurfaceMotion motion = cd::wall_motion(start, end, 1.0, 2.0, step);
  double vx = 0.0, vy = 0.0;
  motion.velocity_at(1.04, 3.0, vx, vy);  // 1 m above the pivot at x_m: spin 2 rad/s adds -2 m/s along x
  EXPECT_DOUBLE_EQ(vx, 10.0 - 2.0);
  EXPECT_DOUBLE_EQ(vy, 0.0);
  motion.velocity_at(2.04, 2.0, vx, vy);  // 1 m to its right: +2 m/s along y
  EXPECT_DOUBLE_EQ(vx, 10.0);
  EXPECT_DOUBLE_EQ(vy, 2.0);
}
