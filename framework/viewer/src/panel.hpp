#pragma once
// The ImGui parts of the window: the HUD (top left), the control panel (right) and the
// messages that stay on screen while something is wrong (a missing exercise, a blow-up).
// They only draw and record what the user asked for; viewer.cpp applies the requests, so an
// exception thrown by the simulation never interrupts an ImGui window half-way.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "springlab/diagnostics.hpp"
#include "springlab/simulation.hpp"

namespace springlab::viewer {

// What the loop runs: edited by keys and by the panel.
struct RunControl {
  bool paused = false;
  double dt = 0.002;  // s
  int substeps = 1;   // steps per frame
  bool drawMasses = true;
  bool wireframe = false;
  bool springsByKind = false;  // K: structural, shear, bend in their own colours
  bool panelCollapsed = false;  // the panel starts as its title bar (a small frame in a page)
  // Requests, consumed by the loop in the same frame.
  bool stepRequested = false;
  bool resetRequested = false;
  bool screenshotRequested = false;
  std::optional<std::string> integratorRequested;
  // A slider moved: the index into the scene's parameters() and the new value, which the
  // loop writes with Parameter::set (a model edit).
  struct ParameterEdit {
    std::size_t index = 0;
    double value = 0.0;
  };
  std::optional<ParameterEdit> parameterEdit;
  // Labels of the panel's last frame that did not fit its width (a --frames run reports
  // them; the viewer tests expect none).
  std::vector<std::string> cutLabels;
};

// An exercise the student has not written yet, from NotImplemented.
struct MissingExercise {
  std::string id;
  std::string title;
  std::string handoutSection;
};

// Frames per second, and the milliseconds of a frame spent stepping the physics and on the
// rest (drawing and GUI beyond what is rendered while the physics runs, waiting for the
// display).
struct FrameRate {
  float fps = 0.0f;
  float physicsMs = 0.0f;
  float drawMs = 0.0f;
};

// Everything the HUD shows.
struct HudInfo {
  std::string sceneName;
  std::string tree;  // "student" or "reference"
  std::string kind;  // "rope", or empty without a simulation
  int masses = 0;
  double time = 0.0;
  double dt = 0.0;
  int substeps = 0;
  std::string integrator;
  std::optional<Energies> energies;  // nullopt when they could not be computed
  std::vector<Observable> observables;  // the scene's volume, pressure, ...
  FrameRate rate;
  bool paused = false;
};

void drawHud(const HudInfo& hud);

// The control panel. `sim` may be null (the scene could not be built); stableDt is
// the stability limit of the step that runs (stepStableDt: 0 no stable dt, +inf none,
// negative: not known yet).
void drawControls(Simulation* sim, const std::vector<std::string>& integratorNames, const std::string& integrator,
                  double stableDt, RunControl& control);

// The large red panel in the middle of the window.
void drawMissingExercise(const MissingExercise& missing);

// Why the run stopped (a blow-up, or another error of the simulation), in red at the bottom.
void drawRunError(const std::string& headline, const std::string& message);

}  // namespace springlab::viewer
