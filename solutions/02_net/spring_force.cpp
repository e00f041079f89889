#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant) {
  // BEGIN EXERCISE 2.2
  // Direction from mass 2 to mass 1; a zero-length spring has none and exerts no force.
  const Vec3 x12 = x1 - x2;
  const double l = x12.norm();
  if (l == 0.0) return Vec3::Zero();
  const double inverseLength = 1.0 / l;  // one division, then products: e = x12 / l

  // Hooke's law along e, plus damping of the relative velocity along e.
  const double alongSpeed = (v1 - v2).dot(x12) * inverseLength;
  return (-springConstant * (l - springLength) - frictionConstant * alongSpeed) * inverseLength * x12;
  // END EXERCISE 2.2
}

}  // namespace springlab::net
