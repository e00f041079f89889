// Exercise 1.2, gravity and air friction (labs/01_rope/gravity_air.cpp): its public tests.
#include <gtest/gtest.h>

#include <springlab/rope/rope.hpp>
#include "seeded.hpp"
#include "rope_fixtures.hpp"

namespace springlab::rope {
namespace {

using GravityAndAirFriction = springlab::testing::Seeded;
using springlab::testing::quietRope;
using HangingRope = springlab::testing::Seeded;

TEST_F(GravityAndAirFriction, WeightIsMassTimesGravitation) {
  const double m = uniform(0.01, 5);
  const Vec3 g = vec3(-10, 10);
  const Vec3 f = gravityAndAirFriction(m, Vec3::Zero(), g, uniform(0, 1));
  EXPECT_LT((f - m * g).norm(), 1e-12 * std::max(1.0, f.norm()))
      << "a mass at rest must feel its weight m g and nothing else " << seedText();
}

TEST_F(GravityAndAirFriction, AirFrictionOpposesVelocity) {
  const double air = uniform(0.01, 1);
  const Vec3 v = vec3(-5, 5);
  const Vec3 f = gravityAndAirFriction(uniform(0.01, 5), v, Vec3::Zero(), air);
  EXPECT_LT((f + air * v).norm(), 1e-12 * std::max(1.0, f.norm()))
      << "without gravity the force must be the air friction -c v, opposite to the velocity " << seedText();
}

TEST_F(HangingRope, EachSpringCarriesTheWeightBelowIt) {
  // A rope hanging straight down settles where spring i holds the weight of the masses below.
  const int n = integer(5, 10);
  RopeParameters p = quietRope(n, 0.1, 200, 0.1, 2.0);
  p.direction = Vec3(0, -1, 0);
  p.gravitation = Vec3(0, -9.81, 0);
  p.airFrictionConstant = 0.3;
  Rope rope(3, p);
  for (int step = 0; step < 30000; ++step) rope.operate(0.001);
  for (int i = 0; i + 1 < n; ++i) {
    const double stretch = (rope.state.pos[i] - rope.state.pos[i + 1]).norm() - p.springLength;
    const double expected = (n - 1 - i) * p.mass * 9.81 / p.springConstant;
    EXPECT_NEAR(stretch, expected, 0.01 * expected + 1e-6)
        << "at rest, spring " << i << " must stretch by (weight of the " << n - 1 - i << " masses below) / k "
        << seedText();
  }
}

}  // namespace
}  // namespace springlab::rope
