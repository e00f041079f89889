// Exercise 2.7, spring force Jacobians (labs/02_net/jacobian.cpp): its public tests.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

class SpringJacobian : public springlab::testing::Seeded {};

TEST_F(SpringJacobian, MatchesFiniteDifferencesOfTheForce) {
  for (int t = 0; t < 50; ++t) {
    const Vec3 x2 = vec3(-1, 1), dir = vec3(-1, 1).normalized(), v1 = vec3(-1, 1), v2 = vec3(-1, 1);
    const double L0 = uniform(0.1, 1), k = uniform(1, 500), kd = uniform(0, 2);
    const Vec3 x1 = x2 + uniform(1.05, 2.0) * L0 * dir;  // stretched: no clamp
    const auto J = springJacobian(x1, x2, k, L0, kd);
    const double h = 1e-6;
    Mat3 dx, dv;
    for (int c = 0; c < 3; ++c) {
      const Vec3 step = h * Vec3::Unit(c);
      // Position derivative without relative velocity (the damper's own dF/dx is left out).
      dx.col(c) = (springDamperForce(x1 + step, x2, v1, v1, k, L0, kd) - springDamperForce(x1 - step, x2, v1, v1, k, L0, kd)) / (2 * h);
      dv.col(c) = (springDamperForce(x1, x2, v1 + step, v2, k, L0, kd) - springDamperForce(x1, x2, v1 - step, v2, k, L0, kd)) / (2 * h);
    }
    ASSERT_LT((J.dx - dx).norm(), 1e-5 * k) << "dF1/dx1 differs from the finite differences of the spring force for "
                                            << "a spring stretched to " << (x1 - x2).norm() / L0 << " L0 " << seedText();
    ASSERT_LT((J.dv - dv).norm(), 1e-6 * std::max(kd, 1.0)) << "dF1/dv1 differs from the finite differences of the damper "
                                                            << seedText();
  }
}

TEST_F(SpringJacobian, IsSymmetricAndNegativeSemidefinite) {
  for (int t = 0; t < 50; ++t) {
    const Vec3 x1 = vec3(-1, 1), x2 = vec3(-1, 1);
    const double L0 = (x1 - x2).norm() * uniform(0.3, 3.0);  // stretched or compressed
    const auto J = springJacobian(x1, x2, uniform(1, 500), L0, uniform(0, 2));
    ASSERT_LT((J.dx - J.dx.transpose()).norm(), 1e-12) << "dF/dx of a spring is symmetric " << seedText();
    ASSERT_LT((J.dv - J.dv.transpose()).norm(), 1e-12) << "dF/dv of a spring is symmetric " << seedText();
    const Eigen::Vector3d ex = Eigen::SelfAdjointEigenSolver<Mat3>(J.dx).eigenvalues();
    const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Mat3>(J.dv).eigenvalues();
    ASSERT_LE(ex.maxCoeff(), 1e-9) << "dF/dx must be negative semidefinite, also when compressed (clamp 1 - L0/l at 0), "
                                   << "or the implicit system is not positive definite " << seedText();
    ASSERT_LE(ev.maxCoeff(), 1e-9) << "dF/dv of a damper is negative semidefinite " << seedText();
  }
}

TEST_F(SpringJacobian, ZeroLengthSpringHasNone) {
  const Vec3 x = vec3(-1, 1);
  const auto J = springJacobian(x, x, 100, 0.5, 1);
  EXPECT_TRUE(J.dx.allFinite() && J.dv.allFinite()) << "a zero-length spring must not give NaN";
  EXPECT_EQ(J.dx, Mat3::Zero()) << "no direction, no stiffness block";
  EXPECT_EQ(J.dv, Mat3::Zero()) << "no direction, no damping block";
}

}  // namespace
}  // namespace springlab::net
