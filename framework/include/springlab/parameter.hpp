#pragma once
// A scene parameter the viewer may edit live. Simulations declare them; the viewer only
// draws a slider per entry and calls Simulation::parametersChanged() after an edit.
#include <string>

namespace springlab {

struct Parameter {
  std::string label;   // "spring constant"
  std::string unit;    // "N/m"
  double* value;       // points into the simulation that declared it
  double min;          // slider range
  double max;
  bool logarithmic;    // slider in log scale (stiffness, damping)
};

}  // namespace springlab
