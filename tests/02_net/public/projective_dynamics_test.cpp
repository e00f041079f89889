// Exercise 2.12: the local step of projective dynamics, and the framework's local/global loop.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using ProjectiveDynamics = springlab::testing::Seeded;
using springlab::testing::netRegistry;
using springlab::testing::fabric;
using springlab::testing::hangingCloth;
using springlab::testing::largestForceOverWeight;
using springlab::testing::lowestPoint;
using springlab::testing::quietNet;

std::unique_ptr<Integrator> projective(int iterations) {
  return springlab::testing::netIntegrator("projective_dynamics", {{"iterations", iterations}});
}

TEST_F(ProjectiveDynamics, ProjectionHasTheRestLengthAlongTheSpring) {
  for (int t = 0; t < 50; ++t) {
    const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1);
    const double L0 = uniform(0.1, 2);
    const Vec3 d = projectSpring(x1, x2, L0);
    ASSERT_NEAR(d.norm(), L0, 1e-12 * L0) << "the projected spring must have its rest length " << seedText();
    ASSERT_NEAR(d.dot(x1 - x2), L0 * (x1 - x2).norm(), 1e-9)
        << "the projected spring must point from x2 to x1, like x1 - x2 " << seedText();
  }
  const Vec3 none = projectSpring(Vec3::Ones(), Vec3::Ones(), 1.0);
  EXPECT_TRUE(none.allFinite()) << "a spring of length zero has no direction: never NaN";
}

TEST_F(ProjectiveDynamics, FixedPointIsTheStaticEquilibrium) {
  // A heavy cloth hanging in its plane from two corners, brought to rest by air friction:
  // where projective dynamics stops, the force model's springs must balance gravity, and one
  // more step must leave the cloth where it is.
  const NetParameters p = hangingCloth(integer(5, 8));
  Net net(3, p), reference(3, p);
  net.setIntegrator(projective(integer(10, 20)));
  reference.setIntegrator(netRegistry().makeIntegrator("implicit_euler"));
  for (int n = 0; n < 900; ++n) {
    net.operate(1.0 / 60.0);
    reference.operate(1.0 / 60.0);
  }
  const double worst = largestForceOverWeight(net);
  EXPECT_LT(worst, 0.01) << "at projective dynamics' rest state a mass still feels " << 100 * worst
                         << " % of its weight: the fixed point must be the force model's equilibrium " << seedText();
  EXPECT_NEAR(lowestPoint(net), lowestPoint(reference), 0.005 * std::abs(lowestPoint(reference)))
      << "the drape must be the force model's (implicit Euler at rest) within 0.5 % " << seedText();
  const std::vector<Vec3> before = net.state.pos;
  net.operate(1.0 / 60.0);
  double moved = 0.0;
  for (int i = 0; i < net.numOfMasses(); ++i) moved = std::max(moved, (net.state.pos[i] - before[i]).norm());
  EXPECT_LT(moved, 1e-4) << "one more step from the rest state moved a mass by " << moved << " m " << seedText();
}

TEST_F(ProjectiveDynamics, StableOnTheFabricAtASixtiethOfASecond) {
  const NetParameters p = fabric(integer(12, 16));  // scenes/net_hanging.json's light fabric
  Net net(3, p);
  net.setIntegrator(projective(integer(1, 10)));
  try {
    for (int n = 0; n < 120; ++n) net.operate(1.0 / 60.0);
  } catch (const BlowUp& e) {
    FAIL() << "projective dynamics must not blow up on the fabric at dt = 1/60 s: " << e.what() << " " << seedText();
  }
  EXPECT_GT(lowestPoint(net), -1.6) << "the fabric (1 m, 10 % stretch limit) cannot hang lower than about 1.5 m " << seedText();
  EXPECT_EQ(net.stats.factorizations, 1) << "the global matrix depends on the model only: factor it once";
  EXPECT_EQ(net.stats.backSubstitutions, net.stats.solverIterations) << "one back-substitution per iteration";
}

TEST_F(ProjectiveDynamics, ConservesMomentumOfAFreeNet) {
  // No pins, gravity or wind: the springs alone cannot change the momentum.
  NetParameters p = quietNet(integer(4, 8));
  p.particleMass = uniform(0.05, 0.5);
  Net net(3, p);
  net.setIntegrator(projective(integer(1, 8)));
  for (int i = 0; i < net.numOfMasses(); ++i) {
    net.state.pos[i] += vec3(-0.05, 0.05);
    net.state.vel[i] = vec3(-1, 1);
  }
  const Vec3 before = net.momentum();
  for (int n = 0; n < 30; ++n) net.operate(0.02);
  EXPECT_LT((net.momentum() - before).norm(), 1e-8 * (1 + before.norm()))
      << "projective dynamics changed the momentum of a free net by " << (net.momentum() - before).norm()
      << " kg m/s: each spring's k A^T d must push its ends equally and oppositely " << seedText();
}

}  // namespace
}  // namespace springlab::net
