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
using springlab::testing::quietNet;

std::unique_ptr<Integrator> projective(int iterations) {
  std::unique_ptr<Integrator> integrator = netRegistry().makeIntegrator("projective_dynamics");
  integrator->setOption("iterations", iterations);
  return integrator;
}

double lowestPoint(const Simulation& sim) {
  double y = INFINITY;
  for (const Vec3& x : sim.state.pos) y = std::min(y, x.y());
  return y;
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
  NetParameters p = springlab::testing::thesisCloth();
  p.resolution = integer(5, 8);
  p.airFriction = 2.0;
  Net net(3, p), reference(3, p);
  net.setIntegrator(projective(integer(10, 20)));
  reference.setIntegrator(netRegistry().makeIntegrator("implicit_euler"));
  for (int n = 0; n < 900; ++n) {
    net.operate(1.0 / 60.0);
    reference.operate(1.0 / 60.0);
  }
  State still = net.state;
  for (Vec3& v : still.vel) v.setZero();
  std::vector<Vec3> f;
  net.evaluateForces(still, f);
  double worst = 0.0;
  for (int i = 0; i < net.numOfMasses(); ++i) {
    if (net.inverseMass(i) != 0.0) worst = std::max(worst, f[i].norm() / (net.masses[i].m * 9.81));
  }
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
  // The light fabric of scenes/net_hanging.json (0.2 kg/m^2, k = 400/40/2 N/m, 10 % stretch
  // limit), held at two corners, without its colliders.
  NetParameters p = quietNet(integer(12, 16));
  p.massModel = MassModel::Density;
  p.arealDensity = 0.2;
  p.springs[SpringKind::Structural] = {true, 400.0, 0.3};
  p.springs[SpringKind::Shear] = {true, 40.0, 0.1};
  p.springs[SpringKind::Bend] = {true, 2.0, 0.02};
  p.pins = {Pin::Corner00, Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  p.airFriction = 0.05;
  p.stretchLimiting = true;
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
