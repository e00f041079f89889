// Exercises 2.7 to 2.9: the spring Jacobians, implicit Euler on the sparse system and with
// per-particle blocks, and the cloth thesis' case where explicit Euler fails.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using ThesisCloth = springlab::testing::Seeded;
using springlab::testing::netRegistry;
using springlab::testing::quietNet;
using springlab::testing::thesisCloth;

// ---- 2.7 ------------------------------------------------------------------------------

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

// ---- 2.8 and 2.9 ------------------------------------------------------------------------

// One free mass on one spring to a pinned mass, moving along the spring.
class OneSpring final : public Simulation {
 public:
  OneSpring(double m, double k, double L0, double kd) : Simulation(3) {
    masses = {Mass{m, true}, Mass{m, false}};
    editSprings() = {Spring{1, 0, k, L0, kd, SpringKind::Structural}};
    state.pos = {Vec3::Zero(), Vec3(L0, 0, 0)};
    state.vel = {Vec3::Zero(), Vec3::Zero()};
    markInitialState();
  }
  std::string kind() const override { return "one spring"; }
  bool addForceJacobian(const State& s, ForceJacobian& J) override {
    const Spring& sp = springs()[0];
    const auto j = springJacobian(s.pos[1], s.pos[0], sp.springConstant, sp.springLength, sp.frictionConstant);
    J.pairs.push_back({1, 0, j.dx, j.dv});
    return true;
  }

 protected:
  void accumulateForces(const State& s, std::vector<Vec3>& f) override {
    const Spring& sp = springs()[0];
    f[1] += springDamperForce(s.pos[1], s.pos[0], s.vel[1], s.vel[0], sp.springConstant, sp.springLength, sp.frictionConstant);
  }
};

// Checks both implicit integrators share.
class ImplicitCase : public springlab::testing::Seeded {
 protected:
  void checkBackwardEuler(const std::string& method);
  void checkPinnedNeverMove(const std::string& method);
};
using ImplicitEuler = ImplicitCase;
using ImplicitEulerBlocks = ImplicitCase;

// Backward Euler for m x'' = -k (x - L0) - kd x' along the spring, five steps.
void ImplicitCase::checkBackwardEuler(const std::string& method) {
  const double m = uniform(0.1, 2), k = uniform(10, 1000), L0 = uniform(0.2, 1), kd = uniform(0, 2);
  const double dt = uniform(0.005, 0.1);
  OneSpring sim(m, k, L0, kd);
  sim.setIntegrator(netRegistry().makeIntegrator(method));
  sim.setBlowUpCheck(false);
  double x = L0 + uniform(0.05, 0.3) * L0, v = uniform(-1, 1);
  sim.state.pos[1].x() = x;
  sim.state.vel[1].x() = v;
  for (int n = 0; n < 5; ++n) {
    sim.operate(dt);
    // (m + dt kd + dt^2 k) dv = dt (F + dt (-k) v)
    const double dv = dt * (-k * (x - L0) - kd * v - dt * k * v) / (m + dt * kd + dt * dt * k);
    v += dv;
    x += dt * v;
    ASSERT_NEAR(sim.state.vel[1].x(), v, 1e-6 * std::max(1.0, std::abs(v)))
        << method << ": one free mass on a spring must follow backward Euler exactly, "
        << "(m + dt kd + dt^2 k) dv = dt (F - dt k v), at step " << n + 1 << " " << seedText();
    ASSERT_NEAR(sim.state.pos[1].x(), x, 1e-6 * std::max(1.0, std::abs(x))) << method << ": x' = x + dt v' " << seedText();
  }
  ASSERT_EQ(sim.state.pos[0], Vec3::Zero()) << method << ": the pinned end never moves";
}

TEST_F(ImplicitEuler, OneSpringIsBackwardEulerExactly) { checkBackwardEuler("implicit_euler"); }

TEST_F(ImplicitEulerBlocks, OneFreeMassMatchesTheFullSystem) { checkBackwardEuler("implicit_euler_blocks"); }

void ImplicitCase::checkPinnedNeverMove(const std::string& method) {
  NetParameters p = thesisCloth();
  p.resolution = integer(4, 10);
  p.pins = {Pin::Corner00, Pin::Corner11, Pin::EdgeU1};
  Net net(3, p);
  net.setIntegrator(netRegistry().makeIntegrator(method));
  const std::vector<Vec3> start = net.state.pos;
  for (int n = 0; n < 60; ++n) {
    net.operate(1.0 / 60.0);
    for (int i = 0; i < net.numOfMasses(); ++i) {
      if (net.masses[i].pinned) {
        ASSERT_EQ(net.state.pos[i], start[i]) << method << ": pinned mass " << i << " moved at step " << n + 1;
        ASSERT_EQ(net.state.vel[i], Vec3::Zero()) << method << ": pinned mass " << i << " has a velocity";
      }
    }
  }
}

TEST_F(ImplicitEuler, PinnedMassesNeverMove) { checkPinnedNeverMove("implicit_euler"); }

TEST_F(ImplicitEulerBlocks, PinnedMassesNeverMove) { checkPinnedNeverMove("implicit_euler_blocks"); }

TEST_F(ImplicitEuler, ConservesMomentumOfAFreeNet) {
  // No pins, gravity or wind: the springs alone cannot change the momentum.
  NetParameters p = quietNet(integer(4, 9));
  p.particleMass = uniform(0.05, 0.5);
  Net net(3, p);
  net.setIntegrator(netRegistry().makeIntegrator("implicit_euler"));
  for (int i = 0; i < net.numOfMasses(); ++i) {
    net.state.pos[i] += vec3(-0.05, 0.05);
    net.state.vel[i] = vec3(-1, 1);
  }
  const Vec3 before = net.momentum();
  double impulse = 0.0;  // how much force the springs exerted, for the tolerance
  for (int n = 0; n < 20; ++n) {
    net.operate(0.02);
    for (const Vec3& f : net.force) impulse += 0.02 * f.norm();
  }
  EXPECT_LT((net.momentum() - before).norm(), 1e-5 * impulse + 1e-12)
      << "implicit Euler changed the momentum of a free net by " << (net.momentum() - before).norm()
      << " kg m/s: each pair's blocks must be equal and opposite " << seedText();
  EXPECT_GT(net.stats.solverIterations, 0) << "the integrator counts the conjugate gradient iterations";
}

// The thesis' cloth for `seconds` at dt = 1/60 s; true when it blew up (BlowUp thrown).
bool blowsUp(std::unique_ptr<Integrator> integrator, double seconds, double* lowest = nullptr) {
  Net net(3, thesisCloth());
  net.setIntegrator(std::move(integrator));
  try {
    for (int n = 0; n < static_cast<int>(seconds * 60); ++n) net.operate(1.0 / 60.0);
  } catch (const BlowUp&) {
    return true;
  }
  if (lowest) {
    *lowest = INFINITY;
    for (const Vec3& x : net.state.pos) *lowest = std::min(*lowest, x.y());
  }
  return false;
}

TEST_F(ThesisCloth, ExplicitEulerBlowsUpImplicitEulerStaysStable) {
  EXPECT_TRUE(blowsUp(std::make_unique<springlab::testing::ForwardEuler>(), 10.0))
      << "with k = 75/22/8 N/m, kd = 0.25 N s/m, m = 1 kg and dt = 1/60 s explicit Euler must blow up "
      << "(and the framework must report it as a BlowUp)";
  double lowest = 0.0;
  EXPECT_FALSE(blowsUp(netRegistry().makeIntegrator("implicit_euler"), 10.0, &lowest))
      << "implicit Euler must stay stable on the same cloth at the same dt";
  EXPECT_TRUE(std::isfinite(lowest)) << "implicit Euler's cloth must stay finite";
}

TEST_F(ThesisCloth, PerParticleBlocksStayStable) {
  double lowest = 0.0;
  EXPECT_FALSE(blowsUp(netRegistry().makeIntegrator("implicit_euler_blocks"), 10.0, &lowest))
      << "implicit Euler with per-particle blocks must stay stable on the thesis' cloth at dt = 1/60 s";
  EXPECT_TRUE(std::isfinite(lowest)) << "and finite";
}

}  // namespace
}  // namespace springlab::net
