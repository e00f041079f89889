#include <springlab/net/exercises.hpp>

namespace springlab::net {

DistanceCorrection xpbdDistanceConstraint(const Vec3& x1, const Vec3& x2, const Vec3& prev1, const Vec3& prev2,
                                          double w1, double w2, double restLength, double alphaTilde, double gamma,
                                          double lambda) {
  // BEGIN EXERCISE 2.11
  DistanceCorrection out;
  const Vec3 d = x1 - x2;
  const double l = d.norm();
  const double denominator = (1.0 + gamma) * (w1 + w2) + alphaTilde;
  if (l == 0.0 || denominator == 0.0) return out;
  const Vec3 e = d * (1.0 / l);  // one division, not three (this runs millions of times a frame)

  // The constraint, its compliance term and its damping term (the velocity along e).
  const double C = l - restLength;
  const double along = e.dot((x1 - prev1) - (x2 - prev2));
  out.dlambda = (-C - alphaTilde * lambda - gamma * along) / denominator;

  // Each end moves along the gradient (e for x1, -e for x2), weighted by its inverse mass.
  out.dx1 = (w1 * out.dlambda) * e;
  out.dx2 = (-w2 * out.dlambda) * e;
  return out;
  // END EXERCISE 2.11
}

}  // namespace springlab::net
