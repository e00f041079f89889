#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 groundContactForce(const Vec3& x, const Vec3& vel, const Ground& ground) {
  // BEGIN EXERCISE 1.3
  // The ground acts only on masses below it.
  const double depth = ground.height - x.y();
  if (depth <= 0.0) return Vec3::Zero();

  // Friction slows the horizontal part of the velocity.
  Vec3 f = Vec3::Zero();
  f.x() = -ground.friction * vel.x();
  f.z() = -ground.friction * vel.z();

  // Absorption slows a downward vertical velocity only (it never pulls a mass down).
  if (vel.y() < 0.0) f.y() -= ground.absorption * vel.y();

  // Repulsion pushes up in proportion to the depth.
  f.y() += ground.repulsion * depth;
  return f;
  // END EXERCISE 1.3
}

}  // namespace springlab::rope
