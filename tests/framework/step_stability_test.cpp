// The limit of the step that runs (springlab/step_stability.hpp) on oscillators whose modes
// are known exactly: each mass tied to the origin, x'' = -w^2 x - gamma x' with w^2 = k/m and
// gamma = c/m. The estimate runs the framework's integrators as they are; the expected values
// are the closed forms of physics.md section 7.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <string>

#include <springlab/midpoint.hpp>
#include <springlab/rk4.hpp>
#include <springlab/step_stability.hpp>
#include <springlab/symplectic_euler.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

using testing::AnchoredOscillators;

// Four masses, k = 100 N/m, m = 1 kg: w = 10 rad/s.
double limitOf(std::unique_ptr<Integrator> integrator, double c, const StepStabilityOptions& o = {}) {
  AnchoredOscillators sim(4, 1.0, 100.0, c);
  sim.setIntegrator(std::move(integrator));
  return stepStableDt(sim, o);
}

// The largest h with |R(h lambda)| <= 1 for both roots lambda of the mode, by bisection.
template <class R>
double polynomialLimit(R amplification, double w, double gamma) {
  const std::complex<double> root = std::sqrt(std::complex<double>(gamma * gamma / 4.0 - w * w));
  const std::complex<double> l1 = -gamma / 2.0 + root, l2 = -gamma / 2.0 - root;
  auto stable = [&](double h) { return std::abs(amplification(h * l1)) <= 1.0 && std::abs(amplification(h * l2)) <= 1.0; };
  double lo = 1e-6 / w, hi = 10.0 / w;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

TEST(StepStability, UndampedSymplecticEulerIs2OverW) {
  EXPECT_NEAR(limitOf(std::make_unique<SymplecticEuler>(), 0.0) / 0.2, 1.0, 0.002);
}

TEST(StepStability, DampedSymplecticEulerSolvesW2Dt2Plus2GammaDtEquals4) {
  // Damping lowers the limit: w^2 h^2 + 2 gamma h = 4, h = (-gamma + sqrt(gamma^2 + 4 w^2)) / w^2.
  for (double gamma : {2.0, 4.0, 12.0, 40.0}) {  // damping ratios 0.1, 0.2, 0.6, 2
    const double exact = (-gamma + std::sqrt(gamma * gamma + 4.0 * 100.0)) / 100.0;
    EXPECT_NEAR(limitOf(std::make_unique<SymplecticEuler>(), gamma) / exact, 1.0, 0.002) << "gamma = " << gamma;
  }
}

TEST(StepStability, Rk4FollowsItsStabilityPolynomial) {
  auto r4 = [](std::complex<double> z) { return 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0; };
  EXPECT_NEAR(limitOf(std::make_unique<RungeKutta4>(), 0.0) / (2.0 * std::sqrt(2.0) / 10.0), 1.0, 0.002);
  for (double gamma : {4.0, 12.0, 40.0}) {
    const double exact = polynomialLimit(r4, 10.0, gamma);
    EXPECT_NEAR(limitOf(std::make_unique<RungeKutta4>(), gamma) / exact, 1.0, 0.002) << "gamma = " << gamma;
  }
}

TEST(StepStability, MidpointIsStableOnlyWithDampingAndFollowsItsPolynomial) {
  auto r2 = [](std::complex<double> z) { return 1.0 + z + z * z / 2.0; };
  for (double gamma : {4.0, 12.0, 40.0}) {
    const double exact = polynomialLimit(r2, 10.0, gamma);
    EXPECT_NEAR(limitOf(std::make_unique<Midpoint>(), gamma) / exact, 1.0, 0.002) << "gamma = " << gamma;
  }
  // Without damping |R(i y)|^2 = 1 + y^4 / 4 > 1 at every dt: no stable dt (not the dt where
  // y^4 / 8 meets the radius slack, 0.027 of 2 / w, which the limit was before).
  EXPECT_EQ(limitOf(std::make_unique<Midpoint>(), 0.0), 0.0);
  // Light damping still gives a finite limit, near y^4 / 8 = gamma h, h = (8 gamma / w^4)^(1/3):
  // gamma = 0.01 puts it at a tenth of 2 / w, where a limit is asked whether it is the slack's;
  // there the radius crosses 1 so slowly that the slack of 1e-6 moves the root by 0.4 %.
  for (double gamma : {0.01, 0.4}) {
    const double exact = polynomialLimit(r2, 10.0, gamma);
    EXPECT_NEAR(limitOf(std::make_unique<Midpoint>(), gamma) / exact, 1.0, gamma < 0.1 ? 0.006 : 0.002)
        << "gamma = " << gamma;
  }
}

TEST(StepStability, ModalRunsAgreeWithTheWholeJacobian) {
  StepStabilityOptions dense, modal;
  dense.denseBelow = 1000;
  modal.denseBelow = 0;
  modal.modes = 2;
  for (double gamma : {0.0, 4.0, 40.0}) {
    EXPECT_NEAR(limitOf(std::make_unique<SymplecticEuler>(), gamma, dense) /
                    limitOf(std::make_unique<SymplecticEuler>(), gamma, modal),
                1.0, 0.002)
        << "gamma = " << gamma;
  }
}

TEST(StepStability, LeavesTheSceneAtItsStart) {
  AnchoredOscillators sim(2, 1.0, 100.0, 2.0);
  const State start = sim.state;
  stepStableDt(sim);
  EXPECT_EQ(sim.state.pos, start.pos);
  EXPECT_EQ(sim.state.vel, start.vel);
  EXPECT_TRUE(sim.blowUpCheckEnabled());
  EXPECT_EQ(sim.stats.steps, 0);
}

// The viewer's worker cancels a computation when the method or a parameter changes: the
// computation stops at its next run of the scene (the n-th question) and leaves the scene as
// a finished one does, its solver tolerance and blow-up check as they were.
TEST(StepStability, CancelledComputationStopsAndLeavesTheSceneAtItsStart) {
  // How often a whole computation asks, so that the stops below fall inside it (its start,
  // its settling, its middle, its last run).
  int questions = 0;
  {
    AnchoredOscillators sim(2, 1.0, 100.0, 2.0);
    StepStabilityOptions o;
    o.cancelled = [&] { return ++questions < 0; };
    stepStableDt(sim, o);
  }
  ASSERT_GT(questions, 10);
  for (int askedBeforeCancel : {0, 5, questions / 2, questions - 1}) {
    AnchoredOscillators sim(2, 1.0, 100.0, 2.0);
    const State start = sim.state;
    const double tolerance = sim.solver.tolerance;
    int asked = 0;
    StepStabilityOptions o;
    o.cancelled = [&] { return ++asked > askedBeforeCancel; };
    EXPECT_THROW(stepStableDt(sim, o), StepStabilityCancelled) << "cancelled after " << askedBeforeCancel;
    EXPECT_EQ(asked, askedBeforeCancel + 1) << "asked again after saying stop";
    EXPECT_EQ(sim.state.pos, start.pos);
    EXPECT_EQ(sim.state.vel, start.vel);
    EXPECT_EQ(sim.solver.tolerance, tolerance);
    EXPECT_TRUE(sim.blowUpCheckEnabled());
  }
}

}  // namespace
}  // namespace springlab
