#pragma once
// The interactive viewer: the only code of springlab that includes OpenGL or GUI headers.
#include <string>

#include "springlab/registry.hpp"

namespace springlab {

struct ViewerOptions {
  int frames = 0;             // 0: run until the window closes; N: close after N frames
  std::string snapshot;       // when set, write a PNG of the last frame here
  int width = 1280;           // window size in pixels
  int height = 800;
  std::string integrator;     // when set, overrides the scene's integrator
  double dt = 0.0;            // s; when > 0, overrides the scene's dt (the panel can change it)
  std::string tree = "student";  // "student" or "reference", shown in the HUD
};

// Open a window on the scene and run it. Returns a process exit code (0 on success).
// A scene whose exercises are missing still opens and shows which exercise is missing.
int runViewer(const Registry& registry, const std::string& scenePath, const ViewerOptions& options);

}  // namespace springlab
