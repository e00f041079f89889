// Exercise 1.8, fixed end following the connection point (labs/01_rope/fixed_end.cpp): its public tests.
#include <gtest/gtest.h>

#include <springlab/rope/rope.hpp>
#include "rope_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::rope {
namespace {

using springlab::testing::quietRope;
using FixedEnd = springlab::testing::Seeded;

TEST_F(FixedEnd, MovesWithTheConnectionVelocity) {
  const PhasePoint c{vec3(-1, 1) + Vec3(0, 5, 0), vec3(-1, 1)};
  const double dt = uniform(0.001, 0.05);
  const PhasePoint next = moveConnection(c, dt, -10.0);
  EXPECT_LT((next.pos - (c.pos + c.vel * dt)).norm(), 1e-12) << "the connection point moves by v dt " << seedText();
  EXPECT_LT((next.vel - c.vel).norm(), 1e-12) << "above the ground the connection keeps its velocity " << seedText();
}

TEST_F(FixedEnd, StopsAtTheGround) {
  const double ground = uniform(-2, 0);
  const PhasePoint c{Vec3(0.3, ground + 0.01, -0.2), Vec3(1, -5, 0.5)};
  const PhasePoint next = moveConnection(c, 0.1, ground);
  EXPECT_NEAR(next.pos.y(), ground, 1e-12) << "the connection point must stop at the ground height " << seedText();
  EXPECT_EQ(next.vel.y(), 0.0) << "at the ground the connection point loses its downward velocity";
  EXPECT_NEAR(next.pos.x(), 0.4, 1e-12) << "the ground stops only the vertical motion";
}

TEST_F(FixedEnd, RopeFollowsTheConnectionPoint) {
  RopeParameters p = quietRope(10, 0.05, 1000, 0.1, 0.5);
  Rope rope(3, p);
  const Vec3 v = vec3(-1, 1);
  rope.setControlVelocity(v);
  for (int n = 0; n < 100; ++n) rope.operate(0.001);
  EXPECT_LT((rope.state.pos[0] - (p.ropeConnectionPos + v * 0.1)).norm(), 1e-9)
      << "after 0.1 s the fixed end must be where the moving connection point is " << seedText();
  EXPECT_LT((rope.state.vel[0] - v).norm(), 1e-9) << "the fixed end must move with the connection point";
}

}  // namespace
}  // namespace springlab::rope
