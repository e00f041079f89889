// Energies, momentum, the stiffness estimate and the blow-up check.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/symplectic_euler.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

using testing::AnchoredOscillators;

TEST(Diagnostics, KineticAndGravitationalEnergyAndMomentum) {
  AnchoredOscillators sim(2, 2.0, 1.0);
  sim.gravitation = Vec3(0, -10, 0);
  sim.state.pos = {Vec3(0, 3, 0), Vec3(0, -1, 0)};
  sim.state.vel = {Vec3(1, 0, 0), Vec3(0, 2, 0)};
  const Energies e = sim.energies();
  EXPECT_DOUBLE_EQ(e.kinetic, 0.5 * 2 * 1 + 0.5 * 2 * 4);
  EXPECT_DOUBLE_EQ(e.gravitational, 2 * 10 * 3 + 2 * 10 * -1);
  EXPECT_EQ(sim.momentum(), Vec3(2, 4, 0));
}

TEST(Diagnostics, ElasticEnergyIsHalfKStretchSquared) {
  AnchoredOscillators sim(2, 1.0, 1.0);
  sim.state.pos = {Vec3(0, 0, 0), Vec3(1.5, 0, 0)};
  sim.springs.push_back(Spring{0, 1, 40.0, 1.0, 0.0});
  EXPECT_DOUBLE_EQ(sim.energies().elastic, 0.5 * 40.0 * 0.25);
}

TEST(Diagnostics, GershgorinBoundOfAUniformChainIs2SqrtKOverM) {
  AnchoredOscillators sim(50, 0.05, 1.0);
  for (int i = 0; i + 1 < 50; ++i) sim.springs.push_back(Spring{i, i + 1, 10000.0, 0.05, 0.0});
  EXPECT_NEAR(springGershgorinBound(sim), 2 * std::sqrt(10000.0 / 0.05), 1e-9);
  EXPECT_NEAR(predictedStableDt(SymplecticEuler{}, springGershgorinBound(sim)), 2.0 / (2 * std::sqrt(2e5)), 1e-12);
}

TEST(BlowUpCheck, NonFiniteStateStopsTheRunNamingTheMass) {
  AnchoredOscillators sim(3, 1.0, 1.0);
  sim.state.pos[2].y() = NAN;
  try {
    sim.operate(0.01);
    FAIL() << "a NaN position must stop the run";
  } catch (const BlowUp& e) {
    EXPECT_NE(std::string(e.what()).find("mass 2"), std::string::npos) << e.what();
  }
}

TEST(BlowUpCheck, QuietOnADampedStableRun) {
  AnchoredOscillators sim(5, 1.0, 100.0, 0.5);
  sim.gravitation = Vec3(0, -9.81, 0);
  EXPECT_NO_THROW(for (int n = 0; n < 10000; ++n) sim.operate(0.01));
}

TEST(BlowUpCheck, EnergyTheUserPutsInIsNotABlowUp) {
  // Dragging a mass 10 m away stores 10^6 J in a stiff spring: the user did it, not dt.
  AnchoredOscillators sim(2, 1.0, 1.0);
  sim.springs.push_back(Spring{0, 1, 20000.0, 1.0, 0.0});
  sim.togglePinned(0);
  EXPECT_NO_THROW({
    sim.grab(1, Vec3(11.0, 0, 0));
    sim.operate(1e-4);
  });
  EXPECT_GT(sim.energies().elastic, 100 * 1.5);
}

TEST(BlowUpCheck, CanBeTurnedOffToWatchAMethodFail) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  sim.setBlowUpCheck(false);
  EXPECT_NO_THROW(for (int n = 0; n < 100; ++n) sim.operate(2.5));
  EXPECT_GT(sim.state.pos[0].norm(), 1e3);
}

}  // namespace
}  // namespace springlab
