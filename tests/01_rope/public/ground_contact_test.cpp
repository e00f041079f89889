// Exercise 1.3, ground contact (labs/01_rope/ground_contact.cpp): its public tests.
#include <gtest/gtest.h>

#include <springlab/rope/rope.hpp>
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using GroundContact = springlab::testing::Seeded;

// The classic rope demo's ground.
Ground someGround() { return Ground{-1.5, 100.0, 0.2, 2.0}; }

TEST_F(GroundContact, NoForceAboveTheGround) {
  const Ground g = someGround();
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x(uniform(-3, 3), g.height + uniform(1e-6, 3), uniform(-3, 3));
    ASSERT_EQ(groundContactForce(x, vec3(-3, 3), g), Vec3::Zero())
        << "the ground must not act on a mass above it " << seedText();
  }
}

TEST_F(GroundContact, RepulsionGrowsWithDepth) {
  const Ground g = someGround();
  const double depth = uniform(0.01, 0.5);
  const Vec3 x(uniform(-3, 3), g.height - depth, uniform(-3, 3));
  const Vec3 f = groundContactForce(x, Vec3::Zero(), g);
  EXPECT_NEAR(f.y(), g.repulsion * depth, 1e-9)
      << "a resting mass below the ground must be pushed up by repulsion * depth " << seedText();
  EXPECT_NEAR(f.x(), 0.0, 1e-12) << "repulsion must be vertical";
  EXPECT_NEAR(f.z(), 0.0, 1e-12) << "repulsion must be vertical";
}

TEST_F(GroundContact, FrictionOpposesHorizontalVelocity) {
  const Ground g = someGround();
  const Vec3 x(0, g.height - 0.1, 0);
  const Vec3 v(uniform(-3, 3), 0.0, uniform(-3, 3));
  const Vec3 f = groundContactForce(x, v, g);
  EXPECT_NEAR(f.x(), -g.friction * v.x(), 1e-9) << "ground friction must be -friction * v along x " << seedText();
  EXPECT_NEAR(f.z(), -g.friction * v.z(), 1e-9) << "ground friction must be -friction * v along z " << seedText();
}

TEST_F(GroundContact, AbsorptionSlowsOnlyDownwardMotion) {
  const Ground g = someGround();
  const double depth = 0.1;
  const Vec3 x(0, g.height - depth, 0);
  const double speed = uniform(0.1, 3);
  const Vec3 down = groundContactForce(x, Vec3(0, -speed, 0), g);
  const Vec3 up = groundContactForce(x, Vec3(0, speed, 0), g);
  EXPECT_NEAR(down.y(), g.repulsion * depth + g.absorption * speed, 1e-9)
      << "a mass moving down into the ground must be slowed by absorption * |v_y| on top of repulsion "
      << seedText();
  EXPECT_NEAR(up.y(), g.repulsion * depth, 1e-9)
      << "absorption must not act on a mass moving up out of the ground (it would glue it down) " << seedText();
}

}  // namespace
}  // namespace springlab::rope
