// Exercises 3.4 and 3.5: the gas, its pressure force, pumping it in and its energy.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <springlab/symplectic_euler.hpp>

#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::quietBody;

class Pressure : public springlab::testing::Seeded {};

// ---- 3.4 ---------------------------------------------------------------------------------

TEST_F(Pressure, TimesVolumeIsNRT) {
  for (int t = 0; t < 100; ++t) {
    const double nRT = uniform(0.1, 1e4), v = uniform(1e-3, 10);
    ASSERT_NEAR(gasPressure(nRT, v) * v, nRT, 1e-9 * nRT) << "Boyle's law: P V = nRT " << seedText();
  }
  EXPECT_EQ(gasPressure(100.0, 0.0), 0.0) << "a body without volume holds no pressure (and no infinity)";
  EXPECT_EQ(gasPressure(100.0, -1.0), 0.0) << "a body turned inside out holds no pressure";
}

TEST_F(Pressure, ForceAndTorqueSumToZeroOnAClosedBody) {
  // Pressure is internal: a closed body cannot push itself along or spin itself up.
  std::mt19937_64 rng(static_cast<unsigned>(integer(0, 1 << 30)));
  for (int t = 0; t < 20; ++t) {
    const SurfaceMesh m = springlab::testing::lumpySphere(integer(0, 2), uniform(0.2, 2), 0.3, vec3(-5, 5), rng);
    std::vector<Vec3> f(m.vertices.size(), Vec3::Zero());
    const double P = uniform(1, 1000);
    addPressureForces(m.vertices, m.triangles, {}, P, f);
    Vec3 total = Vec3::Zero(), torque = Vec3::Zero();
    double size = 0.0;
    for (size_t i = 0; i < f.size(); ++i) {
      total += f[i];
      torque += m.vertices[i].cross(f[i]);
      size += f[i].norm();
    }
    ASSERT_GT(size, 0.0) << "pressure exerts no force at all " << seedText();
    ASSERT_LT(total.norm(), 1e-9 * size) << "the pressure forces on a closed body do not sum to zero: it would "
                                            "propel itself " << seedText();
    ASSERT_LT(torque.norm(), 1e-8 * size * (1 + m.vertices[0].norm()))
        << "the pressure forces on a closed body have a net torque: it would spin itself up " << seedText();
  }
  // The 2D ring too.
  SurfaceMesh ring = ringMesh(integer(3, 40), uniform(0.5, 3));
  for (Vec3& v : ring.vertices) v += Vec3(uniform(-1, 1), uniform(-1, 1), 0.0) * 0.1;
  std::vector<Vec3> f(ring.vertices.size(), Vec3::Zero());
  addPressureForces(ring.vertices, {}, ring.segments, 10.0, f);
  Vec3 total = Vec3::Zero();
  for (const Vec3& x : f) total += x;
  EXPECT_LT(total.norm(), 1e-9) << "the pressure forces on a closed 2D loop do not sum to zero " << seedText();
}

TEST_F(Pressure, PushesASphereOutwardWithPTimesItsArea) {
  // On a sphere every force points out along the radius; their sizes add up to P times the
  // surface area (sum of face areas).
  const SurfaceMesh m = icosphere(1.5, 2);
  const double P = uniform(10, 100);
  std::vector<Vec3> f(m.vertices.size(), Vec3::Zero());
  addPressureForces(m.vertices, m.triangles, {}, P, f);
  double area = 0.0, radial = 0.0;
  for (const Triangle& t : m.triangles) {
    area += 0.5 * (m.vertices[t.b] - m.vertices[t.a]).cross(m.vertices[t.c] - m.vertices[t.a]).norm();
  }
  for (size_t i = 0; i < f.size(); ++i) {
    const Vec3 out = m.vertices[i].normalized();
    ASSERT_GT(f[i].dot(out), 0.0) << "pressure must push vertex " << i << " outward " << seedText();
    radial += f[i].dot(out);
  }
  EXPECT_NEAR(radial, P * area, 0.02 * P * area) << "the outward forces must add up to P times the area";
}

// Radius of a regular n-gon ring of rest radius r0 at which spring tension balances the gas:
// 2 k (l - l0) sin(pi/n) = P l cos(pi/n), l = 2 r sin(pi/n), P = nRT / ((n/2) r^2 sin(2 pi/n)).
double ringEquilibriumRadius(int n, double r0, double k, double nRT) {
  const double s = std::sin(std::numbers::pi / n), c = std::cos(std::numbers::pi / n);
  auto imbalance = [&](double r) {
    const double l = 2 * r * s, l0 = 2 * r0 * s;
    const double P = nRT / (0.5 * n * r * r * std::sin(2 * std::numbers::pi / n));
    return 2 * k * (l - l0) * s - P * l * c;
  };
  double lo = r0, hi = 10 * r0;  // inward pull grows with r, pressure falls: one root
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (imbalance(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(RingEquilibrium, RadiusMatchesTheBalanceOfTensionAndPressure) {
  // The chapter's ring (17 points, radius 30, k = 400, kd = 15, m = 4 each) in zero gravity,
  // pumped up over 2 s (200 steps) and left to settle.
  const int n = 17;
  const double r0 = 30.0, k = 400.0, nRT = 2.0e5;
  SoftBodyParameters p = quietBody(ringMesh(n, r0), 4.0 * n, k, 15.0);
  p.gas = nRT;
  p.inflationTime = 2.0;
  SoftBody ring(2, p);
  for (int step = 0; step < 4000; ++step) ring.operate(0.01);

  Vec3 centroid = Vec3::Zero();
  for (const Vec3& x : ring.state.pos) centroid += x / n;
  double meanRadius = 0.0, spread = 0.0;
  for (const Vec3& x : ring.state.pos) meanRadius += (x - centroid).norm() / n;
  for (const Vec3& x : ring.state.pos) spread = std::max(spread, std::abs((x - centroid).norm() - meanRadius));
  const double expected = ringEquilibriumRadius(n, r0, k, nRT);
  ASSERT_GT(expected, 1.1 * r0) << "test setup: the gas should stretch the ring noticeably";
  EXPECT_NEAR(meanRadius, expected, 1e-3 * expected)
      << "the ring settles where spring tension balances pressure, radius " << expected << " (rest radius " << r0
      << ")";
  EXPECT_LT(spread, 1e-3 * expected) << "the inflated ring should be round";
  for (const Vec3& x : ring.state.pos) EXPECT_EQ(x.z(), 0.0) << "a 2D ring must stay exactly in its plane";
}

// ---- 3.5 ---------------------------------------------------------------------------------

TEST(Inflation, RisesLinearlyInTimeToTheTargetAndStays) {
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 0.0, 2.0), 0.0) << "the pump starts from no gas";
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 0.02, 2.0), 5.0) << "1 % of the pumping time pumps 1 % of the gas";
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 1.0, 2.0), 250.0) << "half way, half the gas";
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 2.0, 2.0), 500.0) << "after the pumping time, the target";
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 200.0, 2.0), 500.0) << "the gas must stop at the target";
  EXPECT_DOUBLE_EQ(inflatedGas(500.0, 0.0, 0.0), 500.0) << "with no inflation time the gas is there at once";
}

TEST(Inflation, GasEnergyDecreasesAsPressureDoesWork) {
  // -dU/dV = P: compare a central difference of the energy with the pressure.
  const double nRT = 300.0, V0 = 2.0;
  EXPECT_NEAR(gasEnergy(nRT, V0, V0), 0.0, 1e-12) << "the gas's energy is zero at the rest volume";
  for (double v : {0.5, 1.0, 2.0, 3.5}) {
    const double h = 1e-6;
    const double slope = (gasEnergy(nRT, v + h, V0) - gasEnergy(nRT, v - h, V0)) / (2 * h);
    EXPECT_NEAR(-slope, gasPressure(nRT, v), 1e-5 * gasPressure(nRT, v))
        << "-dU/dV must equal the pressure nRT / V at V = " << v;
  }
}

// A ball of `sub` subdivisions, radius 0.5 m, 1 kg, gas at full pressure from the start.
SoftBodyParameters pressurisedBall(int sub, double k, double kd, double nRT) {
  SoftBodyParameters p = quietBody(icosphere(0.5, sub), 1.0, k, kd);
  p.gas = nRT;
  return p;
}

TEST(SoftBodyEnergy, IsConservedWithPressureAndNoDamping) {
  // The ball starts at its rest shape with the gas in: it breathes in and out. Kinetic +
  // elastic + gas energy must stay constant (symplectic Euler, small dt), which holds only
  // when the pressure force is exactly -dU/dx of U = -nRT ln(V/V0).
  SoftBody ball(3, pressurisedBall(1, 500.0, 0.0, 100.0));
  ball.setBlowUpCheck(false);
  const double e0 = ball.energies().total();
  double maxKinetic = 0.0, maxDrift = 0.0;
  for (int step = 0; step < 4000; ++step) {
    ball.operate(1e-4);
    const Energies e = ball.energies();
    maxKinetic = std::max(maxKinetic, e.kinetic);
    maxDrift = std::max(maxDrift, std::abs(e.total() - e0));
  }
  ASSERT_GT(maxKinetic, 1.0) << "test setup: the gas should set the ball breathing";
  EXPECT_LT(maxDrift, 0.02 * maxKinetic) << "kinetic + elastic + gas energy drifts by " << maxDrift
                                         << " J while the ball breathes with up to " << maxKinetic
                                         << " J of kinetic energy: the gas energy and the pressure force disagree";
}

TEST(SoftBodyEnergy, BlowUpCheckStaysQuietWhileAStiffBallIsPumpedUp) {
  // A light ball in zero gravity pumped to a high pressure stores far more energy than it
  // started with; the blow-up check must count the gas and not call that a blow-up.
  SoftBodyParameters p = pressurisedBall(2, 2000.0, 0.5, 400.0);
  p.totalMass = 0.05;
  // Pumped over 100 steps of half the stable step (the stiffness does not depend on the gas).
  const double dt = 0.5 * 2.0 / SoftBody(3, p).angularFrequencyBound();
  p.inflationTime = 100 * dt;
  SoftBody ball(3, p);
  EXPECT_NO_THROW(for (int step = 0; step < 3000; ++step) ball.operate(dt))
      << "a steadily pumped ball was taken for a blow-up";
  EXPECT_GT(ball.volume(ball.state), 1.1 * ball.restVolume()) << "test setup: the gas should have inflated the ball";
}

TEST(BoylesLaw, PressureTimesVolumeStaysConstantInASlowSqueeze) {
  // A ball between two plates that close slowly: the pressure rises as the volume falls, and
  // P V stays nRT (isothermal gas).
  SoftBodyParameters p = pressurisedBall(2, 3000.0, 0.5, 50.0);
  p.contactMethod = ContactMethod::Projection;
  p.contact = {0.0, 0.0, 0.0, 0.0};
  p.obstacles.push_back(springlab::testing::floorAt(-0.5));
  Obstacle lid = springlab::testing::floorAt(0.5);
  lid.normal = -Vec3::UnitY();
  p.obstacles.push_back(lid);
  SoftBody ball(3, p);
  auto pv = [&] { return ball.pressure(ball.state) * ball.volume(ball.state); };
  for (int step = 0; step < 2000; ++step) ball.operate(1e-3);  // settle at full pressure
  const double v0 = ball.volume(ball.state), p0 = ball.pressure(ball.state);
  const double dt = 1e-3, speed = 0.15;  // m/s, slow against the ball's vibrations
  for (int step = 0; step < 3000; ++step) {
    ball.obstacles()[1].center.y() -= speed * dt;
    ball.obstacles()[1].velocity = Vec3(0, -speed, 0);
    ball.operate(dt);
  }
  const double v1 = ball.volume(ball.state), p1 = ball.pressure(ball.state);
  ASSERT_LT(v1, 0.85 * v0) << "test setup: the plates should squeeze the ball";
  EXPECT_NEAR(p1 / p0, v0 / v1, 1e-9 * v0 / v1) << "Boyle's law: the pressure must rise as the volume falls";
  EXPECT_NEAR(pv(), 50.0, 1e-9 * 50.0) << "P V must stay nRT through the squeeze";
}

}  // namespace
}  // namespace springlab::softbody
