// A computation in the middle of a run that resets and steps the scene (the blow-up check's
// stability limit, which `sim` and the viewer compute when a detector is about to fire) must
// leave the run as it was: the run then goes on step for step as one that was never
// interrupted. The oracle is that uninterrupted twin, stepped with symplectic Euler (a method
// with no history, so nothing is lost to the restart) through the same user input.
// Without the lab's own data in Simulation::saveRun the rope's fixed end, carried by the
// user's keys, jumped back to its start (seeds.rope FixedEnd, 3 of 300 seeds) and a dragged
// collider went back to where the scene put it.
#include <gtest/gtest.h>

#include <functional>
#include <ostream>
#include <string>

#include <springlab/step_stability.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

struct UserInput {
  std::string scene;
  // What the user does before each step (k counts steps from 0): keys, a drag.
  std::function<void(Simulation&, int k)> act;
};

void PrintTo(const UserInput& input, std::ostream* os) { *os << input.scene; }

// The index in shapes() of the first shape the user may drag.
int firstMovableShape(const Simulation& sim) {
  const std::vector<Shape> shapes = sim.shapes();
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    if (shapes[i].movable) return static_cast<int>(i);
  }
  return -1;
}

// Drag the first movable shape 1 mm a step along x from where it is.
void dragAlongX(Simulation& sim, int k) {
  (void)k;
  const int index = firstMovableShape(sim);
  ASSERT_GE(index, 0) << "the scene has no shape the user may drag";
  const Vec3 at = sim.shapes()[static_cast<std::size_t>(index)].center;
  sim.moveShape(index, at + Vec3(0.001, 0.0, 0.0));
}

void runSteps(Simulation& sim, const UserInput& input, int from, int count, double dt) {
  for (int k = from; k < from + count; ++k) {
    input.act(sim, k);
    sim.operate(dt);
  }
}

class ARunInterruptedByALimit : public ::testing::TestWithParam<UserInput> {};

TEST_P(ARunInterruptedByALimit, GoesOnAsIfNeverInterrupted) {
  const UserInput& input = GetParam();
  const SceneDocument scene = shippedScene(input.scene);
  LoadedScene interrupted = allLabs().loadScene(scene);
  LoadedScene twin = allLabs().loadScene(scene);
  interrupted.sim->setIntegrator(allLabs().makeIntegrator("symplectic_euler"));
  twin.sim->setIntegrator(allLabs().makeIntegrator("symplectic_euler"));
  // Half the limit at the start: a run that stays stable whatever the user does.
  const double dt = 0.5 * stepStableDt(*interrupted.sim);
  runSteps(*interrupted.sim, input, 0, 100, dt);
  runSteps(*twin.sim, input, 0, 100, dt);

  const Simulation::SavedRun saved = interrupted.sim->saveRun();
  const double limit = stepStableDt(*interrupted.sim);  // resets the scene and runs it
  EXPECT_GT(limit, 0.0);
  interrupted.sim->resumeRun(saved);

  runSteps(*interrupted.sim, input, 100, 100, dt);
  runSteps(*twin.sim, input, 100, 100, dt);
  ASSERT_EQ(interrupted.sim->stats.steps, twin.sim->stats.steps);
  EXPECT_EQ(interrupted.sim->state.time, twin.sim->state.time);
  for (int i = 0; i < twin.sim->numOfMasses(); ++i) {
    ASSERT_EQ(interrupted.sim->state.pos[i], twin.sim->state.pos[i]) << "mass " << i;
    ASSERT_EQ(interrupted.sim->state.vel[i], twin.sim->state.vel[i]) << "mass " << i;
  }
  const std::vector<Shape> shapes = interrupted.sim->shapes(), twinShapes = twin.sim->shapes();
  ASSERT_EQ(shapes.size(), twinShapes.size());
  for (std::size_t j = 0; j < shapes.size(); ++j) EXPECT_EQ(shapes[j].center, twinShapes[j].center) << "shape " << j;
  EXPECT_EQ(interrupted.sim->sourceWork(), twin.sim->sourceWork());
  EXPECT_EQ(interrupted.sim->correctionWork(), twin.sim->correctionWork());
}

INSTANTIATE_TEST_SUITE_P(
    UserInput, ARunInterruptedByALimit,
    ::testing::Values(
        // The arrow keys carry the rope's fixed end at 0.5 m/s.
        UserInput{"rope.json", [](Simulation& sim, int) { sim.setControlVelocity(Vec3(0.5, 0.0, 0.0)); }},
        // The user drags the sphere under the falling cloth, and the one pressed into the ball.
        UserInput{"net_sphere_drop.json", dragAlongX}, UserInput{"softbody_user_sphere.json", dragAlongX}),
    [](const ::testing::TestParamInfo<UserInput>& param) {
      std::string name = param.param.scene.substr(0, param.param.scene.find('.'));
      for (char& c : name) {
        if (c == '_') c = 'X';
      }
      return name;
    });

}  // namespace
}  // namespace springlab
