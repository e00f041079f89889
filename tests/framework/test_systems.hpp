#pragma once
// Systems for framework tests whose motion is known exactly. They avoid the spring-damper
// force of Lab 1 on purpose: framework tests ship to students and must not hold an answer.
#include <springlab/simulation.hpp>

namespace springlab::testing {

// n independent masses, each tied to the origin: F = -k x - c v, so x'' = -w^2 x with
// w = sqrt(k/m). A spring list (not used for forces) lets the diagnostics be exercised.
class AnchoredOscillators final : public Simulation {
 public:
  AnchoredOscillators(int n, double m, double k, double c = 0.0, int dim = 3)
      : Simulation(dim), stiffness(k), damping(c) {
    for (int i = 0; i < n; ++i) {
      masses.push_back(Mass{m, false});
      state.pos.push_back(Vec3(1.0, 0.0, 0.0));
      state.vel.push_back(Vec3::Zero());
    }
    markInitialState();
  }
  double stiffness;  // N/m
  double damping;    // N s/m

  std::string kind() const override { return "anchored oscillators"; }
  double angularFrequencyBound() const override { return std::sqrt(stiffness / masses[0].m); }
  using Simulation::markInitialState;

 protected:
  // Two sliders: the anchors' stiffness (a field of this system) and gravity's y.
  std::vector<Parameter> declareParameters() override {
    return {Parameter::field("stiffness", "N/m", stiffness, 0.1, 100.0, true),
            Parameter::field("gravity y", "m/s^2", gravitation.y(), -30.0, 30.0)};
  }
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    for (int i = 0; i < numOfMasses(); ++i) f[i] += -stiffness * s.pos[i] - damping * s.vel[i] + masses[i].m * gravitation;
  }
  double otherPotentialEnergy(const State& s) const override {
    double e = 0;
    for (const Vec3& x : s.pos) e += 0.5 * stiffness * x.squaredNorm();
    return e;
  }
};

}  // namespace springlab::testing
