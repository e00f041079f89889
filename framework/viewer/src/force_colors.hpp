#pragma once
// Colours that show where the forces are: green for no force, red for the strongest.
#include <vector>

#include <glm/glm.hpp>

#include "springlab/math.hpp"

namespace springlab::viewer {

// One colour per mass from |force[i]|, scaled by the frame's 95th percentile so that one
// extreme mass (a grabbed or pinned one) does not turn every other mass green.
std::vector<glm::vec3> forceColors(const std::vector<Vec3>& force);

}  // namespace springlab::viewer
