// Exercise 3.5, pumping the gas in (labs/03_softbody/inflation.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/symplectic_euler.hpp>
#include "seeded.hpp"
#include <springlab/softbody/softbody.hpp>
#include "softbody_fixtures.hpp"

namespace springlab::softbody {
namespace {

using springlab::testing::quietBody;

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
