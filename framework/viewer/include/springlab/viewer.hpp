#pragma once
// The interactive viewer: the only code of springlab that includes OpenGL or GUI headers.
#include <string>

#include "springlab/registry.hpp"
#include "springlab/simulation.hpp"

namespace springlab {

struct ViewerOptions {
  int frames = 0;             // 0: run until the window closes; N: close after N frames
  std::string snapshot;       // when set, write a PNG of the last frame here
  int width = 1280;           // window size in pixels
  int height = 800;
  std::string integrator;     // when set, overrides the scene's integrator
  double dt = 0.0;            // s; when > 0, overrides the scene's dt (the panel can change it)
  std::string tree = "student";  // "student" or "reference", shown in the HUD
  bool paused = false;        // start paused (P or the panel continues)
  bool compact = false;       // start with the panel collapsed (a small frame in a web page)
};

// Open a window on the scene and run it. Returns a process exit code (0 on success).
// A scene whose exercises are missing still opens and shows which exercise is missing.
// In the browser (Emscripten) it returns once the first frame is scheduled and the page runs
// the frames: `registry` must then live as long as the page.
int runViewer(const Registry& registry, const std::string& scenePath, const ViewerOptions& options);

// The viewer running in this process, as the browser page's JavaScript hook sees it
// (framework/web/page_hooks.cpp): step it and read its scene, as a test compares with `sim`.
class LiveViewer {
 public:
  virtual ~LiveViewer() = default;
  virtual Simulation* simulation() = 0;  // null when the scene could not be built
  virtual int substeps() const = 0;      // steps of dt per frame
  virtual double dt() const = 0;         // s
  virtual std::string integratorName() const = 0;
  // The missing exercise or the error that stopped the run, as the viewer shows it; empty
  // while the run is fine.
  virtual std::string problem() const = 0;
  // `frames` frames as the viewer steps one (its substeps, a grabbed mass or dragged
  // collider moved along), whether paused or not.
  virtual void stepFrames(int frames) = 0;
  virtual void setPaused(bool paused) = 0;
  virtual void resize(int width, int height) = 0;  // pixels
};

// The viewer runViewer started, or null before it opened its window.
LiveViewer* liveViewer();

}  // namespace springlab
