#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 springDamperForce(const Vec3& x1, const Vec3& x2, const Vec3& v1, const Vec3& v2,
                       double springConstant, double springLength, double frictionConstant) {
  // BEGIN EXERCISE 1.1
  // Direction from mass 2 to mass 1; a zero-length spring has none and exerts no force.
  const Vec3 x12 = x1 - x2;
  const double l = x12.norm();
  if (l == 0.0) return Vec3::Zero();
  const Vec3 e = x12 / l;

  // Hooke's law along e, plus damping of the relative velocity along e.
  return -springConstant * (l - springLength) * e - frictionConstant * (v1 - v2).dot(e) * e;
  // END EXERCISE 1.1
}

}  // namespace springlab::rope
