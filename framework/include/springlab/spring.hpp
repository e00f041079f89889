#pragma once
// A damped spring between two masses, named as in the handout. It holds indices into
// Simulation::masses, never pointers, so the mass array may grow or be copied freely.
#include <ostream>

namespace springlab {

// The role a spring plays; the viewer draws each kind in its own colour. A net has
// structural, shear and bend springs; a soft body's extra springs (to the far side) are Extra.
enum class SpringKind : int { Structural = 0, Shear = 1, Bend = 2, Extra = 3 };

// "structural", "shear", "bend" or "extra": for messages (and test failures, through <<).
constexpr const char* name(SpringKind kind) {
  switch (kind) {
    case SpringKind::Structural: return "structural";
    case SpringKind::Shear: return "shear";
    case SpringKind::Bend: return "bend";
    case SpringKind::Extra: return "extra";
  }
  return "unknown";
}
inline std::ostream& operator<<(std::ostream& out, SpringKind kind) { return out << name(kind); }

struct Spring {
  int mass1 = 0;                 // index of the first end
  int mass2 = 0;                 // index of the second end
  double springConstant = 0.0;   // k, N/m, > 0
  double springLength = 0.0;     // rest length L0, m, >= 0
  double frictionConstant = 0.0; // kd, N s/m, >= 0 (damping along the spring)
  SpringKind kind = SpringKind::Structural;  // its role (the viewer's colour, a lab's panel)
};

}  // namespace springlab
