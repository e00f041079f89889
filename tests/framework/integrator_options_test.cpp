// A scene's "integrator_options" reach the method they name, survive a change of integrator
// (studies switch methods on a loaded scene), and bad names or values are refused with the key.
#include <gtest/gtest.h>

#include <springlab/registry.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

// A do-nothing method with one option, remembering the value it was given.
class Sweeps final : public Integrator {
 public:
  std::string name() const override { return "sweeps"; }
  int order() const override { return 1; }
  double stabilityConstant() const override { return 2.0; }
  void step(Simulation& sim, double dt) override { sim.state.time += dt; }
  std::vector<std::string> optionNames() const override { return {"iterations"}; }
  void setOption(const std::string& option, int value) override {
    if (option != "iterations") Integrator::setOption(option, value);
    iterations = value;
  }
  int iterations = 1;
};

Registry toyRegistry() {
  Registry r;
  registerFramework(r);
  r.addIntegrator("sweeps", [] { return std::make_unique<Sweeps>(); });
  r.addScene("toy", [](SceneReader&, const SceneSettings&) {
    return std::make_unique<testing::AnchoredOscillators>(1, 1.0, 1.0);
  });
  return r;
}

LoadedScene load(const Registry& r, const std::string& options) {
  SceneReader reader = SceneReader::fromText(R"({"lab": "toy", "name": "toy", "description": "", "dimension": 3, "dt": 0.01, "substeps": 1,
    "integrator": "sweeps", "gravity": [0, 0, 0], "toy": {})" + options + "}", "scenes/toy.json");
  return r.loadScene(reader);
}

TEST(IntegratorOptions, SceneOptionsReachTheMethodAndSurviveASwitch) {
  const Registry r = toyRegistry();
  LoadedScene scene = load(r, R"(, "integrator_options": {"sweeps": {"iterations": 7}})");
  EXPECT_EQ(dynamic_cast<Sweeps&>(scene.sim->integrator()).iterations, 7) << "the scene's option must reach the method";
  scene.sim->setIntegrator(r.makeIntegrator("symplectic_euler"));
  scene.sim->setIntegrator(r.makeIntegrator("sweeps"));
  EXPECT_EQ(dynamic_cast<Sweeps&>(scene.sim->integrator()).iterations, 7)
      << "a method set later on the same scene (as studies do) must get the scene's options too";
  LoadedScene plain = load(r, "");
  EXPECT_EQ(dynamic_cast<Sweeps&>(plain.sim->integrator()).iterations, 1) << "without options the method's default";
}

TEST(IntegratorOptions, UnknownNamesAndBadValuesAreRefusedWithTheKey) {
  const Registry r = toyRegistry();
  const auto message = [&](const std::string& options) {
    try {
      load(r, options);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string method = message(R"(, "integrator_options": {"sweep": {"iterations": 7}})");
  EXPECT_NE(method.find("sweep"), std::string::npos) << method;
  EXPECT_NE(method.find("scenes/toy.json"), std::string::npos) << method;
  const std::string option = message(R"(, "integrator_options": {"sweeps": {"iteration": 7}})");
  EXPECT_NE(option.find("iteration"), std::string::npos) << option;
  const std::string value = message(R"(, "integrator_options": {"sweeps": {"iterations": 0}})");
  EXPECT_NE(value.find("iterations"), std::string::npos) << value;
}

}  // namespace
}  // namespace springlab
