// Integrator classes built on the exercise kernels: they gather each mass's state and
// acceleration, call the kernel, and scatter the result. Given; the kernels are yours.
#include <utility>
#include <vector>

#include <springlab/rope/rope.hpp>

namespace springlab::rope {

namespace {

// a_i = F_i / m_i, zero for a mass the scene moves (pinned or grabbed).
Vec3 acceleration(const Simulation& sim, const std::vector<Vec3>& f, int i) {
  return f[i] * sim.inverseMass(i);
}

class ExplicitEuler final : public Integrator {
 public:
  std::string name() const override { return "explicit_euler"; }
  int order() const override { return 1; }
  double stabilityConstant() const override { return 0.0; }
  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      const PhasePoint next =
          explicitEulerStep({sim.state.pos[i], sim.state.vel[i]}, acceleration(sim, sim.force, i), dt);
      sim.state.pos[i] = next.pos;
      sim.state.vel[i] = next.vel;
    }
    sim.state.time += dt;
  }
};

class PositionVerlet final : public Integrator {
 public:
  std::string name() const override { return "position_verlet"; }
  int order() const override { return 2; }
  double stabilityConstant() const override { return 2.0; }
  void reset() override { previous_.clear(); }
  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    const bool first = previous_.size() != sim.state.pos.size();
    std::vector<Vec3> current = sim.state.pos;
    for (int i = 0; i < sim.numOfMasses(); ++i) {
      const Vec3 a = acceleration(sim, sim.force, i);
      // A mass the scene moves keeps its velocity; Verlet would estimate it from history.
      const bool kinematic = sim.inverseMass(i) == 0.0;
      const PhasePoint next = first || kinematic
                                  ? positionVerletFirstStep({sim.state.pos[i], sim.state.vel[i]}, a, dt)
                                  : positionVerletStep(sim.state.pos[i], previous_[i], a, dt);
      sim.state.pos[i] = next.pos;
      sim.state.vel[i] = next.vel;
    }
    previous_ = std::move(current);
    sim.state.time += dt;
  }

 private:
  std::vector<Vec3> previous_;  // [n] positions one step back
};

class VelocityVerlet final : public Integrator {
 public:
  std::string name() const override { return "velocity_verlet"; }
  int order() const override { return 2; }
  double stabilityConstant() const override { return 2.0; }
  void reset() override { a_.clear(); }
  void step(Simulation& sim, double dt) override {
    const int n = sim.numOfMasses();
    // Accelerations at the start: those computed at the end of the last step, once known.
    if (a_.size() != static_cast<size_t>(n)) {
      sim.evaluateForces(sim.state, sim.force);
      a_.resize(n);
      for (int i = 0; i < n; ++i) a_[i] = acceleration(sim, sim.force, i);
    }

    // Drift to the new positions; velocity-dependent forces see a half-kicked velocity.
    State& next = next_;
    next = sim.state;  // copies into kept buffers
    for (int i = 0; i < n; ++i) {
      next.pos[i] = velocityVerletPosition({sim.state.pos[i], sim.state.vel[i]}, a_[i], dt);
      next.vel[i] = sim.state.vel[i] + 0.5 * a_[i] * dt;
    }
    sim.evaluateForces(next, sim.force);

    // Kick with the mean of old and new accelerations; keep the new ones for the next step.
    for (int i = 0; i < n; ++i) {
      const Vec3 nextA = acceleration(sim, sim.force, i);
      next.vel[i] = velocityVerletVelocity(sim.state.vel[i], a_[i], nextA, dt);
      a_[i] = nextA;
    }
    next.time += dt;
    std::swap(sim.state, next);  // both buffers stay for the next step
  }

 private:
  std::vector<Vec3> a_;  // [n] accelerations at the current state, from the last step
  State next_;           // the state being built, kept between steps
};

}  // namespace

void registerIntegrators(Registry& registry) {
  registry.addIntegrator("explicit_euler", [] { return std::make_unique<ExplicitEuler>(); });
  registry.addIntegrator("position_verlet", [] { return std::make_unique<PositionVerlet>(); });
  registry.addIntegrator("velocity_verlet", [] { return std::make_unique<VelocityVerlet>(); });
}

}  // namespace springlab::rope
