#pragma once
// Colours that show where the forces are: green for no force, red for the strongest.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "springlab/math.hpp"

namespace springlab::viewer {

// One colour per mass from |force[i]| into `colors` (n of them; green where force has no
// entry), scaled by the frame's 95th percentile so that one extreme mass (a grabbed or
// pinned one) does not turn every other mass green. `work` is scratch space: the caller
// keeps both vectors, and a frame allocates nothing once they have the scene's size.
void forceColors(const std::vector<Vec3>& force, std::size_t n, std::vector<glm::vec3>& colors,
                 std::vector<float>& work);

}  // namespace springlab::viewer
