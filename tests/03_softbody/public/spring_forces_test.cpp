// Exercise 3.1, spring forces (labs/03_softbody/spring_forces.cpp): its public tests.
#include <gtest/gtest.h>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::Seeded;

std::vector<Vec3> zeros(size_t n) { return std::vector<Vec3>(n, Vec3::Zero()); }

class SpringForces : public Seeded {};

TEST_F(SpringForces, AreOppositeOnTheTwoEnds) {
  for (int t = 0; t < 100; ++t) {
    const std::vector<Vec3> pos = {vec3(-1, 1), vec3(-1, 1)}, vel = {vec3(-2, 2), vec3(-2, 2)};
    const std::vector<Spring> springs = {{0, 1, uniform(1, 1000), uniform(0, 2), uniform(0, 5), SpringKind::Structural}};
    std::vector<Vec3> f = zeros(2);
    addSpringForces(pos, vel, springs, f);
    ASSERT_LT((f[0] + f[1]).norm(), 1e-9 * (1.0 + f[0].norm()))
        << "the spring pushes its two ends with forces that are not equal and opposite " << seedText();
    ASSERT_GT(f[0].norm(), 0.0) << "a stretched or moving spring exerts no force at all " << seedText();
  }
}

TEST_F(SpringForces, FollowHookesLawAndDampAlongTheSpring) {
  // Mass 1 at distance l along x from mass 2: F1 = -k (l - L0) along x, damping only along x.
  const double k = uniform(10, 1000), L0 = uniform(0.5, 1.5), l = uniform(0.2, 2.0), kd = uniform(0.1, 3);
  const std::vector<Vec3> pos = {Vec3(l, 0, 0), Vec3::Zero()};
  std::vector<Vec3> f = zeros(2);
  addSpringForces(pos, zeros(2), {{0, 1, k, L0, 0.0, SpringKind::Structural}}, f);
  EXPECT_NEAR(f[0].x(), -k * (l - L0), 1e-9 * k) << "Hooke's law: F1 = -k (l - L0) e " << seedText();
  EXPECT_NEAR(f[0].y(), 0.0, 1e-12) << "a spring pushes only along its own direction " << seedText();

  // Relative velocity (a, b, 0): only its part along the spring is damped.
  const double a = uniform(-2, 2), b = uniform(-2, 2);
  f = zeros(2);
  addSpringForces(pos, {Vec3(a, b, 0), Vec3::Zero()}, {{0, 1, k, l, kd, SpringKind::Structural}}, f);
  EXPECT_NEAR(f[0].x(), -kd * a, 1e-9) << "damping must be -kd ((v1 - v2) . e) e " << seedText();
  EXPECT_NEAR(f[0].y(), 0.0, 1e-12) << "sideways relative motion must not be damped by the spring " << seedText();
}

TEST_F(SpringForces, ZeroLengthSpringExertsNoForce) {
  const Vec3 x = vec3(-1, 1);
  std::vector<Vec3> f = zeros(2);
  addSpringForces({x, x}, {vec3(-1, 1), vec3(-1, 1)}, {{0, 1, 100.0, 0.5, 1.0, SpringKind::Structural}}, f);
  EXPECT_TRUE(f[0].allFinite() && f[1].allFinite()) << "a spring of zero length gave a NaN force";
  EXPECT_EQ(f[0].norm(), 0.0) << "a spring of zero length has no direction and must exert no force";
}

}  // namespace
}  // namespace springlab::softbody
