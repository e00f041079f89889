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
