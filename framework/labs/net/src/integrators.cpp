// The implicit integrators built on exercises 2.8 and 2.9 (given). They run on any scene
// that provides its force Jacobians (Simulation::addForceJacobian).
#include <cmath>

#include <springlab/net/net.hpp>
#include <springlab/solvers/block_jacobi_cg.hpp>

namespace springlab::net {

namespace {

// Both variants end the same way: v += dv, then x += dt v with the new velocity.
void applyVelocityChange(Simulation& sim, const std::vector<Vec3>& dv, double dt) {
  State& s = sim.state;
  for (int i = 0; i < sim.numOfMasses(); ++i) {
    s.vel[i] += dv[i];
    s.pos[i] += dt * s.vel[i];
  }
  s.time += dt;
}

// Linearised backward Euler, the whole sparse system solved by conjugate gradients.
class ImplicitEuler final : public Integrator {
 public:
  // CG stops at this residual relative to |b|.
  static constexpr double kTolerance = 1e-6;

  static constexpr std::string_view kName = "implicit_euler";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  double stabilityConstant() const override { return INFINITY; }
  void reset() override { guess_.resize(0); }

  void step(Simulation& sim, double dt) override {
    const int n = sim.numOfMasses();
    // Forces and their Jacobians at the start of the step.
    sim.evaluateForces(sim.state, sim.force);
    sim.forceJacobian(sim.state, jacobian_, kName);

    // The system over the free masses (exercise 2.8).
    free_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) free_[static_cast<std::size_t>(i)] = sim.inverseMass(i) != 0.0;
    system_.prepare(free_, jacobian_);
    assembleImplicitEuler(sim, sim.force, jacobian_, dt, system_);

    // Conjugate gradients, warm-started from the last step's dv where the rows still fit.
    dv_.assign(static_cast<std::size_t>(n), Vec3::Zero());
    if (system_.size() > 0) {
      if (guess_.size() != system_.size()) guess_.setZero(system_.size());
      cg_.tolerance = kTolerance;
      sim.stats.solverIterations += cg_.solve(system_, guess_);
      for (int i = 0; i < n; ++i) {
        if (system_.row(i) >= 0) dv_[static_cast<std::size_t>(i)] = guess_.segment<3>(system_.row(i));
      }
    }
    applyVelocityChange(sim, dv_, dt);
  }

 private:
  ForceJacobian jacobian_;
  BlockSystem system_;
  std::vector<char> free_;      // [n] 1 for a mass the forces move
  std::vector<Vec3> dv_;        // [n] m/s
  Eigen::VectorXd guess_;       // [3 x free masses] last solution, CG's starting point
  BlockJacobiCG cg_;
};

// Linearised backward Euler keeping each mass's own 3x3 block only (exercise 2.9).
class ImplicitEulerBlocks final : public Integrator {
 public:
  static constexpr std::string_view kName = "implicit_euler_blocks";
  std::string name() const override { return std::string(kName); }
  int order() const override { return 1; }
  double stabilityConstant() const override { return INFINITY; }

  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    sim.forceJacobian(sim.state, jacobian_, kName);
    dv_.assign(static_cast<std::size_t>(sim.numOfMasses()), Vec3::Zero());
    implicitEulerBlocks(sim, sim.force, jacobian_, dt, diagonal_, dv_);
    applyVelocityChange(sim, dv_, dt);
  }

 private:
  ForceJacobian jacobian_;
  std::vector<Mat3> diagonal_;  // [n] workspace
  std::vector<Vec3> dv_;        // [n] m/s
};

}  // namespace

void registerXpbd(Registry& registry);                // xpbd.cpp
void registerProjectiveDynamics(Registry& registry);  // projective_dynamics.cpp

void registerIntegrators(Registry& registry) {
  registerXpbd(registry);
  registerProjectiveDynamics(registry);
  registry.addIntegrator("implicit_euler", [] { return std::make_unique<ImplicitEuler>(); });
  registry.addIntegrator("implicit_euler_blocks", [] { return std::make_unique<ImplicitEulerBlocks>(); });
}

}  // namespace springlab::net
