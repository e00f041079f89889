// Bullet's position-based cloth (Debian libbullet-dev, float) on the grids and steps of
// bench/net_drape.cpp, built only with SPRINGLAB_BULLET_BENCH (CMake turns it off when Bullet
// is missing). One iteration is a whole 5 s run from the flat start, one thread; counters:
// ms_per_frame (CPU time / 300 frames of 1/60 s) and drape_m (the lowest point after 5 s, m).
//   BulletClothDrape/r/material/piterations: material 0 thesis (1 kg per mass, one step of
//     1/60 s per frame), 1 fabric (0.2 kg/m^2, two steps of 1/120 s per frame); Bullet's
//     position iterations per step (piterations; 10 is what the anchor figures use). Position-
//     based cloth has no spring constant: its stretch is set by the iterations, so the fabric
//     also runs with more of them, to compare at the drape our cloth reaches (README: "at equal
//     drape").
#include <algorithm>
#include <ctime>
#include <memory>

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include "bench_support.hpp"

namespace springlab::bench {
namespace {

constexpr int kFrames = 300;  // 5 s of 1/60 s frames

// Steps per frame and the step of each material.
int stepsPerFrame(int material) { return material == 0 ? 1 : 2; }
double stepOf(int material) { return 1.0 / 60.0 / stepsPerFrame(material); }

// ---- Bullet ---------------------------------------------------------------------------------
// The world of physics.md section 6's anchor figures: CreatePatch (structural and one diagonal
// per cell, links at full stiffness) plus generateBendingConstraints(2), the total mass of
// the material, `iterations` position iterations, gravity only (no ground: the cloth hangs above it).
struct BulletCloth {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDefaultSoftBodySolver softSolver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration, &softSolver};
  btSoftBody* body = nullptr;

  BulletCloth(int r, int material, int iterations) {
    world.setGravity(btVector3(0, -9.81f, 0));
    btSoftBodyWorldInfo& info = world.getWorldInfo();
    info.m_gravity = btVector3(0, -9.81f, 0);
    info.m_broadphase = &broadphase;
    info.m_dispatcher = &dispatcher;
    info.m_sparsesdf.Initialize();
    // Corners 00 and 10 (bits 1 and 2) pinned, as in our cloth: the edge z = 0 from x = -0.5 to 0.5.
    body = btSoftBodyHelpers::CreatePatch(info, btVector3(-0.5f, 0, 0), btVector3(0.5f, 0, 0), btVector3(-0.5f, 0, 1),
                                          btVector3(0.5f, 0, 1), r, r, 1 + 2, true);
    btSoftBody::Material* bend = body->appendMaterial();
    bend->m_kLST = material == 0 ? 0.5f : 0.1f;
    body->generateBendingConstraints(2, bend);
    body->m_cfg.piterations = iterations;
    body->m_cfg.kDP = 0.005f;  // a little velocity damping, as our air friction
    const double totalMass = material == 0 ? 1.0 * r * r : 0.2;
    body->setTotalMass(static_cast<btScalar>(totalMass), false);
    world.addSoftBody(body);
  }
  ~BulletCloth() {
    world.removeSoftBody(body);
    delete body;
  }
  BulletCloth(const BulletCloth&) = delete;
  BulletCloth& operator=(const BulletCloth&) = delete;

  double lowest() const {
    double y = 0.0;
    for (int i = 0; i < body->m_nodes.size(); ++i) y = std::min(y, static_cast<double>(body->m_nodes[i].m_x.y()));
    return y;
  }
};

void BulletClothDrape(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0)), material = static_cast<int>(bench.range(1));
  const int iterations = static_cast<int>(bench.range(2));
  double drape = 0.0, cpu = 0.0;
  const auto step = static_cast<btScalar>(stepOf(material));
  for (auto _ : bench) {
    bench.PauseTiming();
    auto cloth = std::make_unique<BulletCloth>(r, material, iterations);
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    for (int n = 0; n < kFrames * stepsPerFrame(material); ++n) cloth->world.stepSimulation(step, 0, step);
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    drape = cloth->lowest();
    bench.ResumeTiming();
  }
  bench.counters["ms_per_frame"] = 1e3 * cpu / (static_cast<double>(bench.iterations()) * kFrames);
  bench.counters["drape_m"] = drape;
}
BENCHMARK(BulletClothDrape)
    ->ArgNames({"r", "material", "piterations"})
    ->ArgsProduct({{32, 64, 128}, {0, 1}, {10}})
    ->ArgsProduct({{32, 64}, {1}, {20, 40, 80}})
    ->Args({64, 1, 160})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench
