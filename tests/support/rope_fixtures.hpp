#pragma once
// Small rope scenes for tests, built in code so each test states the physics it sets up.
#include <memory>

#include <springlab/registry.hpp>

#include <springlab/rope/rope.hpp>

#include "matches_reference.hpp"  // MatchesReference below

namespace springlab::testing {

// A rope with no gravity, air or ground unless the test asks for them.
inline RopeParameters quietRope(int masses, double m, double k, double restLength, double kd) {
  RopeParameters p;
  p.numOfMasses = masses;
  p.mass = m;
  p.springConstant = k;
  p.springLength = restLength;
  p.springFrictionConstant = kd;
  p.ropeConnectionPos = Vec3::Zero();
  p.ropeConnectionVel = Vec3::Zero();
  p.direction = Vec3(1, 0, 0);
  p.gravitation = Vec3::Zero();
  p.airFrictionConstant = 0.0;
  p.ground = Ground{-1.0e9, 0.0, 0.0, 0.0};
  return p;
}

// A registry with the framework's and this lab's integrators and scene kinds.
inline Registry ropeRegistry() {
  Registry r;
  registerFramework(r);
  rope::registerLab(r);
  return r;
}

}  // namespace springlab::testing

// ---- the fixture of the hidden suite MatchesReference (every tests/01_rope/hidden/*.cpp) -----
// One class for the whole suite (see matches_reference.hpp): a new hidden file uses it by name.
namespace springlab::rope {

class MatchesReference : public springlab::testing::MatchesReferenceFixture<500> {};

}  // namespace springlab::rope
