#include <springlab/rope/rope.hpp>

namespace springlab::rope {

Rope::Rope(int dim, const RopeParameters& p) : RopeSimulation(dim, p) {
  // Build the chain from exercise 1.7 and start the run from it.
  RopeLayout layout = buildRope(p);
  masses = std::move(layout.masses);
  editSprings() = std::move(layout.springs);
  state.pos = std::move(layout.pos);
  state.vel = std::move(layout.vel);
  finishBuilding();
}

std::vector<std::string> Rope::forceTermNames() const {
  return {"spring forces (exercise 1.1, springDamperForce)",
          "gravity and air friction (exercise 1.2, gravityAndAirFriction)",
          "ground contact (exercise 1.3, groundContactForce)"};
}

void Rope::accumulateForces(const State& s, std::vector<Vec3>& f) {
  // Springs: equal and opposite on their two ends (exercise 1.1).
  if (forceTermOn(kSprings)) {
    for (const Spring& sp : springs()) {
      const Vec3 f1 = springDamperForce(s.pos[sp.mass1], s.pos[sp.mass2], s.vel[sp.mass1], s.vel[sp.mass2],
                                        sp.springConstant, sp.springLength, sp.frictionConstant);
      f[sp.mass1] += f1;
      f[sp.mass2] -= f1;
    }
  }
  // Gravity, air and ground on each mass (exercises 1.2 and 1.3).
  const bool gravityAndAir = forceTermOn(kGravityAndAir), groundActs = forceTermOn(kGround);
  for (int i = 0; i < numOfMasses(); ++i) {
    if (gravityAndAir) f[i] += gravityAndAirFriction(masses[i].m, s.vel[i], gravitation, airFrictionConstant);
    if (groundActs) f[i] += groundContactForce(s.pos[i], s.vel[i], ground);
  }
}

void Rope::afterStep(double dt) {
  // The connection point moves; the fixed mass follows it exactly (exercise 1.8).
  const PhasePoint next = moveConnection({ropeConnectionPos, ropeConnectionVel}, dt, ground.height);
  ropeConnectionPos = next.pos;
  ropeConnectionVel = next.vel;
  state.pos[0] = ropeConnectionPos;
  state.vel[0] = ropeConnectionVel;
}

}  // namespace springlab::rope
