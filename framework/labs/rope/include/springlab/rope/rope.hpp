#pragma once
// Lab 1: the rope, given code. The Rope system and the integrators built on the exercise
// kernels of springlab/rope/exercises.hpp; the framework compiles this once and links it
// with the student's exercises (labs/01_rope/) or the reference (solutions/01_rope/).
#include <springlab/integrator.hpp>
#include <springlab/registry.hpp>
#include <springlab/rope/exercises.hpp>
#include <springlab/rope_simulation.hpp>

namespace springlab::rope {

// ---- The rope system and the integrators built from the exercises -----------------------
class Rope final : public RopeSimulation {
 public:
  Rope(int dimension, const RopeParameters& parameters);

  // The terms of accumulateForces, in the order of ForceTerm (the blow-up check names one).
  enum ForceTerm { kSprings, kGravityAndAir, kGround };
  std::vector<std::string> forceTermNames() const override;

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override;
  void afterStep(double dt) override;
};

// Registers the "rope" scene kind and the integrators of this lab.
void registerLab(Registry& registry);

}  // namespace springlab::rope
