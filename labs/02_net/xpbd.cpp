#include <springlab/net/exercises.hpp>

namespace springlab::net {

DistanceCorrection xpbdDistanceConstraint(const Vec3& x1, const Vec3& x2, const Vec3& prev1, const Vec3& prev2,
                                          double w1, double w2, double restLength, double alphaTilde, double gamma,
                                          double lambda) {
  // TODO exercise 2.11 (XPBD distance constraint): write this part; see handouts/02_net.md, Exercise 2.11 (physics in section 7.a, XPBD).
  throw springlab::NotImplemented("2.11", "XPBD distance constraint", "handouts/02_net.md, Exercise 2.11 (physics in section 7.a, XPBD)");
}

}  // namespace springlab::net
