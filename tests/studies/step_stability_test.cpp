// The stability limit of the step that runs (springlab/step_stability.hpp) against the closed
// forms of physics.md section 7: on a uniform damped chain every mode q'' = -w^2 q - gamma q'
// is stepped by a 2x2 matrix written out here from each method's update formulas, and the
// chain's limit is the smallest over its modes. The step-map estimate never sees these.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Dense>

#include <springlab/frequency_estimate.hpp>
#include <springlab/step_stability.hpp>
#include <springlab/studies/run.hpp>
#include <springlab/studies/stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// ---- the closed forms: one mode, one method ---------------------------------------------------
// The step of q'' = -w2 q - g q' as a matrix on (q, q'), from each method's formulas.
Eigen::Matrix2d modeStep(const std::string& method, double w2, double g, double h) {
  Eigen::Matrix2d A;  // the rate matrix: d/dt (q, v) = A (q, v)
  A << 0.0, 1.0, -w2, -g;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d hA = h * A;
  if (method == "explicit_euler") return I + hA;
  if (method == "midpoint") return I + hA + hA * hA / 2.0;
  if (method == "rk4") return I + hA + hA * hA / 2.0 + hA * hA * hA / 6.0 + hA * hA * hA * hA / 24.0;
  if (method == "symplectic_euler" || method == "position_verlet") {
    // Kick with the force at the start, drift with the new velocity (position Verlet's
    // x' = 2x - x_prev + h^2 a with v = (x - x_prev) / h is the same map).
    Eigen::Matrix2d S;
    S << 1.0 - h * h * w2, h * (1.0 - h * g), -h * w2, 1.0 - h * g;
    return S;
  }
  if (method == "velocity_verlet") {
    // State (q, v, a) with a kept from the last step: a = -w2 q - g (v - a h / 2), so
    // a = (-w2 q - g v) / (1 - g h / 2). Drift with a half kick, force at the new position
    // and half-kicked velocity, then the second half kick.
    const double d = 1.0 - g * h / 2.0;
    const Eigen::RowVector2d a(-w2 / d, -g / d);             // a as a row acting on (q, v)
    const Eigen::RowVector2d q1 = Eigen::RowVector2d(1.0, h) + h * h / 2.0 * a;
    const Eigen::RowVector2d vHalf = Eigen::RowVector2d(0.0, 1.0) + h / 2.0 * a;
    const Eigen::RowVector2d a1 = -w2 * q1 - g * vHalf;
    Eigen::Matrix2d S;
    S.row(0) = q1;
    S.row(1) = vHalf + h / 2.0 * a1;
    return S;
  }
  ADD_FAILURE() << "no closed form for " << method;
  return I;
}

double modeRadius(const std::string& method, double w2, double g, double h) {
  return Eigen::EigenSolver<Eigen::Matrix2d>(modeStep(method, w2, g, h)).eigenvalues().cwiseAbs().maxCoeff();
}

// The largest h with every mode's radius <= 1, by bisection from a bracket [lo, hi].
double closedFormLimit(const std::string& method, const std::vector<std::pair<double, double>>& modes, double lo,
                       double hi) {
  auto stable = [&](double h) {
    for (const auto& [w2, g] : modes) {
      if (modeRadius(method, w2, g, h) > 1.0 + 1e-12) return false;
    }
    return true;
  };
  if (!stable(lo)) return 0.0;
  if (stable(hi)) return INFINITY;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

// ---- a uniform damped chain: N free masses hanging sideways from a fixed end ---------------
// m = 0.05 kg, k = 10000 N/m, L0 = 0.05 m, spring dampers kd along each spring and air a. At
// the start the springs are at rest length along x, so the linearised chain has only its
// axial modes w_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2N + 1))) (fixed-free chain) with
// gamma_j = a / m + (kd / k) w_j^2, and transverse modes with w = 0, gamma = a / m.
constexpr int kChainMasses = 12;
constexpr double kMass = 0.05, kStiffness = 10000.0, kAir = 0.02;

SceneDocument dampedChain(double kd) {
  SceneDocument d = shippedScene("rope.json");
  for (const std::string& s :
       {"rope.masses=" + std::to_string(kChainMasses + 1), std::string("rope.ground.height=-100"),
        "rope.spring_friction=" + std::to_string(kd), std::string("rope.air_friction=0.02")}) {
    d.set(s);
  }
  return d;
}

std::vector<std::pair<double, double>> chainModes(double kd) {
  std::vector<std::pair<double, double>> modes{{0.0, kAir / kMass}};
  for (int j = 1; j <= kChainMasses; ++j) {
    const double w = 2.0 * std::sqrt(kStiffness / kMass) *
                     std::sin((2 * j - 1) * std::numbers::pi / (2.0 * (2 * kChainMasses + 1)));
    modes.push_back({w * w, kAir / kMass + kd / kStiffness * w * w});
  }
  return modes;
}

double stepLimit(const SceneDocument& scene, const std::string& integrator, const StepStabilityOptions& o = {}) {
  LoadedScene loaded = allLabs().loadScene(scene);
  loaded.sim->setIntegrator(allLabs().makeIntegrator(integrator));
  return stepStableDt(*loaded.sim, o);
}

TEST(StepStabilityExplore, DampedChain) {
  const double wMax = 2.0 * std::sqrt(kStiffness / kMass);
  for (double kd : {0.0, 0.2, 2.0, 4.5, 10.0, 30.0}) {
    for (const std::string m : {"explicit_euler", "symplectic_euler", "position_verlet", "velocity_verlet", "midpoint", "rk4"}) {
      const double exact = closedFormLimit(m, chainModes(kd), 1e-9, 10.0 / wMax);
      StepStabilityOptions dense, modal;
      dense.denseBelow = 1000;
      modal.denseBelow = 0;
      const double krylov = stepLimit(dampedChain(kd), m, modal);
      const double full = stepLimit(dampedChain(kd), m, dense);
      std::printf("kd %5.2f %-18s exact %.5g krylov %.5g (%.4f) dense %.5g (%.4f)\n", kd, m.c_str(), exact, krylov,
                  krylov / exact, full, full / exact);
    }
  }
}

}  // namespace
}  // namespace springlab
