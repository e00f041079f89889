#include <algorithm>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

PhasePoint projectContact(const PhasePoint& point, const Penetration& p, const Vec3& obstacleVelocity,
                          const ContactMaterial& c) {
  // BEGIN EXERCISE 3.8
  if (!p.touching) return point;
  // Move out of the obstacle along the normal.
  PhasePoint out{point.pos + p.depth * p.normal, point.vel};

  // Approaching: bounce the normal relative velocity, scaled by the restitution.
  const Vec3 relative = point.vel - obstacleVelocity;
  const double vn = relative.dot(p.normal);
  if (vn >= 0.0) return out;
  const Vec3 vt = relative - vn * p.normal;
  const double normalChange = -(1.0 + c.restitution) * vn;

  // Coulomb: the tangential speed drops by at most mu times the normal change, never below 0.
  const double speed = vt.norm();
  const double kept = speed > 0.0 ? std::max(0.0, 1.0 - c.friction * normalChange / speed) : 0.0;
  out.vel = obstacleVelocity - c.restitution * vn * p.normal + kept * vt;
  return out;
  // END EXERCISE 3.8
}

}  // namespace springlab::softbody
