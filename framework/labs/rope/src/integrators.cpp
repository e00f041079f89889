// Integrator classes built on the exercise kernels: they gather each mass's state and
// acceleration, call the kernel, and scatter the result. Given; the kernels are yours.
#include <cstddef>
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
  void reset() override {
    previous_.clear();
    written_.clear();
  }
  void step(Simulation& sim, double dt) override {
    sim.evaluateForces(sim.state, sim.force);
    const int n = sim.numOfMasses();
    const bool first = previous_.size() != static_cast<std::size_t>(n);
    if (first) {
      previous_.resize(n);
      written_.resize(n);
    }
    for (int i = 0; i < n; ++i) {
      const PhasePoint now{sim.state.pos[i], sim.state.vel[i]};
      const Vec3 a = acceleration(sim, sim.force, i);
      // A mass the scene moves keeps its velocity; Verlet would estimate it from history.
      const bool kinematic = sim.inverseMass(i) == 0.0;
      // A contact (or the user) that moved the mass or changed its velocity after the last step
      // gave it a new state: its history is then where that velocity came from, x - dt v, so a
      // bounce bounces. (Verlet's own velocity is (x - x_prev) / dt: untouched, this is x_prev.)
      const bool restarted = !first && (now.pos != written_[i].pos || now.vel != written_[i].vel);
      const Vec3 previous = restarted ? Vec3(now.pos - dt * now.vel) : previous_[i];
      const PhasePoint next =
          first || kinematic ? positionVerletFirstStep(now, a, dt) : positionVerletStep(now.pos, previous, a, dt);
      previous_[i] = now.pos;
      written_[i] = next;
      sim.state.pos[i] = next.pos;
      sim.state.vel[i] = next.vel;
    }
    sim.state.time += dt;
  }

 private:
  std::vector<Vec3> previous_;       // [n] positions one step back
  std::vector<PhasePoint> written_;  // [n] the state this integrator left each mass in
};

class VelocityVerlet final : public Integrator {
 public:
  std::string name() const override { return "velocity_verlet"; }
  int order() const override { return 2; }
  double stabilityConstant() const override { return 2.0; }
  void reset() override { a_.clear(); }
  void step(Simulation& sim, double dt) override {
    const int n = sim.numOfMasses();
    State& next = next_;
    // Accelerations at the start: those computed at the end of the last step, once known.
    if (a_.size() != static_cast<size_t>(n)) {
      sim.evaluateForces(sim.state, sim.force);
      a_.resize(n);
      for (int i = 0; i < n; ++i) a_[i] = acceleration(sim, sim.force, i);
    } else if (sim.state.pos != written_.pos || sim.state.vel != written_.vel) {
      // A stretch limit, a contact or the user moved masses or changed velocities after the
      // last step: the kept accelerations belong to positions that are gone. Evaluate them
      // again where the masses are, with the velocity the last evaluation saw (half-kicked)
      // changed as the state's was, so the method stays the same map with or without the
      // change (with the state's own velocity its damped limit would be another, up to twice
      // as large).
      next = sim.state;  // copies into kept buffers
      for (int i = 0; i < n; ++i) next.vel[i] = halfKicked_[i] + (sim.state.vel[i] - written_.vel[i]);
      sim.evaluateForces(next, sim.force);
      for (int i = 0; i < n; ++i) a_[i] = acceleration(sim, sim.force, i);
    }

    // Drift to the new positions; velocity-dependent forces see a half-kicked velocity.
    next = sim.state;  // copies into kept buffers
    for (int i = 0; i < n; ++i) {
      next.pos[i] = velocityVerletPosition({sim.state.pos[i], sim.state.vel[i]}, a_[i], dt);
      next.vel[i] = sim.state.vel[i] + 0.5 * a_[i] * dt;
    }
    sim.evaluateForces(next, sim.force);
    halfKicked_ = next.vel;  // copies into a kept buffer

    // Kick with the mean of old and new accelerations; keep the new ones for the next step.
    for (int i = 0; i < n; ++i) {
      const Vec3 nextA = acceleration(sim, sim.force, i);
      next.vel[i] = velocityVerletVelocity(sim.state.vel[i], a_[i], nextA, dt);
      a_[i] = nextA;
    }
    next.time += dt;
    written_.pos = next.pos;  // copies into kept buffers
    written_.vel = next.vel;
    std::swap(sim.state, next);  // both buffers stay for the next step
  }

 private:
  std::vector<Vec3> a_;           // [n] accelerations at the current state, from the last step
  std::vector<Vec3> halfKicked_;  // [n] the velocities a_ was evaluated with
  State next_;                    // the state being built, kept between steps
  State written_;                 // the positions and velocities this step left, to see another's change
};

}  // namespace

void registerIntegrators(Registry& registry) {
  registry.addIntegrator("explicit_euler", [] { return std::make_unique<ExplicitEuler>(); });
  registry.addIntegrator("position_verlet", [] { return std::make_unique<PositionVerlet>(); });
  registry.addIntegrator("velocity_verlet", [] { return std::make_unique<VelocityVerlet>(); });
}

}  // namespace springlab::rope
