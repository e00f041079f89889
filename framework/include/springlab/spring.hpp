#pragma once
// A damped spring between two masses, named as in the handout. It holds indices into
// Simulation::masses, never pointers, so the mass array may grow or be copied freely.

namespace springlab {

// The roles springs play in a net; the viewer draws each in its own colour.
enum SpringKind : int { kStructural = 0, kShear = 1, kBend = 2, kExtra = 3 };

struct Spring {
  int mass1 = 0;                 // index of the first end
  int mass2 = 0;                 // index of the second end
  double springConstant = 0.0;   // k, N/m, > 0
  double springLength = 0.0;     // rest length L0, m, >= 0
  double frictionConstant = 0.0; // kd, N s/m, >= 0 (damping along the spring)
  int kind = 0;                  // what the viewer colours it as: a SpringKind
};

}  // namespace springlab
