// Exercise 2.8, implicit Euler with the sparse system (labs/02_net/implicit_euler.cpp): its public tests.
#include <gtest/gtest.h>

#include <cmath>

#include <springlab/net/net.hpp>
#include "net_fixtures.hpp"
#include "net_implicit.hpp"
#include "seeded.hpp"

namespace springlab::net {
namespace {

using ThesisCloth = springlab::testing::Seeded;
using springlab::testing::netRegistry;
using springlab::testing::quietNet;
using springlab::testing::blowsUp;
using springlab::testing::ImplicitCase;
using ImplicitEuler = ImplicitCase;

TEST_F(ImplicitEuler, OneSpringIsBackwardEulerExactly) { checkBackwardEuler("implicit_euler"); }

TEST_F(ImplicitEuler, PinnedMassesNeverMove) { checkPinnedNeverMove("implicit_euler"); }

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

TEST_F(ThesisCloth, ExplicitEulerBlowsUpImplicitEulerStaysStable) {
  EXPECT_TRUE(blowsUp(std::make_unique<springlab::testing::ForwardEuler>(), 10.0))
      << "with k = 75/22/8 N/m, kd = 0.25 N s/m, m = 1 kg and dt = 1/60 s explicit Euler must blow up "
      << "(and the framework must report it as a BlowUp)";
  double lowest = 0.0;
  EXPECT_FALSE(blowsUp(netRegistry().makeIntegrator("implicit_euler"), 10.0, &lowest))
      << "implicit Euler must stay stable on the same cloth at the same dt";
  EXPECT_TRUE(std::isfinite(lowest)) << "implicit Euler's cloth must stay finite";
}

}  // namespace
}  // namespace springlab::net
