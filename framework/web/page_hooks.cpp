// The page's JavaScript hook (page_hooks.js wraps these as Module.springlab): step the scene
// the viewer shows and read it, in the shape `springlab sim --out FILE.json` writes a frame,
// so a test compares the browser's physics with the native program's.
#include <emscripten.h>

#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include <springlab/diagnostics.hpp>
#include <springlab/viewer.hpp>

namespace {

using springlab::LiveViewer;

nlohmann::json toJson(const springlab::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// The scene now: time, energies, observables, positions and velocities, and what stops it.
nlohmann::json stateOf(LiveViewer& viewer) {
  nlohmann::json state;
  state["dt"] = viewer.dt();
  state["substeps"] = viewer.substeps();
  state["integrator"] = viewer.integratorName();
  state["problem"] = viewer.problem();
  springlab::Simulation* sim = viewer.simulation();
  if (!sim) return state;
  state["masses"] = sim->numOfMasses();
  state["time"] = sim->state.time;
  try {
    const springlab::Energies e = sim->energies();
    state["energy"] = {{"kinetic", e.kinetic}, {"gravitational", e.gravitational},
                       {"elastic", e.elastic}, {"other", e.other}, {"total", e.total()}};
    auto& observed = state["observables"] = nlohmann::json::object();
    for (const springlab::Observable& o : sim->observables()) observed[o.name] = o.value;
  } catch (const std::exception& e) {
    // A missing exercise: the numbers stay out, the problem says which.
    state["problem"] = e.what();
  }
  auto& pos = state["pos"] = nlohmann::json::array();
  auto& vel = state["vel"] = nlohmann::json::array();
  for (std::size_t i = 0; i < sim->state.pos.size(); ++i) {
    pos.push_back(toJson(sim->state.pos[i]));
    vel.push_back(toJson(sim->state.vel[i]));
  }
  return state;
}

}  // namespace

extern "C" {

// Step `frames` frames as the viewer does (paused or not). 0, or -1 before the viewer runs.
EMSCRIPTEN_KEEPALIVE int springlab_step(int frames) {
  LiveViewer* viewer = springlab::liveViewer();
  if (!viewer) return -1;
  viewer->stepFrames(frames);
  return 0;
}

// The state as JSON text (valid until the next call); "null" before the viewer runs.
EMSCRIPTEN_KEEPALIVE const char* springlab_state() {
  static std::string text;
  LiveViewer* viewer = springlab::liveViewer();
  text = viewer ? stateOf(*viewer).dump() : "null";
  return text.c_str();
}

EMSCRIPTEN_KEEPALIVE void springlab_set_paused(int paused) {
  if (LiveViewer* viewer = springlab::liveViewer()) viewer->setPaused(paused != 0);
}

EMSCRIPTEN_KEEPALIVE void springlab_resize(int width, int height) {
  if (LiveViewer* viewer = springlab::liveViewer()) viewer->resize(width, height);
}

}  // extern "C"
