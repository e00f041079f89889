// Extended position-based dynamics (given loop; Macklin, Mueller and Chentanez 2016) on the
// scene's springs, built on exercise 2.11. Each spring is a distance constraint of compliance
// 1/k and constraint damping from its kd, so with enough iterations its equilibrium is the
// force model's. External forces once per step; per substep of h = dt / substeps: predict, project
// every constraint `iterations` times (Gauss-Seidel, multipliers from zero), v = (x - x_old)/h.
// Contacts, stretch limiting and self-collision stay in the scene's afterStep (once per step).
#include <cmath>
#include <memory>
#include <string>

#include <springlab/net/net.hpp>

#include "external_forces.hpp"

namespace springlab::net {

namespace {

class Xpbd final : public Integrator {
 public:
  static constexpr std::string_view kName = "xpbd";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  // Stable at any dt: positions are projected, never pushed by a stiff force.
  double stabilityConstant() const override { return INFINITY; }

  std::vector<std::string> optionNames() const override { return {"iterations", "substeps"}; }
  void setOption(const std::string& option, int value) override {
    if (option == "iterations") iterations_ = value;
    else if (option == "substeps") substeps_ = value;
    else Integrator::setOption(option, value);
  }

  void step(Simulation& sim, double dt) override {
    // The external forces once per step, at its start, for every substep: they change slowly
    // (gravity, air, wind), and each evaluation costs three passes over the springs (the
    // scene's forces, then the springs' own taken out again), several times a projection sweep.
    externalForces(sim, external_);
    const double h = dt / substeps_;
    for (int k = 0; k < substeps_; ++k) substep(sim, h);
  }

 private:
  // `flatten` inlines exercise 2.11 into the sweep where the compiler sees it (the reference
  // is one unit), as Net's force loop does with 2.2.
  [[gnu::flatten]] void substep(Simulation& sim, double h) {
    State& s = sim.state;
    const int n = sim.numOfMasses();

    // Predict: the external forces move the masses freely for h (symplectic Euler).
    previous_ = s.pos;
    for (int i = 0; i < n; ++i) {
      s.vel[i] += (h * sim.inverseMass(i)) * external_[i];
      s.pos[i] += h * s.vel[i];
    }

    // Project every spring's constraint, `iterations` sweeps, multipliers from zero.
    lambda_.assign(sim.springs.size(), 0.0);
    const double inverseH2 = 1.0 / (h * h);
    for (int sweep = 0; sweep < iterations_; ++sweep) {
      for (std::size_t c = 0; c < sim.springs.size(); ++c) {
        const Spring& sp = sim.springs[c];
        if (sp.springConstant <= 0.0) continue;  // no stiffness, no constraint
        // alpha~ = 1 / (k h^2); gamma = alpha~ (h^2 kd) / h = kd / (k h).
        const double alphaTilde = inverseH2 / sp.springConstant;
        const double gamma = sp.frictionConstant / (sp.springConstant * h);
        const DistanceCorrection d =
            xpbdDistanceConstraint(s.pos[sp.mass1], s.pos[sp.mass2], previous_[sp.mass1], previous_[sp.mass2],
                                   sim.inverseMass(sp.mass1), sim.inverseMass(sp.mass2), sp.springLength,
                                   alphaTilde, gamma, lambda_[c]);
        s.pos[sp.mass1] += d.dx1;
        s.pos[sp.mass2] += d.dx2;
        lambda_[c] += d.dlambda;
      }
    }
    sim.stats.solverIterations += iterations_;
    sim.stats.constraintProjections += static_cast<long>(iterations_) * static_cast<long>(sim.springs.size());

    // Velocities from the positions' change; masses the scene moves keep theirs.
    const double inverseH = 1.0 / h;
    for (int i = 0; i < n; ++i) {
      if (sim.inverseMass(i) != 0.0) s.vel[i] = (s.pos[i] - previous_[i]) * inverseH;
    }
    s.time += h;
  }

  int iterations_ = 10;  // Gauss-Seidel sweeps over the constraints per substep
  int substeps_ = 1;     // substeps per integrator step
  std::vector<Vec3> external_;   // [n] N
  std::vector<Vec3> previous_;   // [n] m, positions at the start of the substep
  std::vector<double> lambda_;   // [springs] the constraints' multipliers in this substep
};

}  // namespace

void registerXpbd(Registry& registry) {
  registry.addIntegrator(std::string(Xpbd::kName), [] { return std::make_unique<Xpbd>(); });
}

}  // namespace springlab::net
