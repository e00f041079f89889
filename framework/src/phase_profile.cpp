#include "springlab/phase_profile.hpp"

namespace springlab {

std::string_view phaseName(Phase phase) {
  switch (phase) {
    case Phase::kOther: return "other";
    case Phase::kForces: return "forces";
    case Phase::kIntegration: return "integration";
    case Phase::kCollisions: return "collisions";
    case Phase::kStretchLimit: return "stretch limit";
    case Phase::kNormals: return "normals";
    case Phase::kCount: break;
  }
  return "?";
}

double PhaseProfile::totalSeconds() const {
  double total = 0.0;
  for (double s : seconds_) total += s;
  return total;
}

}  // namespace springlab
