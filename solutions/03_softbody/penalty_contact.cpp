#include <algorithm>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

Vec3 penaltyContactForce(const Penetration& p, const Vec3& relativeVelocity, const ContactMaterial& c) {
  // BEGIN EXERCISE 3.7
  if (!p.touching) return Vec3::Zero();
  // Normal: a virtual spring pushing out by the depth, damped, and never pulling inwards.
  const double vn = relativeVelocity.dot(p.normal);
  const double normalForce = std::max(0.0, c.stiffness * p.depth - c.damping * vn);

  // Tangential: viscous friction, capped by Coulomb's law at mu times the normal force.
  const Vec3 vt = relativeVelocity - vn * p.normal;
  Vec3 tangential = -c.damping * vt;
  const double limit = c.friction * normalForce;
  if (tangential.norm() > limit) tangential *= limit / tangential.norm();
  return normalForce * p.normal + tangential;
  // END EXERCISE 3.7
}

}  // namespace springlab::softbody
