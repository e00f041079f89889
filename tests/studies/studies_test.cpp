// The study tools: resolution rules keep the physical object, observables, the advisor.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <springlab/studies/resolution.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

TEST(RopeResolution, KeepsLengthMassAndStretch) {
  const SceneDocument rope = shippedScene("rope.json");
  const SceneDocument fine = allLabs().atResolution(rope, 159);
  auto total = [](const SceneDocument& d, const char* key) {
    const auto& r = d.json["rope"];
    return r[key].get<double>() * (r["masses"].get<int>() - 1);
  };
  EXPECT_EQ(allLabs().resolution(fine), 159);
  EXPECT_NEAR(total(fine, "rest_length"), total(rope, "rest_length"), 1e-12) << "the rope's length must not change";
  EXPECT_NEAR(total(fine, "mass"), total(rope, "mass"), 1e-12) << "the rope's free mass must not change";
  const auto& a = rope.json["rope"];
  const auto& b = fine.json["rope"];
  EXPECT_NEAR(b["spring_constant"].get<double>() * b["rest_length"].get<double>(),
              a["spring_constant"].get<double>() * a["rest_length"].get<double>(), 1e-9)
      << "k L0 sets the stretch under load and must not change";
  EXPECT_NO_THROW(allLabs().loadScene(fine));
}

TEST(BallResolution, NestedKeyRefinesTheMeshAndKeepsTheMass) {
  const SceneDocument ball = shippedScene("softbody_ball.json");
  const SceneDocument coarse = allLabs().atResolution(ball, 1);
  EXPECT_EQ(allLabs().resolution(coarse), 1);
  EXPECT_EQ(coarse.json["softbody"]["mesh"]["subdivisions"].get<int>(), 1) << "the dotted key mesh.subdivisions is nested";
  EXPECT_EQ(coarse.json["softbody"]["total_mass"], ball.json["softbody"]["total_mass"]);
  EXPECT_EQ(allLabs().loadScene(coarse).sim->numOfMasses(), 42) << "an icosphere of 1 subdivision has 42 vertices";
}

TEST(NetResolution, KeepsTheTotalMassOfAPerParticleNet) {
  SceneDocument net = shippedScene("net_hanging.json");
  auto totalMass = [](const SceneDocument& d) {
    double m = 0.0;
    const LoadedScene scene = allLabs().loadScene(d);  // alive while the loop reads its masses
    for (const Mass& mass : scene.sim->masses) m += mass.m;
    return m;
  };
  const double total = totalMass(net);
  net.json["net"].erase("areal_density");
  net.json["net"]["particle_mass"] = total / 400.0;  // 20 x 20 masses
  const SceneDocument fine = allLabs().atResolution(net, 31);
  EXPECT_EQ(allLabs().resolution(fine), 31);
  EXPECT_NEAR(totalMass(fine), totalMass(net), 1e-9 * total) << "the same cloth at any resolution";
}

TEST(RopeObservables, SagAndTipOfAHangingMass) {
  LoadedScene s = allLabs().loadScene(shippedScene("mass_on_spring.json"));
  const std::vector<Observable> o = s.sim->observables();
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o[0].name, "sag");
  EXPECT_DOUBLE_EQ(o[0].value, 1.0) << "the mass hangs 1 m (the rest length) below the connection";
  EXPECT_EQ(o[1].name, "tip_y");
  EXPECT_DOUBLE_EQ(o[1].value, -1.0);
}

// A small, quick advisor problem: a 20-mass rope falling for 0.5 s.
studies::Advice adviseSmallRope(double tolerance) {
  SceneDocument rope = shippedScene("rope.json");
  rope.set("rope.masses=20");
  studies::AdviseOptions o;
  o.tolerance = tolerance;
  o.duration = 0.5;
  o.samples = 10;
  o.levels = 6;
  o.resolutions = {5, 10, 20};
  o.integrators = {"symplectic_euler", "velocity_verlet", "rk4"};
  o.threads = 1;
  o.progress = false;
  return studies::advise(allLabs(), rope, o);
}

// The scene's slider labelled `label`; fails the test when there is none.
Parameter slider(Simulation& sim, const std::string& label) {
  for (const Parameter& p : sim.parameters()) {
    if (p.label == label) return p;
  }
  ADD_FAILURE() << "the " << sim.kind() << " has no parameter \"" << label << "\"";
  return {};
}

TEST(NetPanel, StiffnessSliderRetunesOnlyItsKindOfSpring) {
  LoadedScene flag = allLabs().loadScene(shippedScene("net_flag.json"));
  Simulation& sim = *flag.sim;
  std::vector<double> shearBefore;
  for (const Spring& s : sim.springs()) {
    if (s.kind == SpringKind::Shear) shearBefore.push_back(s.springConstant);
  }
  const Parameter structural = slider(sim, "structural stiffness");
  ASSERT_TRUE(structural.set);
  structural.set(123.0);
  EXPECT_EQ(structural.get(), 123.0) << "the slider reads back what it wrote";
  std::vector<double> shearAfter;
  for (const Spring& s : sim.springs()) {
    if (s.kind == SpringKind::Structural) {
      EXPECT_EQ(s.springConstant, 123.0) << "every structural spring takes the new k";
    }
    if (s.kind == SpringKind::Shear) shearAfter.push_back(s.springConstant);
  }
  EXPECT_EQ(shearAfter, shearBefore) << "shear springs keep their k";
}

TEST(NetPanel, WindAnglesTurnTheWindAndReadBack) {
  LoadedScene flag = allLabs().loadScene(shippedScene("net_flag.json"));
  Simulation& sim = *flag.sim;
  const Parameter azimuth = slider(sim, "wind azimuth"), elevation = slider(sim, "wind elevation");
  ASSERT_TRUE(azimuth.set && elevation.set);
  azimuth.set(90.0);
  elevation.set(30.0);
  EXPECT_NEAR(azimuth.get(), 90.0, 1e-9);
  EXPECT_NEAR(elevation.get(), 30.0, 1e-9);
  // A wind turned to blow along +z pushes the flag further along +z than the scene's own
  // wind (mostly along +x).
  LoadedScene unturned = allLabs().loadScene(shippedScene("net_flag.json"));
  for (int n = 0; n < 200; ++n) {
    sim.operate(flag.settings.dt);
    unturned.sim->operate(flag.settings.dt);
  }
  EXPECT_GT(sim.state.pos.back().z(), unturned.sim->state.pos.back().z() + 1e-3)
      << "the turned wind must carry the free corner further along +z";
}

TEST(SoftBodyPanel, PressureSliderSetsTheGasAtRestVolume) {
  LoadedScene ball = allLabs().loadScene(shippedScene("softbody_ball.json"));
  const Parameter pressure = slider(*ball.sim, "pressure at rest volume");
  ASSERT_TRUE(pressure.set);
  const double before = pressure.get();
  ASSERT_GT(before, 0.0);
  pressure.set(2.0 * before);
  EXPECT_NEAR(pressure.get(), 2.0 * before, 1e-9 * before) << "the slider reads back what it wrote";
  const Parameter gravity = slider(*ball.sim, "gravity y");
  gravity.set(-1.0);
  EXPECT_EQ(ball.sim->gravitation.y(), -1.0) << "the gravity slider writes gravitation";
}

TEST(SoftBodyDrag, DraggedSphereEndsTheStepAtTheCursorAndStaysWhenLetGo) {
  LoadedScene scene = allLabs().loadScene(shippedScene("softbody_user_sphere.json"));
  Simulation& sim = *scene.sim;
  int movable = -1;
  const std::vector<Shape> shapes = sim.shapes();
  for (int k = 0; k < static_cast<int>(shapes.size()); ++k) {
    if (shapes[static_cast<size_t>(k)].movable) movable = k;
  }
  ASSERT_GE(movable, 0) << "the scene has a movable sphere";
  const Vec3 from = shapes[static_cast<size_t>(movable)].center;
  const double dt = scene.settings.dt;
  sim.moveShape(movable, from + Vec3(0.01, 0, 0));
  sim.operate(dt);
  EXPECT_TRUE(sim.shapes()[static_cast<size_t>(movable)].center.isApprox(from + Vec3(0.01, 0, 0)))
      << "the sphere ends the step where the user holds it";
  sim.operate(dt);
  EXPECT_TRUE(sim.shapes()[static_cast<size_t>(movable)].center.isApprox(from + Vec3(0.01, 0, 0)))
      << "a sphere let go stays";
}

TEST(Advisor, GivesTheSameAnswerOnEveryRunAndACoarserOneForALooserTolerance) {
  const studies::Advice tight = adviseSmallRope(0.02);
  const studies::Advice again = adviseSmallRope(0.02);
  const studies::Advice loose = adviseSmallRope(0.3);
  ASSERT_GE(tight.best, 0) << "some integrator must meet 2 %";
  ASSERT_GE(loose.best, 0);
  EXPECT_EQ(tight.snippet.dump(), again.snippet.dump()) << "the advice must not depend on timing";

  const auto& t = tight.candidates[tight.best];
  const auto& l = loose.candidates[loose.best];
  const double tightCost = t.evaluationsPerSecond * tight.chosenResolution;
  const double looseCost = l.evaluationsPerSecond * loose.chosenResolution;
  EXPECT_LE(loose.chosenResolution, tight.chosenResolution);
  EXPECT_LT(looseCost, tightCost) << "a looser tolerance must allow a cheaper model: " << loose.snippet.dump()
                                  << " against " << tight.snippet.dump();
}

}  // namespace
}  // namespace springlab

namespace springlab {
namespace {

// Lab 3 pumps its gas over simulated seconds: a run at a quarter of the scene's dt (every
// chart's reference run) holds the same gas at the same time, half the target half way.
TEST(SoftBodyInflation, PumpsTheSameGasHistoryAtAnyTimeStep) {
  const auto gasAt = [](double dt, double seconds) {
    LoadedScene loaded = testing::allLabs().loadScene(std::string(SPRINGLAB_SOURCE_DIR) + "/scenes/softbody_ball.json");
    const long steps = std::lround(seconds / dt);
    for (long k = 0; k < steps; ++k) loaded.sim->operate(dt);
    for (const Observable& o : loaded.sim->observables()) {
      if (o.name == "gas nRT") return o.value;
    }
    ADD_FAILURE() << "the soft body reports no \"gas nRT\" observable";
    return 0.0;
  };
  // softbody_ball.json: nRT = 30 J pumped in over 0.1 s, dt = 0.5 ms.
  const double atSceneDt = gasAt(5e-4, 0.05);
  const double atQuarterDt = gasAt(1.25e-4, 0.05);
  EXPECT_NEAR(atSceneDt, 15.0, 1e-9) << "half way through the pumping time, half the target gas";
  EXPECT_NEAR(atQuarterDt, atSceneDt, 1e-9) << "a smaller dt pumped another gas history";
}

}  // namespace
}  // namespace springlab
