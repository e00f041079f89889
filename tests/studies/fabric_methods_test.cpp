// XPBD and projective dynamics take part in the study tools on the fabric like every other
// integrator, with no special case: the advisor weighs them with their errors, and the
// stability chart finds no dt limit for either.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <springlab/studies/resolution.hpp>
#include <springlab/studies/stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// The fabric (net_hanging.json without its sphere) on a coarse 8 x 8 grid, so a study is quick.
SceneDocument smallFabric() {
  SceneDocument fabric = shippedScene("net_hanging.json");
  fabric.set("net.colliders.spheres=[]");
  fabric.set("net.resolution=8");
  return fabric;
}

const studies::Candidate* candidate(const studies::Advice& advice, const std::string& name) {
  for (const studies::Candidate& c : advice.candidates) {
    if (c.integrator == name) return &c;
  }
  return nullptr;
}

TEST(FabricAdvisor, WeighsXpbdAndProjectiveDynamicsByTheirErrors) {
  studies::AdviseOptions o;
  o.tolerance = 0.02;
  o.duration = 0.5;
  o.samples = 10;
  o.levels = 4;
  o.resolutions = {8};
  o.threads = 1;
  o.progress = false;  // every registered integrator: the advisor's own list
  const studies::Advice advice = studies::advise(allLabs(), smallFabric(), o);
  for (const char* name : {"xpbd", "projective_dynamics"}) {
    const studies::Candidate* c = candidate(advice, name);
    ASSERT_NE(c, nullptr) << "the advisor's candidates on the fabric must include " << name;
    EXPECT_TRUE(std::isfinite(c->error) && c->error > 0.0)
        << name << ": the candidate carries its error against the RK4 reference (got " << c->error << ", note \""
        << c->note << "\")";
  }
  ASSERT_GE(advice.best, 0) << "some integrator meets 2 % on the coarse fabric";
}

TEST(FabricStability, XpbdAndProjectiveDynamicsHaveNoDtLimit) {
  studies::StabilityOptions o;
  o.integrators = {"xpbd", "projective_dynamics"};
  o.duration = 0.5;
  o.threads = 1;
  o.progress = false;
  const studies::Stability study = studies::stability(allLabs(), smallFabric(), o);
  ASSERT_EQ(study.methods.size(), 2u) << "both methods are charted (none skipped)";
  for (const studies::CriticalDt& m : study.methods) {
    EXPECT_TRUE(std::isinf(m.stabilityConstant)) << m.integrator << " declares itself stable at any dt";
    EXPECT_TRUE(std::isinf(m.measured)) << m.integrator << ": the largest trial dt survived (got " << m.measured << " s)";
  }
}

// The fabric at r = 16 after 5 s at the scene's dt (1/120 s), with `method` and its options,
// without the stretch limit: its tethers hold every method's sag near the same shape, which
// would hide how far XPBD's own springs hang.
double drapeAfterFiveSeconds(const std::string& method, const nlohmann::json& options) {
  SceneDocument fabric = smallFabric();
  fabric.set("net.resolution=16");
  fabric.set("net.stretch_limit.enabled=false");
  fabric.json["integrator_options"] = options;
  LoadedScene scene = allLabs().loadScene(fabric);
  scene.sim->setIntegrator(allLabs().makeIntegrator(method));
  for (int n = 0; n < 600; ++n) scene.sim->operate(scene.settings.dt);
  double lowest = INFINITY;
  for (const Vec3& x : scene.sim->state.pos) lowest = std::min(lowest, x.y());
  return -lowest;
}

TEST(FabricXpbd, WarmStartHangsAtTheForceModelsDrapeWithOneSweep) {
  // XPBD's multipliers from zero: one sweep per substep ends short of the tension that holds
  // the cloth, so it hangs too low. Warm-started from the last substep's tensions, its rest
  // state is the force model's equilibrium whatever the sweeps.
  const double implicit = drapeAfterFiveSeconds("implicit_euler", nlohmann::json::object());
  const double cold = drapeAfterFiveSeconds("xpbd", {{"xpbd", {{"iterations", 1}, {"substeps", 8}}}});
  const double warm = drapeAfterFiveSeconds("xpbd", {{"xpbd", {{"iterations", 1}, {"substeps", 8}, {"warm_start", 1}}}});
  EXPECT_NEAR(warm, implicit, 0.003 * implicit) << "warm-started XPBD (8 substeps x 1 sweep) must hang where the springs "
                                                   "balance gravity, as implicit Euler does";
  EXPECT_GT(std::abs(cold - implicit), 3 * std::abs(warm - implicit))
      << "from zero multipliers the same sweeps hang measurably lower (cold " << cold << " m, warm " << warm
      << " m, implicit Euler " << implicit << " m)";
}

}  // namespace
}  // namespace springlab
