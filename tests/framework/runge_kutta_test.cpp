// The framework's midpoint (RK2) and RK4 integrators on oscillators with exact answers:
// convergence order, stability limit, energy behaviour, force evaluations per step.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <springlab/midpoint.hpp>
#include <springlab/rk4.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

using testing::AnchoredOscillators;

template <class Method>
std::unique_ptr<AnchoredOscillators> oscillatorWith(double k, double c = 0.0) {
  auto sim = std::make_unique<AnchoredOscillators>(1, 1.0, k, c);
  sim->setIntegrator(std::make_unique<Method>());
  return sim;
}

// Position error at t = 1 s on x'' = -4 x, x(0) = 1 (exact: cos 2t).
template <class Method>
double errorAt1s(double dt) {
  AnchoredOscillators sim(1, 1.0, 4.0);
  sim.setIntegrator(std::make_unique<Method>());
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  for (int n = 0; n < steps; ++n) sim.operate(dt);
  return std::abs(sim.state.pos[0].x() - std::cos(2.0));
}

// Oscillator energy relative to its start after `steps` steps at w dt = y (w = 1 rad/s).
template <class Method>
double energyRatioAfter(int steps, double y) {
  AnchoredOscillators sim(1, 1.0, 1.0);
  sim.setIntegrator(std::make_unique<Method>());
  sim.setBlowUpCheck(false);
  const double e0 = sim.energies().total();
  for (int n = 0; n < steps; ++n) sim.operate(y);
  return sim.energies().total() / e0;
}

// Largest stable w dt (w = 1): bisection on whether the amplitude stays below 10 in 20000 steps.
template <class Method>
double criticalWdt(double lo, double hi) {
  auto stable = [](double y) {
    AnchoredOscillators sim(1, 1.0, 1.0);
    sim.setIntegrator(std::make_unique<Method>());
    sim.setBlowUpCheck(false);
    for (int n = 0; n < 20000; ++n) {
      sim.operate(y);
      if (!(sim.state.pos[0].norm() < 10.0)) return false;
    }
    return true;
  };
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

TEST(Midpoint, ConvergesAtSecondOrder) {
  EXPECT_NEAR(std::log2(errorAt1s<Midpoint>(0.002) / errorAt1s<Midpoint>(0.001)), 2.0, 0.15);
}

TEST(RungeKutta4, ConvergesAtFourthOrder) {
  EXPECT_NEAR(std::log2(errorAt1s<RungeKutta4>(0.02) / errorAt1s<RungeKutta4>(0.01)), 4.0, 0.15);
}

TEST(Midpoint, CostsTwoForceEvaluationsPerStep) {
  auto sim = oscillatorWith<Midpoint>(1.0);
  for (int n = 0; n < 10; ++n) sim->operate(0.01);
  EXPECT_EQ(sim->stats.forceEvaluations, 20);
}

TEST(RungeKutta4, CostsFourForceEvaluationsPerStep) {
  auto sim = oscillatorWith<RungeKutta4>(1.0);
  for (int n = 0; n < 10; ++n) sim->operate(0.01);
  EXPECT_EQ(sim->stats.forceEvaluations, 40);
}

TEST(RungeKutta4, CriticalStepIsTwoRootTwoOverW) {
  const double measured = criticalWdt<RungeKutta4>(2.0, 3.5);
  EXPECT_NEAR(measured / (2.0 * std::sqrt(2.0)), 1.0, 0.02)
      << "RK4 on x'' = -x must be stable up to w dt = 2 sqrt 2 = 2.83, measured " << measured;
  EXPECT_DOUBLE_EQ(RungeKutta4().stabilityConstant(), 2.0 * std::sqrt(2.0));
}

TEST(RungeKutta4, EnergyDecaysSlowlyOnUndampedOscillator) {
  // |R(iy)|^2 = 1 - y^6/72 + y^8/576 per step: at y = 0.5 about 2e-4 lost per step.
  const double ratio = energyRatioAfter<RungeKutta4>(100000, 0.5);
  EXPECT_LT(ratio, 0.01) << "RK4 must lose energy on an undamped oscillator";
  EXPECT_GT(ratio, 0.0);
  EXPECT_NEAR(energyRatioAfter<RungeKutta4>(1000, 0.5), std::pow(1.0 - std::pow(0.5, 6) / 72 + std::pow(0.5, 8) / 576, 1000), 1e-9);
}

TEST(Midpoint, EnergyGrowsSlowlyOnUndampedOscillator) {
  // Gain 1 + y^4/4 per step, whatever the dt: at y = 0.1, e^(100000 * 2.5e-5) = e^2.5.
  const double ratio = energyRatioAfter<Midpoint>(100000, 0.1);
  EXPECT_NEAR(std::log(ratio), 100000 * std::log1p(std::pow(0.1, 4) / 4), 1e-6)
      << "the midpoint method multiplies an oscillator's energy by 1 + (w dt)^4 / 4 each step";
  EXPECT_EQ(Midpoint().stabilityConstant(), 0.0);
}

TEST(Midpoint, StableWithDampingAtSmallSteps) {
  auto sim = oscillatorWith<Midpoint>(1.0, 0.2);
  for (int n = 0; n < 100000; ++n) sim->operate(0.1);
  EXPECT_LT(sim->state.pos[0].norm(), 1e-3) << "a damped oscillator must come to rest with the midpoint method";
}

TEST(RungeKutta4, PinnedMassNeverMoves) {
  AnchoredOscillators sim(2, 1.0, 1.0);
  sim.setIntegrator(std::make_unique<RungeKutta4>());
  sim.gravitation = Vec3(0, -9.81, 0);
  sim.togglePinned(1);
  const Vec3 start = sim.state.pos[1];
  for (int n = 0; n < 100; ++n) sim.operate(0.01);
  EXPECT_EQ(sim.state.pos[1], start) << "RK4 moved a pinned mass";
}

}  // namespace
}  // namespace springlab
