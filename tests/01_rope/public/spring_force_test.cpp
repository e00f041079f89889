// Exercise 1.1: the spring-damper force, checked against Hooke's law and linear damping.
#include <gtest/gtest.h>

#include <springlab/rope/rope.hpp>
#include "seeded.hpp"
#include "rope_fixtures.hpp"

namespace springlab::rope {
namespace {

using SpringForce = springlab::testing::Seeded;
using springlab::testing::quietRope;
using RopeDynamics = springlab::testing::Seeded;

TEST_F(SpringForce, IsZeroAtRestLengthWithoutRelativeMotion) {
  const Vec3 x2 = vec3(-1, 1);
  const Vec3 dir = vec3(-1, 1).normalized();
  const double L0 = uniform(0.1, 2.0);
  const Vec3 v = vec3(-1, 1);
  const Vec3 f = springDamperForce(x2 + L0 * dir, x2, v, v, uniform(1, 1000), L0, uniform(0, 5));
  EXPECT_LT(f.norm(), 1e-9) << "a spring at its rest length whose ends move together must exert no force "
                            << seedText();
}

TEST_F(SpringForce, IsOppositeOnEnds) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1), v1 = vec3(-2, 2), v2 = vec3(-2, 2);
    const double k = uniform(1, 1000), L0 = uniform(0.1, 2), kd = uniform(0, 5);
    const Vec3 on1 = springDamperForce(x1, x2, v1, v2, k, L0, kd);
    const Vec3 on2 = springDamperForce(x2, x1, v2, v1, k, L0, kd);
    ASSERT_LT((on1 + on2).norm(), 1e-9 * std::max(1.0, on1.norm()))
        << "the spring force is not opposite on its two ends (Newton's third law) " << seedText();
  }
}

TEST_F(SpringForce, FollowsHookesLawAlongTheSpring) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1);
    const double k = uniform(1, 1000), L0 = uniform(0.1, 2);
    const Vec3 f = springDamperForce(x1, x2, Vec3::Zero(), Vec3::Zero(), k, L0, 0.0);
    const double l = (x1 - x2).norm();
    const Vec3 e = (x1 - x2) / l;
    ASSERT_LT((f - f.dot(e) * e).norm(), 1e-9 * std::max(1.0, f.norm()))
        << "the elastic force must point along the spring " << seedText();
    ASSERT_NEAR(f.dot(e), -k * (l - L0), 1e-9 * k)
        << "the elastic force must be -k (l - L0) along e = (x1 - x2)/l: a stretched spring pulls mass 1 "
           "towards mass 2, a compressed one pushes it away "
        << seedText();
  }
}

TEST_F(SpringForce, DampsRelativeVelocityAlongTheSpringOnly) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x2 = vec3(-1, 1);
    const Vec3 e = vec3(-1, 1).normalized();
    const double L0 = uniform(0.1, 2), kd = uniform(0.1, 5);
    const Vec3 x1 = x2 + L0 * e;  // at rest length: only damping acts
    const Vec3 v1 = vec3(-2, 2), v2 = vec3(-2, 2);
    const Vec3 f = springDamperForce(x1, x2, v1, v2, 100.0, L0, kd);
    ASSERT_LT((f + kd * (v1 - v2).dot(e) * e).norm(), 1e-9 * std::max(1.0, f.norm()))
        << "the damping force must be -kd ((v1 - v2) . e) e: it resists the relative velocity along the "
           "spring and ignores motion across it "
        << seedText();
  }
}

TEST_F(SpringForce, ZeroLengthSpringExertsNoForce) {
  const Vec3 x = vec3(-1, 1);
  const Vec3 f = springDamperForce(x, x, vec3(-1, 1), vec3(-1, 1), 100.0, 0.5, 1.0);
  EXPECT_TRUE(f.allFinite()) << "two ends at the same point give a NaN force: guard l == 0";
  EXPECT_EQ(f, Vec3::Zero()) << "a spring of zero length has no direction; it must exert no force";
}

TEST_F(RopeDynamics, InternalForcesConserveMomentum) {
  // Without gravity, air and ground, forces are spring forces only: they sum to zero.
  RopeParameters p = quietRope(integer(3, 30), 0.05, uniform(10, 1e4), 0.1, uniform(0, 1));
  Rope rope(3, p);
  for (int i = 0; i < rope.numOfMasses(); ++i) {
    rope.state.pos[i] += vec3(-0.05, 0.05);
    rope.state.vel[i] = vec3(-1, 1);
  }
  rope.init();
  rope.solve();
  Vec3 total = Vec3::Zero();
  double scale = 0;
  for (const Vec3& f : rope.force) {
    total += f;
    scale += f.norm();
  }
  EXPECT_LT(total.norm(), 1e-9 * std::max(1.0, scale))
      << "the rope's internal forces must sum to zero (momentum is conserved) " << seedText();
}

}  // namespace
}  // namespace springlab::rope
