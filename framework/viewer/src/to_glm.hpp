#pragma once
// The one conversion from the core's double-precision vectors to the GPU's floats.
#include <glm/vec3.hpp>

#include <springlab/math.hpp>

namespace springlab::viewer {

inline glm::vec3 toGlm(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace springlab::viewer
