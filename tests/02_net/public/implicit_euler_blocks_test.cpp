// Exercise 2.9, implicit Euler with per-particle blocks (labs/02_net/implicit_euler_blocks.cpp): its public tests.
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
using springlab::testing::blowsUp;
using springlab::testing::ImplicitCase;
using ImplicitEulerBlocks = ImplicitCase;

TEST_F(ImplicitEulerBlocks, OneFreeMassMatchesTheFullSystem) { checkBackwardEuler("implicit_euler_blocks"); }

TEST_F(ImplicitEulerBlocks, PinnedMassesNeverMove) { checkPinnedNeverMove("implicit_euler_blocks"); }

TEST_F(ThesisCloth, PerParticleBlocksStayStable) {
  double lowest = 0.0;
  EXPECT_FALSE(blowsUp(netRegistry().makeIntegrator("implicit_euler_blocks"), 10.0, &lowest))
      << "implicit Euler with per-particle blocks must stay stable on the thesis' cloth at dt = 1/60 s";
  EXPECT_TRUE(std::isfinite(lowest)) << "and finite";
}

}  // namespace
}  // namespace springlab::net
