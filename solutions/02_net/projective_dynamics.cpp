#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 projectSpring(const Vec3& x1, const Vec3& x2, double restLength) {
  // BEGIN EXERCISE 2.12
  // The nearest vector of length L0: the current direction, scaled to the rest length.
  const Vec3 d = x1 - x2;
  const double l = d.norm();
  if (l == 0.0) return Vec3::Zero();
  return (restLength / l) * d;
  // END EXERCISE 2.12
}

}  // namespace springlab::net
