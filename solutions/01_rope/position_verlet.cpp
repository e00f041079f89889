#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

PhasePoint positionVerletFirstStep(const PhasePoint& s, const Vec3& a, double dt) {
  // BEGIN EXERCISE 1.5
  // Taylor step from the initial state: there is no previous position yet.
  const Vec3 next = s.pos + s.vel * dt + 0.5 * a * dt * dt;
  return {next, (next - s.pos) / dt};
  // END EXERCISE 1.5
}

PhasePoint positionVerletStep(const Vec3& pos, const Vec3& previousPos, const Vec3& a, double dt) {
  // BEGIN EXERCISE 1.5
  // Central difference of positions; the velocity is estimated from the last move.
  const Vec3 next = 2.0 * pos - previousPos + a * dt * dt;
  return {next, (next - pos) / dt};
  // END EXERCISE 1.5
}

}  // namespace springlab::rope
