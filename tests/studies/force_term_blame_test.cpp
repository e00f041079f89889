// A NaN planted in one force term of a shipped scene (through the panel's slider, as a
// student's broken exercise would make it) stops the run with a message that names the
// lab's term and its exercise, not dt.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// The shipped scene with the scene keys (`--set` assignments) and then the named sliders set,
// stepped with an explicit integrator (an implicit one may solve a NaN right-hand side to a
// finite step); the BlowUp message of the first steps ("" and a failure when none comes).
std::string blowUpMessageWith(const std::string& scene, const std::vector<std::pair<std::string, double>>& sliders,
                              const std::vector<std::string>& keys = {}) {
  SceneDocument document = shippedScene(scene);
  for (const std::string& key : keys) document.set(key);
  LoadedScene loaded = allLabs().loadScene(document);
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(allLabs().makeIntegrator("symplectic_euler"));
  for (const auto& [label, value] : sliders) {
    bool found = false;
    for (const Parameter& p : sim.parameters()) {
      if (p.label == label) {
        p.set(value);
        found = true;
      }
    }
    EXPECT_TRUE(found) << scene << " has no slider \"" << label << "\"";
  }
  try {
    for (int step = 0; step < 10; ++step) sim.operate(loaded.settings.dt);
  } catch (const BlowUp& e) {
    return e.what();
  }
  ADD_FAILURE() << scene << ": the planted NaN should have stopped the run with a BlowUp";
  return "";
}

TEST(ForceTermBlame, RopeGroundContactIsNamed) {
  // The ground above the rope, pushing with a NaN stiffness: exercise 1.3's term.
  const std::string what = blowUpMessageWith("rope.json", {{"ground height", 1.0}, {"ground repulsion", NAN}});
  EXPECT_NE(what.find("from the rope's ground contact (exercise 1.3, groundContactForce)"), std::string::npos) << what;
  EXPECT_NE(what.find("dt is not the cause"), std::string::npos) << what;
  EXPECT_EQ(what.find("too large"), std::string::npos) << what;
}

TEST(ForceTermBlame, RopeAirFrictionIsNamedWithGravity) {
  const std::string what = blowUpMessageWith("rope.json", {{"air friction", NAN}});
  EXPECT_NE(what.find("from the rope's gravity and air friction (exercise 1.2"), std::string::npos) << what;
}

TEST(ForceTermBlame, NetWindIsNamed) {
  const std::string what = blowUpMessageWith("net_flag.json", {{"wind strength", NAN}});
  EXPECT_NE(what.find("from the net's wind (exercises 2.3 and 2.4"), std::string::npos) << what;
}

TEST(ForceTermBlame, SoftBodyPressureIsNamed) {
  const std::string what = blowUpMessageWith("softbody_ball.json", {{"pressure at rest volume", NAN}});
  EXPECT_NE(what.find("from the soft body's gas pressure"), std::string::npos) << what;
}

TEST(ForceTermBlame, SoftBodySpringsAreNamed) {
  const std::string what = blowUpMessageWith("softbody_ball.json", {{"spring constant", NAN}});
  EXPECT_NE(what.find("from the soft body's spring forces (exercise 3.1"), std::string::npos) << what;
}

TEST(ForceTermBlame, TheDiagnosisLeavesEveryTermOn) {
  // After the diagnosis the scene's forces are whole again: a reset run of a healthy rope
  // matches a fresh one.
  LoadedScene fresh = allLabs().loadScene(shippedScene("rope.json"));
  LoadedScene diagnosed = allLabs().loadScene(shippedScene("rope.json"));
  for (const Parameter& p : diagnosed.sim->parameters()) {
    if (p.label == "air friction") p.set(NAN);
  }
  EXPECT_THROW(diagnosed.sim->operate(0.002), BlowUp);
  for (const Parameter& p : diagnosed.sim->parameters()) {
    if (p.label == "air friction") p.set(0.02);
  }
  diagnosed.sim->reset();
  std::vector<Vec3> a, b;
  fresh.sim->evaluateForces(fresh.sim->state, a);
  diagnosed.sim->evaluateForces(diagnosed.sim->state, b);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "mass " << i;
}

}  // namespace
}  // namespace springlab
