// PhaseProfile: where a step's time goes. Only relations between times are checked (an inner
// phase is charged to itself, not to the phase it interrupts; the phases add up to no more
// than the wall time), never a duration.
#include <gtest/gtest.h>

#include <chrono>

#include <springlab/phase_profile.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

using Clock = std::chrono::steady_clock;

// Keep the CPU busy for about `ms` milliseconds.
void busy(double ms) {
  const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
  volatile double x = 0.0;
  while (Clock::now() < end) x = x + 1.0;
}

TEST(PhaseProfile, AnInnerPhaseIsChargedToItselfNotToTheOneItInterrupts) {
  PhaseProfile profile;
  profile.setEnabled(true);
  const Clock::time_point start = Clock::now();
  {
    const PhaseProfile::Scope forces(profile, Phase::kForces);
    const PhaseProfile::Scope normals(profile, Phase::kNormals);
    busy(20.0);
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GT(profile.seconds(Phase::kNormals), 0.015);
  EXPECT_LT(profile.seconds(Phase::kForces), profile.seconds(Phase::kNormals))
      << "the forces phase held only the normals phase, so almost no time is its own";
  EXPECT_LE(profile.totalSeconds(), wall);
  EXPECT_DOUBLE_EQ(profile.totalSeconds(), profile.seconds(Phase::kForces) + profile.seconds(Phase::kNormals));
}

TEST(PhaseProfile, TimeOutsideEveryScopeIsNotCharged) {
  PhaseProfile profile;
  profile.setEnabled(true);
  { const PhaseProfile::Scope s(profile, Phase::kCollisions); }
  busy(10.0);  // between steps
  { const PhaseProfile::Scope s(profile, Phase::kCollisions); }
  EXPECT_LT(profile.totalSeconds(), 0.005);
}

TEST(PhaseProfile, OffByDefaultAndOnForASimulationsSteps) {
  testing::AnchoredOscillators sim(50, 1.0, 10.0, 0.1);
  for (int n = 0; n < 10; ++n) sim.operate(1e-3);
  EXPECT_EQ(sim.profile.totalSeconds(), 0.0) << "nothing is timed unless asked";

  sim.profile.setEnabled(true);
  const Clock::time_point start = Clock::now();
  for (int n = 0; n < 200; ++n) sim.operate(1e-3);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GT(sim.profile.seconds(Phase::kForces), 0.0);
  EXPECT_GT(sim.profile.seconds(Phase::kIntegration), 0.0);
  EXPECT_LE(sim.profile.totalSeconds(), wall);
  EXPECT_EQ(phaseName(Phase::kStretchLimit), "stretch limit");
}

}  // namespace
}  // namespace springlab
