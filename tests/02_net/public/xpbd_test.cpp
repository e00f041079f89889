// Exercise 2.11: the XPBD distance constraint, and the framework's XPBD loop built on it.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using Xpbd = springlab::testing::Seeded;
using springlab::testing::netRegistry;
using springlab::testing::fabric;
using springlab::testing::hangingCloth;
using springlab::testing::largestForceOverWeight;
using springlab::testing::quietNet;
using springlab::testing::netIntegrator;
using springlab::testing::lowestPoint;

constexpr double kPi = 3.14159265358979323846;

// One mass m on one spring (k, L0, no damper) to a pinned mass at the origin, no gravity.
class MassOnConstraint final : public Simulation {
 public:
  MassOnConstraint(double m, double k, double L0) : Simulation(3) {
    masses = {Mass{m, true}, Mass{m, false}};
    editSprings() = {Spring{1, 0, k, L0, 0.0, SpringKind::Structural}};
    state.pos = {Vec3::Zero(), Vec3(L0, 0, 0)};
    state.vel = {Vec3::Zero(), Vec3::Zero()};
    markInitialState();
  }
  std::string kind() const override { return "mass on a constraint"; }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    const Spring& sp = springs()[0];
    f[1] += springDamperForce(s.pos[1], s.pos[0], s.vel[1], s.vel[0], sp.springConstant, sp.springLength, 0.0);
    f[1] += masses[1].m * gravitation;
  }
};

TEST_F(Xpbd, ProjectionWithoutComplianceRestoresTheRestLength) {
  for (int t = 0; t < 50; ++t) {
    const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1);
    const double L0 = uniform(0.1, 2), w1 = 1.0 / uniform(0.1, 2), w2 = t % 5 == 0 ? 0.0 : 1.0 / uniform(0.1, 2);
    const DistanceCorrection c = xpbdDistanceConstraint(x1, x2, x1, x2, w1, w2, L0, 0.0, 0.0, 0.0);
    const Vec3 y1 = x1 + c.dx1, y2 = x2 + c.dx2;
    ASSERT_NEAR((y1 - y2).norm(), L0, 1e-9 * L0)
        << "with no compliance (alpha = 0) one projection must bring the spring to its rest length " << seedText();
    const Vec3 e = (x1 - x2).normalized();
    ASSERT_LT(c.dx1.cross(e).norm() + c.dx2.cross(e).norm(), 1e-9) << "the ends move along the spring only " << seedText();
    if (w2 == 0.0) {
      ASSERT_EQ(c.dx2, Vec3::Zero()) << "a pinned end (w = 0) never moves " << seedText();
    } else {
      ASSERT_LT((c.dx1 / w1 + c.dx2 / w2).norm(), 1e-9)
          << "m1 dx1 + m2 dx2 must vanish (the correction keeps the centre of mass) " << seedText();
    }
    ASSERT_NEAR(c.dlambda, -((x1 - x2).norm() - L0) / (w1 + w2), 1e-9) << "dlambda = -C / (w1 + w2) when alpha = 0 " << seedText();
  }
  const DistanceCorrection none = xpbdDistanceConstraint(Vec3::Ones(), Vec3::Ones(), Vec3::Ones(), Vec3::Ones(), 1, 1, 1, 0, 0, 0);
  EXPECT_TRUE(none.dx1.allFinite() && none.dx2.allFinite() && std::isfinite(none.dlambda))
      << "a zero-length constraint has no direction: no correction, never NaN";
}

TEST_F(Xpbd, ComplianceOneOverKOscillatesAtTheSpringFrequency) {
  // alpha = 1/k: one mass on one constraint must swing like a spring of stiffness k, period
  // 2 pi sqrt(m/k), whatever the iteration count (the compliance fixes the stiffness).
  const double m = uniform(0.1, 2), k = uniform(50, 500), L0 = uniform(0.2, 1);
  const double period = 2 * kPi * std::sqrt(m / k), dt = period / 400;
  for (const int iterations : {1, 4}) {
    MassOnConstraint sim(m, k, L0);
    sim.setIntegrator(netIntegrator("xpbd", {{"iterations", iterations}}));
    sim.state.pos[1].x() = L0 * (1 + uniform(0.05, 0.2));
    // Upward crossings of the rest length over three periods: their spacing is the period.
    std::vector<double> crossings;
    double previous = sim.state.pos[1].x() - L0;
    for (int n = 0; n < 2000 && crossings.size() < 4; ++n) {
      sim.operate(dt);
      const double stretch = sim.state.pos[1].x() - L0;
      if (previous < 0 && stretch >= 0) crossings.push_back(sim.state.time - dt * stretch / (stretch - previous));
      previous = stretch;
    }
    ASSERT_EQ(crossings.size(), 4u) << "the mass must keep oscillating about the rest length (" << iterations
                                    << " iterations) " << seedText();
    const double measured = (crossings.back() - crossings.front()) / 3;
    EXPECT_NEAR(measured, period, 0.02 * period)
        << "with compliance 1/k and " << iterations << " iteration(s), the period must be 2 pi sqrt(m/k) = " << period
        << " s, measured " << measured << " s " << seedText();
  }
  // alpha -> 0: the constraint is inextensible, the length stays L0 however the mass swings.
  MassOnConstraint stiff(m, 1e12, L0);
  stiff.gravitation = Vec3(0, -9.81, 0);
  stiff.setIntegrator(netIntegrator("xpbd", {{"iterations", 1}}));
  stiff.setBlowUpCheck(false);
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    stiff.operate(0.01);
    worst = std::max(worst, std::abs((stiff.state.pos[1] - stiff.state.pos[0]).norm() - L0));
  }
  EXPECT_LT(worst, 1e-6 * L0) << "with compliance near 0 the pendulum's length must stay L0; it strayed by " << worst
                              << " m " << seedText();
  EXPECT_LT(stiff.state.pos[1].y(), -0.1 * L0) << "the pendulum must swing down under gravity " << seedText();
}

TEST_F(Xpbd, ReachesTheStaticDrapeOfTheForceModel) {
  // The same springs as a force model run to rest with implicit Euler; XPBD with compliance
  // 1/k and enough iterations must come to rest where the springs' forces balance gravity.
  const int r = integer(5, 8);
  Net reference(3, hangingCloth(r)), xpbd(3, hangingCloth(r));
  reference.setIntegrator(netRegistry().makeIntegrator("implicit_euler"));
  xpbd.setIntegrator(netIntegrator("xpbd", {{"iterations", 50}}));
  for (int n = 0; n < 900; ++n) {
    reference.operate(1.0 / 60.0);
    xpbd.operate(1.0 / 60.0);
  }
  const double residual = largestForceOverWeight(xpbd);

  // Not exactly zero: each projection moves along the gradient at its own iterate, so the
  // corrections of a step add up along slightly turned directions (1-2 % of the weight on this
  // cloth stretched to five times its size, whatever the iteration count).
  EXPECT_LT(residual, 0.05) << "XPBD's rest state must be the force model's equilibrium; a mass there still feels "
                            << 100 * residual << " % of its weight " << seedText();
  EXPECT_NEAR(lowestPoint(xpbd), lowestPoint(reference), 0.005 * std::abs(lowestPoint(reference)))
      << "XPBD's drape (lowest point) must be the force model's within 0.5 % " << seedText();
}

TEST_F(Xpbd, StableOnTheFabricAtASixtiethOfASecond) {
  Net net(3, fabric(integer(12, 16)));
  net.setIntegrator(netIntegrator("xpbd", {{"iterations", integer(1, 10)}}));
  try {
    for (int n = 0; n < 120; ++n) net.operate(1.0 / 60.0);
  } catch (const BlowUp& e) {
    FAIL() << "XPBD must not blow up on the fabric at dt = 1/60 s: " << e.what() << " " << seedText();
  }
  EXPECT_GT(lowestPoint(net), -1.6) << "the fabric (1 m, 10 % stretch limit) cannot hang lower than about 1.5 m " << seedText();
}

TEST_F(Xpbd, ConservesMomentumOfAFreeNet) {
  // No pins, gravity or wind: the constraints alone cannot change the momentum.
  NetParameters p = quietNet(integer(4, 8));
  p.particleMass = uniform(0.05, 0.5);
  Net net(3, p);
  net.setIntegrator(netIntegrator("xpbd", {{"iterations", integer(1, 8)}, {"substeps", integer(1, 3)}}));
  for (int i = 0; i < net.numOfMasses(); ++i) {
    net.state.pos[i] += vec3(-0.05, 0.05);
    net.state.vel[i] = vec3(-1, 1);
  }
  const Vec3 before = net.momentum();
  for (int n = 0; n < 30; ++n) net.operate(0.02);
  EXPECT_LT((net.momentum() - before).norm(), 1e-9 * (1 + before.norm()))
      << "XPBD changed the momentum of a free net by " << (net.momentum() - before).norm()
      << " kg m/s: each projection must move the ends by w1 dlambda e and -w2 dlambda e " << seedText();
  EXPECT_GT(net.stats.constraintProjections, 0) << "the loop counts its constraint projections";
}

}  // namespace
}  // namespace springlab::net
