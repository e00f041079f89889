// The Simulation base and the framework's symplectic Euler, on oscillators with exact answers.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include <springlab/symplectic_euler.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

using testing::AnchoredOscillators;

TEST(SymplecticEuler, EnergyStaysBoundedOnUndampedOscillator) {
  // w dt = 0.5: the energy oscillates between about (1 - w dt/2) and 1/(1 - w dt/2) of its
  // start (the modified energy is conserved) but never drifts.
  AnchoredOscillators sim(1, 1.0, 4.0);
  const double e0 = sim.energies().total();
  double lo = e0, hi = e0;
  for (int n = 0; n < 100000; ++n) {
    sim.operate(0.25);
    lo = std::min(lo, sim.energies().total());
    hi = std::max(hi, sim.energies().total());
  }
  const double y = 0.5;
  EXPECT_LT(hi / e0, 1.001 / (1.0 - y / 2)) << "symplectic Euler's energy rose beyond its bounded oscillation";
  EXPECT_GT(lo / e0, 0.999 * (1.0 - y / 2)) << "symplectic Euler's energy fell beyond its bounded oscillation";
}

TEST(SymplecticEuler, StableJustBelowWdt2) {
  AnchoredOscillators sim(1, 1.0, 1.0);  // w = 1 rad/s
  for (int n = 0; n < 20000; ++n) sim.operate(1.99);
  EXPECT_LT(sim.state.pos[0].norm(), 20.0) << "symplectic Euler must stay bounded at w dt = 1.99";
}

TEST(SymplecticEuler, BlowsUpJustAboveWdt2AndSaysWhy) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  try {
    for (int n = 0; n < 20000; ++n) sim.operate(2.01);
    FAIL() << "symplectic Euler at w dt = 2.01 must blow up and be reported";
  } catch (const BlowUp& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("symplectic_euler"), std::string::npos) << what;
    EXPECT_NE(what.find("too large"), std::string::npos) << what;
    // The limit of the linearised step, 2 / w_max = 2 s to the bisection's 0.2 %.
    EXPECT_NE(what.find("stable only below dt = 1.99"), std::string::npos) << "the safe dt 2 s must be named: " << what;
  }
}

// A limit computed elsewhere (the viewer's worker, on a copy) names the cause without being
// computed again; a new method or an edited model forgets it.
TEST(SymplecticEuler, BlowUpMessageTakesAKnownLimitUntilTheMethodOrModelChanges) {
  auto messageAt = [](AnchoredOscillators& sim) {
    try {
      for (int n = 0; n < 20000; ++n) sim.operate(2.01);
    } catch (const BlowUp& e) {
      return std::string(e.what());
    }
    return std::string("no blow-up");
  };
  AnchoredOscillators sim(1, 1.0, 1.0);
  sim.setKnownStepLimit(1.5);
  EXPECT_EQ(sim.knownStepLimit(), std::optional<double>(1.5));
  EXPECT_NE(messageAt(sim).find("stable only below dt = 1.5 s"), std::string::npos) << messageAt(sim);

  AnchoredOscillators changedMethod(1, 1.0, 1.0);
  changedMethod.setKnownStepLimit(1.5);
  changedMethod.setIntegrator(std::make_unique<SymplecticEuler>());
  EXPECT_FALSE(changedMethod.knownStepLimit());
  EXPECT_NE(messageAt(changedMethod).find("stable only below dt = 1.99"), std::string::npos);

  AnchoredOscillators edited(1, 1.0, 1.0);
  edited.setKnownStepLimit(1.5);
  edited.editModel([](Simulation&) {});
  EXPECT_FALSE(edited.knownStepLimit());
}

TEST(SymplecticEuler, ConvergesAtFirstOrder) {
  auto errorAt1s = [](double dt) {
    AnchoredOscillators sim(1, 1.0, 4.0);
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    for (int n = 0; n < steps; ++n) sim.operate(dt);
    return std::abs(sim.state.pos[0].x() - std::cos(2.0));
  };
  EXPECT_NEAR(std::log2(errorAt1s(0.001) / errorAt1s(0.0005)), 1.0, 0.15);
}

TEST(Simulation, CountsOneForceEvaluationPerSymplecticStep) {
  AnchoredOscillators sim(3, 1.0, 1.0);
  for (int n = 0; n < 10; ++n) sim.operate(0.01);
  EXPECT_EQ(sim.stats.steps, 10);
  EXPECT_EQ(sim.stats.forceEvaluations, 10);
}

TEST(Simulation, PinnedMassNeverMoves) {
  AnchoredOscillators sim(2, 1.0, 1.0);
  sim.gravitation = Vec3(0, -9.81, 0);
  sim.togglePinned(1);
  const Vec3 start = sim.state.pos[1];
  for (int n = 0; n < 1000; ++n) sim.operate(0.01);
  EXPECT_EQ(sim.state.pos[1], start) << "a pinned mass moved";
  EXPECT_NE(sim.state.pos[0], start) << "the free mass should have moved";
}

TEST(Simulation, ResetRestoresTheInitialState) {
  AnchoredOscillators sim(2, 1.0, 1.0);
  const State start = sim.state;
  for (int n = 0; n < 100; ++n) sim.operate(0.01);
  sim.reset();
  EXPECT_EQ(sim.state.pos, start.pos);
  EXPECT_EQ(sim.state.vel, start.vel);
  EXPECT_EQ(sim.state.time, 0.0);
  EXPECT_EQ(sim.stats.steps, 0);
}

TEST(Simulation, GrabbedMassFollowsTheTarget) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  sim.grab(0, Vec3(0.5, 0.5, 0));
  sim.operate(0.01);
  EXPECT_EQ(sim.state.pos[0], Vec3(0.5, 0.5, 0));
  sim.release();
  sim.operate(0.01);
  EXPECT_NE(sim.state.pos[0], Vec3(0.5, 0.5, 0)) << "a released mass must move again";
}

TEST(Simulation, PlanarSystemStaysExactlyPlanar) {
  AnchoredOscillators sim(4, 1.0, 3.0, 0.1, 2);
  sim.gravitation = Vec3(0.3, -9.81, 0);
  for (int n = 0; n < 1000; ++n) sim.operate(0.01);
  for (const Vec3& x : sim.state.pos) EXPECT_EQ(x.z(), 0.0);
}

TEST(Simulation, ForceJacobianOfASceneWithoutOneNamesSceneAndIntegrator) {
  // A scene that does not linearise its forces: implicit integrators get a clear error.
  AnchoredOscillators sim(2, 1.0, 3.0);
  ForceJacobian J;
  J.pairs.push_back({0, 1, Mat3::Identity(), Mat3::Identity()});
  try {
    sim.forceJacobian(sim.state, J, "implicit_euler");
    FAIL() << "forceJacobian must throw for a scene without addForceJacobian";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("implicit_euler"), std::string::npos) << what;
    EXPECT_NE(what.find("anchored oscillators"), std::string::npos) << what;
  }
  EXPECT_TRUE(J.pairs.empty()) << "forceJacobian starts from an empty J";
}

// Symplectic Euler that counts how often its history is forgotten.
class ResetCountingEuler final : public Integrator {
 public:
  explicit ResetCountingEuler(int& resets) : resets_(resets) {}
  std::string name() const override { return "reset_counting_euler"; }
  int order() const override { return 1; }
  double stabilityConstant() const override { return 2.0; }
  void reset() override { ++resets_; }
  void step(Simulation& sim, double dt) override { euler_.step(sim, dt); }

 private:
  SymplecticEuler euler_;
  int& resets_;
};

TEST(ModelEdit, ForgetsTheIntegratorsHistory) {
  // History such as Verlet's previous positions belongs to the model it was made with.
  AnchoredOscillators sim(2, 1.0, 1.0);
  int resets = 0;
  sim.setIntegrator(std::make_unique<ResetCountingEuler>(resets));
  sim.operate(0.01);
  const int before = resets;
  sim.editModel([](Simulation& model) { model.gravitation = Vec3(0, -9.81, 0); });
  EXPECT_EQ(resets, before + 1) << "editModel must reset the integrator";
  EXPECT_EQ(sim.gravitation, Vec3(0, -9.81, 0)) << "editModel must apply the edit";
  sim.togglePinned(0);
  EXPECT_EQ(resets, before + 2) << "pinning is a model edit and must reset the integrator";
}

TEST(ModelEdit, StiffeningThroughEditModelIsNotABlowUp) {
  // 1 kg at 1 m on a 1 N/m anchor holds 0.5 J. Made 10^4 times stiffer it holds 5000 J: far
  // beyond the energy scale the blow-up check measured at the start, unless it is re-armed.
  const double dt = 0.001;  // w dt = 0.1: stable at either stiffness
  AnchoredOscillators direct(1, 1.0, 1.0);
  direct.stiffness = 1.0e4;
  EXPECT_THROW(direct.operate(dt), BlowUp) << "without editModel the check takes the new energy for a blow-up";

  AnchoredOscillators edited(1, 1.0, 1.0);
  edited.editModel([&](Simulation&) { edited.stiffness = 1.0e4; });
  EXPECT_NO_THROW(for (int n = 0; n < 1000; ++n) edited.operate(dt)) << "editModel must re-arm the blow-up check";
}

TEST(ModelEdit, ParameterSetterChangesTheModelAndGetterReadsItBack) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  int resets = 0;
  sim.setIntegrator(std::make_unique<ResetCountingEuler>(resets));
  const int before = resets;
  const std::vector<Parameter> parameters = sim.parameters();
  ASSERT_EQ(parameters.size(), 2u);
  parameters[0].set(9.0);
  parameters[1].set(-3.0);
  EXPECT_EQ(sim.stiffness, 9.0) << "the stiffness slider must write the system's stiffness";
  EXPECT_EQ(sim.gravitation.y(), -3.0) << "the gravity slider must write gravitation";
  EXPECT_EQ(parameters[0].get(), 9.0);
  EXPECT_EQ(parameters[1].get(), -3.0);
  EXPECT_EQ(resets, before + 2) << "each set() must be a model edit (editModel resets the integrator)";
  // The new stiffness acts: w = sqrt(9 / 1) = 3 rad/s, so x(t) = cos(3 t).
  for (int n = 0; n < 1000; ++n) sim.operate(1e-4);
  EXPECT_NEAR(sim.state.pos[0].x(), std::cos(0.3), 1e-3) << "the oscillator must swing at the edited stiffness";
}

TEST(ModelEdit, EditThatAddsMassesWithoutStateIsRefused) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  EXPECT_THROW(sim.editModel([](Simulation& model) { model.masses.push_back(Mass{}); }), std::logic_error);
}

TEST(ModelEdit, SpringsChangeOnlyInsideEditModel) {
  // The springs have one writer, so whatever a lab derives from them follows every change.
  AnchoredOscillators sim(2, 1.0, 1.0);
  EXPECT_THROW(sim.editSprings(), std::logic_error) << "springs must not be writable outside editModel";
  sim.editModel([](Simulation& model) { model.editSprings().push_back(Spring{0, 1, 40.0, 1.0, 0.0}); });
  ASSERT_EQ(sim.springs().size(), 1u) << "editModel must let the edit change the springs";
  EXPECT_THROW(sim.editSprings(), std::logic_error) << "springs must not stay writable after editModel";
}

TEST(Simulation, RejectsDimensionOtherThan2Or3) {
  EXPECT_THROW(AnchoredOscillators(1, 1.0, 1.0, 0.0, 4), std::invalid_argument);
}

}  // namespace
}  // namespace springlab
