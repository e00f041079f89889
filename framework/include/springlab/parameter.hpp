#pragma once
// A scene parameter the viewer may edit live. Simulations declare them
// (Simulation::declareParameters); the viewer draws a slider per entry, reads it with get()
// and writes it with set(). Simulation::parameters() hands them out with every set() made a
// model edit (Simulation::editModel), so a slider re-arms the blow-up check and resets the
// integrator's history like any other edit. get() and set() read and write the simulation
// itself: a lab keeps no copy of the value for the panel.
#include <functional>
#include <string>
#include <utility>

namespace springlab {

struct Parameter {
  std::string label;                // "spring constant"
  std::string unit;                 // "N/m"
  std::function<double()> get;      // the value now, read from the simulation
  std::function<void(double)> set;  // writes the value into the simulation's model
  double min = 0.0;                 // slider range
  double max = 1.0;
  bool logarithmic = false;         // slider in log scale (stiffness, damping)

  // A parameter that is one number of the model, read and written as it is (`value` lives
  // in the simulation that declares the parameter).
  static Parameter field(std::string label, std::string unit, double& value, double min, double max,
                         bool logarithmic = false) {
    return {std::move(label), std::move(unit), [&value] { return value; }, [&value](double v) { value = v; }, min, max,
            logarithmic};
  }
};

}  // namespace springlab
