// Energies, momentum, the stiffness estimate and the blow-up check.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <memory>


#include "test_systems.hpp"

namespace springlab {
namespace {

using testing::AnchoredOscillators;

// The message of the BlowUp one step of dt must throw; a failure (and "") when none comes.
std::string blowUpMessage(Simulation& sim, double dt) {
  try {
    sim.operate(dt);
  } catch (const BlowUp& e) {
    return e.what();
  }
  ADD_FAILURE() << "the step should have stopped the run with a BlowUp";
  return "";
}

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
  sim.editModel([](Simulation& model) { model.editSprings().push_back(Spring{0, 1, 40.0, 1.0, 0.0}); });
  EXPECT_DOUBLE_EQ(sim.energies().elastic, 0.5 * 40.0 * 0.25);
}

TEST(Diagnostics, GershgorinBoundOfAUniformChainIs2SqrtKOverM) {
  AnchoredOscillators sim(50, 0.05, 1.0);
  sim.editModel([](Simulation& model) {
    for (int i = 0; i + 1 < 50; ++i) model.editSprings().push_back(Spring{i, i + 1, 10000.0, 0.05, 0.0});
  });
  EXPECT_NEAR(springGershgorinBound(sim), 2 * std::sqrt(10000.0 / 0.05), 1e-9);
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
  sim.editModel([](Simulation& model) { model.editSprings().push_back(Spring{0, 1, 20000.0, 1.0, 0.0}); });
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

// The viewer hands the blow-up check the limit its worker computed (setKnownStepLimit): the
// message then computes no limit of its own on the viewer's thread, not even the one where
// the run was stopped, and says so.
TEST(BlowUpCheck, ALimitComputedElsewhereIsNotComputedAgainWhereTheRunStopped) {
  AnchoredOscillators sim(1, 1.0, 1.0);  // w = 1 rad/s: symplectic Euler's limit is 2 s
  sim.setKnownStepLimit(1000.0);        // as if the worker had found 1000 s
  std::string what;
  for (int n = 0; n < 1000 && what.empty(); ++n) {
    try {
      sim.operate(2.5);
    } catch (const BlowUp& e) {
      what = e.what();
    }
  }
  ASSERT_FALSE(what.empty()) << "2.5 s is past the oscillator's limit of 2 s";
  EXPECT_NE(what.find("below the stability limit"), std::string::npos) << what;
  EXPECT_NE(what.find("(1000 s)"), std::string::npos) << what;
  EXPECT_NE(what.find("not computed here"), std::string::npos) << what;
}

// Two masses with a spring list and a force made of named terms, one of which may be planted
// non-finite: the blow-up check must name the mass and the term, not dt.
class PlantedForces final : public Simulation {
 public:
  enum class Plant { kNone, kOwnForce, kSpringDirection };
  explicit PlantedForces(Plant p) : Simulation(3), plant(p) {
    masses = {Mass{1.0, false}, Mass{1.0, false}, Mass{1.0, false}};
    state.pos = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(p == Plant::kSpringDirection ? 1.0 : 2.0, 0, 0)};
    state.vel.assign(3, Vec3::Zero());
    editSprings() = {Spring{0, 1, 10.0, 1.0, 0.0}, Spring{1, 2, 10.0, 1.0, 0.0}};
    gravitation = Vec3(0, -9.81, 0);
    markInitialState();
  }
  Plant plant;
  std::string kind() const override { return "planted system"; }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    // A "spring" term that is not Lab 1's spring force: k times the unit vector between the
    // ends, 0/0 when they coincide.
    for (const Spring& sp : springs()) {
      const Vec3 d = s.pos[sp.mass2] - s.pos[sp.mass1];
      const Vec3 pull = sp.springConstant * 1e-3 * d / d.norm();
      f[sp.mass1] += pull;
      f[sp.mass2] -= pull;
    }
    for (int i = 0; i < numOfMasses(); ++i) f[i] += masses[i].m * gravitation;
    // The lab's own term: a normal never zeroed, on mass 1.
    if (plant == Plant::kOwnForce) f[1] += Vec3(NAN, 0, 0);
  }
};

TEST(BlowUpCheck, ANonFiniteForceIsNamedNotBlamedOnDt) {
  PlantedForces sim(PlantedForces::Plant::kOwnForce);
  const std::string what = blowUpMessage(sim, 0.005);
  EXPECT_NE(what.find("the force on mass 1"), std::string::npos) << what;
  EXPECT_NE(what.find("before the state did"), std::string::npos) << what;
  EXPECT_NE(what.find("planted system's own forces"), std::string::npos) << what;
  EXPECT_NE(what.find("dt is not the cause"), std::string::npos) << what;
  EXPECT_EQ(what.find("too large"), std::string::npos) << what;
  EXPECT_EQ(sim.stats.forceEvaluations, 1) << "the diagnosis must not count as the run's force evaluations";
}

TEST(BlowUpCheck, ANonFiniteSpringForceNamesTheSpring) {
  PlantedForces sim(PlantedForces::Plant::kSpringDirection);  // masses 1 and 2 coincide
  const std::string what = blowUpMessage(sim, 0.005);
  EXPECT_NE(what.find("the force on mass 1"), std::string::npos) << what;
  EXPECT_NE(what.find("from the spring forces"), std::string::npos) << what;
  EXPECT_NE(what.find("spring 1 (masses 1-2) has both ends at one point"), std::string::npos) << what;
  // The diagnosis leaves the model as it was.
  EXPECT_EQ(sim.springs()[0].springConstant, 10.0);
  EXPECT_EQ(sim.gravitation, Vec3(0, -9.81, 0));
}

// ---- detector 5's measure: motion that reverses every step ---------------------------------------
// The oracle is the definition: a velocity that flips sign every step with amplitude A has
// second difference 4 A; a smooth motion (constant acceleration a) has a dt^2, and a single
// impact is not held over the window.
TEST(StepReversal, AVelocityThatFlipsEveryStepIsHeldAtItsAmplitude) {
  StepReversal reversal;
  const double amplitude = 0.3, dt = 1e-3;
  double held = 0.0;
  for (int k = 0; k < StepReversal::kWindow + 2; ++k) {
    // mass 0 drifts smoothly under gravity, mass 1 flips about that drift
    const double drift = -9.81 * dt * k;
    held = reversal.record({Vec3(0, drift, 0), Vec3(0, drift + (k % 2 == 0 ? amplitude : -amplitude), 0)});
  }
  EXPECT_NEAR(held, amplitude, 1e-12);
  EXPECT_EQ(reversal.lastMass(), 1);
}

TEST(StepReversal, SmoothMotionAndAnImpactAreNotHeld) {
  StepReversal reversal;
  const double dt = 1e-3;
  double held = 0.0;
  for (int k = 0; k < 3 * StepReversal::kWindow; ++k) {
    // uniform acceleration: a zero second difference; one impact (a velocity turned at step 40)
    double v = -9.81 * dt * k;
    if (k >= 40) v = -v;
    held = std::max(held, reversal.record({Vec3(0, v, 0)}));
  }
  EXPECT_LT(held, 1e-12);
}

// A stable mode near its limit turns back every step while it decays (radius 0.999 a step: a
// hundred times slower than the window): not held.
TEST(StepReversal, AFlipThatDiesOutIsNotHeld) {
  StepReversal reversal;
  double held = 0.0, amplitude = 1.0;
  for (int k = 0; k < 4 * StepReversal::kWindow; ++k, amplitude *= 0.999) {
    held = std::max(held, reversal.record({Vec3(k % 2 == 0 ? amplitude : -amplitude, 0, 0)}));
  }
  EXPECT_EQ(held, 0.0);
}

TEST(StepReversal, RestartForgetsTheWindow) {
  StepReversal reversal;
  for (int k = 0; k < StepReversal::kWindow + 2; ++k) reversal.record({Vec3(k % 2 == 0 ? 1.0 : -1.0, 0, 0)});
  reversal.restart();
  EXPECT_EQ(reversal.record({Vec3(1, 0, 0)}), 0.0);
}

}  // namespace
}  // namespace springlab
