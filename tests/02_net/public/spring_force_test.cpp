// Exercise 2.2, spring-damper force (labs/02_net/spring_force.cpp): its public tests.
#include <gtest/gtest.h>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using SpringForce = springlab::testing::Seeded;
using NetDynamics = springlab::testing::Seeded;
using springlab::testing::quietNet;

TEST_F(SpringForce, FollowsHookesLawAndDampsAlongTheSpring) {
  const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1), v1 = vec3(-2, 2), v2 = vec3(-2, 2);
  const double k = uniform(1, 500), L0 = uniform(0.1, 2), kd = uniform(0, 2);
  const Vec3 e = (x1 - x2).normalized();
  const double l = (x1 - x2).norm();
  const Vec3 want = -k * (l - L0) * e - kd * (v1 - v2).dot(e) * e;
  const Vec3 f = springDamperForce(x1, x2, v1, v2, k, L0, kd);
  EXPECT_LT((f - want).norm(), 1e-9 * std::max(1.0, want.norm()))
      << "F1 = -k (l - L0) e - kd ((v1 - v2) . e) e with e from mass 2 to mass 1 " << seedText();
  EXPECT_LT((springDamperForce(x2, x1, v2, v1, k, L0, kd) + f).norm(), 1e-9 * std::max(1.0, f.norm()))
      << "the force on mass 2 is the opposite of the force on mass 1 " << seedText();
  EXPECT_EQ(springDamperForce(x1, x1, v1, v2, k, L0, kd), Vec3::Zero()) << "a zero-length spring exerts no force";
}

TEST_F(NetDynamics, InternalForcesConserveMomentum) {
  // Springs only (no gravity, wind or pins): the forces add up to zero at any state.
  NetParameters p = quietNet(integer(3, 8));
  Net net(3, p);
  for (int i = 0; i < net.numOfMasses(); ++i) {
    net.state.pos[i] += vec3(-0.05, 0.05);
    net.state.vel[i] = vec3(-1, 1);
  }
  net.solve();
  Vec3 total = Vec3::Zero();
  double scale = 0.0;
  for (const Vec3& f : net.force) {
    total += f;
    scale += f.norm();
  }
  EXPECT_LT(total.norm(), 1e-9 * std::max(1.0, scale))
      << "internal spring forces must add up to zero (every spring pushes its ends equally and oppositely) "
      << seedText();
}

}  // namespace
}  // namespace springlab::net
