// Exercise 1.4, explicit Euler step (labs/01_rope/explicit_euler.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/rope/rope.hpp>
#include "rope_oscillator.hpp"
#include "seeded.hpp"
#include "rope_fixtures.hpp"

namespace springlab::rope {
namespace {

using ExplicitEuler = springlab::testing::Seeded;
using springlab::testing::kOmega;
using springlab::testing::Method;
using springlab::testing::observedOrder;
using springlab::testing::run;
using springlab::testing::spring;
using springlab::testing::quietRope;
using RopeDynamics = springlab::testing::Seeded;

const Method explicitEuler = [](const PhasePoint& s, const Vec3&, bool, double dt) {
  return explicitEulerStep(s, spring(s.pos), dt);
};

TEST_F(ExplicitEuler, UpdatesFromTheOldState) {
  const PhasePoint s{vec3(-1, 1), vec3(-1, 1)};
  const Vec3 a = vec3(-10, 10);
  const double dt = uniform(0.001, 0.1);
  const PhasePoint next = explicitEulerStep(s, a, dt);
  EXPECT_LT((next.pos - (s.pos + s.vel * dt)).norm(), 1e-12)
      << "explicit Euler moves the position with the OLD velocity (the new one makes it symplectic Euler) "
      << seedText();
  EXPECT_LT((next.vel - (s.vel + a * dt)).norm(), 1e-12) << "explicit Euler: v' = v + a dt " << seedText();
}

TEST_F(ExplicitEuler, OscillatorEnergyGrowsBy1PlusWdtSquaredEachStep) {
  const double dt = uniform(0.01, 0.2);
  std::vector<double> e;
  run(explicitEuler, dt, 50, &e);
  const double gain = 1.0 + kOmega * kOmega * dt * dt;
  EXPECT_NEAR(e.back() / 0.5 / (kOmega * kOmega), std::pow(gain, 50), 1e-9 * std::pow(gain, 50))
      << "on an undamped oscillator explicit Euler multiplies the energy by exactly 1 + (w dt)^2 per step "
      << seedText();
}

TEST_F(ExplicitEuler, ConvergesAtFirstOrder) {
  EXPECT_NEAR(observedOrder(explicitEuler), 1.0, 0.15) << "halving dt must halve explicit Euler's error";
}

TEST_F(RopeDynamics, SymplecticEulerKeepsEnergyBoundedAndExplicitEulerGainsIt) {
  // An undamped mass on a spring at w dt = 0.2: energy oscillates within about +-w dt/2 with
  // symplectic Euler, and grows by (1 + (w dt)^2) per step with explicit Euler.
  auto energyAfter = [](const std::string& method) {
    Registry registry = springlab::testing::ropeRegistry();
    RopeParameters p = quietRope(2, 1.0, 100.0, 1.0, 0.0);
    Rope rope(3, p);
    rope.setIntegrator(registry.makeIntegrator(method));
    rope.setBlowUpCheck(false);
    rope.state.pos[1].x() += 0.1;
    const double e0 = rope.energies().total();
    double worst = 1.0;
    for (int n = 0; n < 2000; ++n) {
      rope.operate(0.02);
      worst = std::max(worst, rope.energies().total() / e0);
    }
    return std::pair{rope.energies().total() / e0, worst};  // final and largest E / E0
  };
  EXPECT_LT(energyAfter("symplectic_euler").second, 1.15)
      << "symplectic Euler's energy must stay bounded on an undamped spring";
  EXPECT_GT(energyAfter("explicit_euler").first, 1.0e6)
      << "explicit Euler must gain energy on an undamped spring (factor 1.04 per step)";
}

}  // namespace
}  // namespace springlab::rope
