// How far the per-particle blocks (implicit_euler_blocks) are from the implicit Euler step they
// approximate, on the light fabric of net_hanging.json (without its sphere) at r = 32 after
// 5 s. One block-Jacobi sweep solves each mass against its neighbours' old velocities: the
// cloth behaves far stiffer than its springs and hangs a fraction of the full solve's drape.
// handouts/02_net.md ("Per-particle blocks") quotes these figures; the bounds hold them.
// Measured with the tethers at an eighth of the stretch allowance (net.cpp): full solve
// 1.010 m, one sweep 0.650 m, up to 400 sweeps to a residual of 1e-4: 1.010 m (before, with
// tethers at the whole allowance: 1.016, 0.000 (the cloth stayed flat) and 1.016 m).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <springlab/diagnostics.hpp>
#include <springlab/simulation.hpp>

#include "study_registry.hpp"

namespace springlab {
namespace {

using testing::allLabs;
using testing::shippedScene;

// The lowest point's drop below the pins (m) after 5 s.
double drapeAfter5s(const std::string& integrator, int sweeps = 1) {
  SceneDocument d = shippedScene("net_hanging.json");
  d.set("net.resolution=32");
  d.set("net.colliders.spheres=[]");
  d.set("integrator=" + integrator);
  if (sweeps > 1) d.json["solver"] = {{"block_sweeps", sweeps}, {"block_tolerance", 1e-4}};
  const LoadedScene scene = allLabs().loadScene(d);
  // One sweep at the scene's dt is past its limit and is reported (OneSweepAtTheScenesStepIs
  // ReportedUnstable); its drape is measured all the same, as the handout quotes it.
  scene.sim->setBlowUpCheck(false);
  const double dt = scene.settings.dt;
  for (int n = 0; n < static_cast<int>(5.0 / dt + 0.5); ++n) scene.sim->operate(dt);
  double lowest = INFINITY;
  for (const Vec3& x : scene.sim->state.pos) lowest = std::min(lowest, x.y());
  return -lowest;
}

TEST(PerParticleBlocks, OneSweepHangsFarShorterThanTheFullSolve) {
  const double full = drapeAfter5s("implicit_euler");
  const double blocks = drapeAfter5s("implicit_euler_blocks");
  const double error = std::abs(blocks - full) / full;
  std::printf("drape after 5 s: full solve %.4f m, one block sweep %.4f m, relative error %.3f\n", full, blocks, error);
  EXPECT_GT(full, 0.9) << "the full implicit solve lets the fabric hang about 1 m";
  EXPECT_LT(blocks, 0.8 * full) << "one block sweep is much stiffer: the error the handout reports";
}

// One sweep at the scene's 1/120 s is far past its limit (0.6 ms): the cloth gains about 10 J
// per step, which the stretch limit takes out again, and its total energy stays near 4 J, far
// below the allowance of half the energy scale (272 J) that `sim` gives without a measured swing.
// The check holds the step's own energy (the total less the corrections' work) and reports it.
TEST(PerParticleBlocks, OneSweepAtTheScenesStepIsReportedUnstable) {
  SceneDocument d = shippedScene("net_hanging.json");
  d.set("net.resolution=32");
  d.set("net.colliders.spheres=[]");
  d.set("integrator=implicit_euler_blocks");
  const LoadedScene scene = allLabs().loadScene(d);
  const double dt = scene.settings.dt;
  try {
    for (int n = 0; n < static_cast<int>(5.0 / dt + 0.5); ++n) scene.sim->operate(dt);
    ADD_FAILURE() << "one block sweep at " << dt << " s ran 5 s unreported; total energy "
                  << scene.sim->energies().total() << " J";
  } catch (const BlowUp& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("passivity"), std::string::npos) << why;
    EXPECT_NE(why.find("corrections after each step"), std::string::npos) << why;
    EXPECT_LT(scene.sim->energies().total(), 20.0) << "the total energy itself stays small";
  }
}

TEST(PerParticleBlocks, SweepsToATolerancePullTowardsTheFullSolve) {
  const double full = drapeAfter5s("implicit_euler");
  const double one = drapeAfter5s("implicit_euler_blocks");
  const double swept = drapeAfter5s("implicit_euler_blocks", 400);
  std::printf("drape after 5 s: full %.4f m, 1 sweep %.4f m, up to 400 sweeps %.4f m\n", full, one, swept);
  EXPECT_LT(std::abs(swept - full), std::abs(one - full)) << "more sweeps, closer to the system they approximate";
  // Measured: 1.0159 m against 1.0161 m (block_tolerance 1e-4).
  EXPECT_LT(std::abs(swept - full), 0.01 * full) << "sweeps to a tolerance of 1e-4 reach the full solve's drape within 1 %";
}

}  // namespace
}  // namespace springlab
