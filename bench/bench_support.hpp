#pragma once
// What the benchmarks share: the scenes they time, the thread count, and per-step counters.
// Everything here times the reference solutions; README.md's "Performance" section shows the
// table `./springlab bench` prints from these benchmarks.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include <springlab/registry.hpp>
#include <springlab/simulation.hpp>

#include <springlab/net/net.hpp>

namespace springlab::bench {

// A registry with the framework's and every lab's integrators and scene kinds.
const Registry& registry();

// The cloth of the benchmarks: 1 m x 1 m, r x r masses, lying flat, held at two corners of one
// edge, under gravity, with nothing else (no wind, colliders or corrections).
//   material 0 "thesis": 1 kg per mass, k = 75 / 22 / 8 N/m, kd = 0.25 N s/m (the cloth thesis);
//   material 1 "fabric": 0.2 kg/m^2, k = 400 / 150 / 15 N/m; light masses on stiff springs,
//     so the implicit system is badly conditioned (dt^2 k / m ~ 2e4 at r = 64, dt = 1/60 s).
net::NetParameters cloth(int r, int material);
// The thesis' frame: the thesis cloth plus what its table times besides forces and
// integration: a sphere under the cloth and a ground plane (collisions), stretch limiting to
// 10 % (stretch limit), thesis-model wind (normals).
net::NetParameters thesisFrame(int r);

// A scene file of scenes/ with KEY=VALUE changes.
LoadedScene loadScene(const std::string& file, const std::vector<std::string>& sets = {});

// Run OpenMP's loops on `threads` threads (no-op without OpenMP).
void useThreads(int threads);

// Time `sim.operate(dt)` per iteration after `warmup` steps, and report per step: the
// phases of sim.profile (ms), force evaluations and solver iterations, masses and springs.
void timeSteps(benchmark::State& bench, Simulation& sim, double dt, int warmup);
// timeSteps on a scene file of scenes/ with KEY=VALUE changes, at the scene's dt.
void timeScene(benchmark::State& bench, const std::string& file, const std::vector<std::string>& sets, int warmup);

}  // namespace springlab::bench
