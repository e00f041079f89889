#include <algorithm>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

SpringJacobian springJacobian(const Vec3& x1, const Vec3& x2, double springConstant, double springLength,
                              double frictionConstant) {
  // BEGIN EXERCISE 2.7
  SpringJacobian J;
  const Vec3 x12 = x1 - x2;
  const double l = x12.norm();
  if (l == 0.0) return J;
  const double inverseLength = 1.0 / l;
  const Vec3 e = inverseLength * x12;
  const Mat3 along = e * e.transpose();

  // Stiffness along the spring, plus the tension's pull across it (never negative):
  // c (I - e e^T) + e e^T = c I + (1 - c) e e^T.
  const double across = std::max(0.0, 1.0 - springLength * inverseLength);
  J.dx = (-springConstant * (1.0 - across)) * along;
  J.dx.diagonal().array() -= springConstant * across;
  // The damper acts along the spring only.
  J.dv = -frictionConstant * along;
  return J;
  // END EXERCISE 2.7
}

}  // namespace springlab::net
