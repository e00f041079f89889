#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

Vec3 gravityAndAirFriction(double m, const Vec3& vel, const Vec3& gravitation,
                           double airFrictionConstant) {
  // BEGIN EXERCISE 1.2
  return m * gravitation - airFrictionConstant * vel;
  // END EXERCISE 1.2
}

}  // namespace springlab::rope
