// Implicit Euler on the hanging cloth: backward Euler is stable at every dt wherever the
// linearised forces are (K and C symmetric, the rest a stable equilibrium), and the step that
// runs (exercise 2.8's system, solved by conjugate gradients) is backward Euler linearised at
// the start of the step. So at the cloth's rest its limit must come out unbounded. Two oracles
// that share nothing with step_stability.cpp: the whole Jacobian of one step at a plain run's
// rest, by finite differences written here, and plain runs at large steps, which settle to the
// same drape. The instrument, given that rest (StepStabilityOptions::at), must agree.
//
// Left to settle by itself the instrument linearises where the first swing turned, not at a
// rest; there it holds the state in place with a constant load (step_stability.cpp). Without
// that it said 112.6 ms on the 8 x 8 cloth and 47.6 ms on the 32 x 32 one of handout 02's chart.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include <springlab/step_stability.hpp>
#include <springlab/studies/stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// The hanging cloth at r x r masses with only springs, air and gravity at work (stretch
// limiting off, as handout 02's stability chart has it: a position correction is not the
// step's linear solve), under implicit Euler.
SceneDocument clothWithoutStretchLimit(int r) {
  SceneDocument scene = shippedScene("net_hanging.json");
  scene.set("net.resolution=" + std::to_string(r));
  scene.set("net.stretch_limit.enabled=false");
  scene.set("integrator=implicit_euler");
  return scene;
}

// A plain run of `seconds` at `dt` with no blow-up check; returns the drape height (m) at its end.
double drapeAfter(Simulation& sim, double dt, double seconds) {
  sim.setBlowUpCheck(false);
  for (long i = 0; i < std::lround(seconds / dt); ++i) sim.simulate(dt);
  for (const Observable& o : sim.observables())
    if (o.name == "drape_height") return o.value;
  ADD_FAILURE() << "the cloth has no drape_height observable";
  return NAN;
}

// The spectral radius of one step of dt from `rest` (velocities zero), every free coordinate
// moved by 1e-7 in turn, the solver's tolerance at 1e-13 so that its error stays below that.
double stepRadiusAt(Simulation& sim, const State& rest, double dt) {
  std::vector<std::pair<int, int>> dofs;
  for (int i = 0; i < sim.numOfMasses(); ++i)
    if (sim.inverseMass(i) != 0.0)
      for (int a = 0; a < 3; ++a) dofs.emplace_back(i, a);
  const int n = static_cast<int>(dofs.size());
  auto stepFrom = [&](const State& s) {
    sim.state = s;
    sim.integrator().reset();
    sim.simulate(dt);
    Eigen::VectorXd y(2 * n);
    for (int k = 0; k < n; ++k) {
      y[k] = sim.state.pos[static_cast<std::size_t>(dofs[static_cast<std::size_t>(k)].first)][dofs[static_cast<std::size_t>(k)].second];
      y[n + k] = sim.state.vel[static_cast<std::size_t>(dofs[static_cast<std::size_t>(k)].first)][dofs[static_cast<std::size_t>(k)].second];
    }
    return y;
  };
  const double h = 1e-7;
  const Eigen::VectorXd y0 = stepFrom(rest);
  Eigen::MatrixXd J(2 * n, 2 * n);
  for (int c = 0; c < 2 * n; ++c) {
    State s = rest;
    const auto [i, a] = dofs[static_cast<std::size_t>(c % n)];
    (c < n ? s.pos : s.vel)[static_cast<std::size_t>(i)][a] += h;
    J.col(c) = (stepFrom(s) - y0) / h;
  }
  return Eigen::EigenSolver<Eigen::MatrixXd>(J, false).eigenvalues().cwiseAbs().maxCoeff();
}

// The 8 x 8 cloth (372 coordinates). Measured: the radius at the rest is 0.985 at 10 ms, 0.886
// at 0.1 s and 0.866 at 1 s, the instrument's at the same rest the same to 1e-4; runs at 160 ms
// and 640 ms settle within 0.1 mm of the drape at 10 ms.
TEST(HangingCloth, ImplicitEulersStepAtItsRestIsStableAtEveryDt) {
  const SceneDocument scene = clothWithoutStretchLimit(8);
  LoadedScene plain = allLabs().loadScene(scene);
  plain.sim->solver.tolerance = 1e-13;
  const double restDrape = drapeAfter(*plain.sim, 0.01, 20.0);
  State rest = plain.sim->state;
  for (Vec3& v : rest.vel) v.setZero();

  StepStabilityOptions atRest;
  atRest.at = rest;
  for (double dt : {0.01, 0.1, 1.0}) {
    const double oracle = stepRadiusAt(*plain.sim, rest, dt);
    EXPECT_LT(oracle, 1.0) << "the whole Jacobian at the rest, dt = " << dt << " s";
    EXPECT_NEAR(stepSpectralRadius(*plain.sim, dt, atRest).radius, oracle, 1e-4) << "the instrument at the rest, dt = " << dt << " s";
  }
  const double limit = stepStableDt(*plain.sim, atRest);
  EXPECT_TRUE(std::isinf(limit)) << "implicit Euler's limit at its rest: " << limit << " s";
  const double predicted = studies::sceneStepStableDt(allLabs(), scene, "implicit_euler");
  EXPECT_TRUE(std::isinf(predicted)) << "implicit Euler's limit at the settled state: " << predicted << " s";

  for (double dt : {0.16, 0.64}) {
    LoadedScene far = allLabs().loadScene(scene);
    EXPECT_NEAR(drapeAfter(*far.sim, dt, 20.0), restDrape, 1e-3) << "implicit Euler at dt = " << dt << " s, 20 s";
  }
}

// The 32 x 32 cloth of handout 02's chart (6144 coordinates: the modal directions).
TEST(HangingCloth, ImplicitEulerHasNoLimitOnTheChartsCloth) {
  const double predicted = studies::sceneStepStableDt(allLabs(), clothWithoutStretchLimit(32), "implicit_euler");
  EXPECT_TRUE(std::isinf(predicted)) << "implicit Euler's predicted limit: " << predicted << " s";
}

}  // namespace
}  // namespace springlab
