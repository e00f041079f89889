#include <springlab/net/exercises.hpp>

namespace springlab::net {

Vec3 windForce(const Wind& wind, const Vec3& vel, const Vec3& normal, double area) {
  // BEGIN EXERCISE 2.4
  if (wind.model == WindModel::Relative) {
    // Pressure of the air's velocity relative to the mass, across the surface only.
    const Vec3 relative = wind.strength * wind.direction - vel;
    return area * wind.drag * relative.dot(normal) * normal;
  }
  // The thesis: along the wind, as strong as the surface faces it, from either side.
  return area * wind.strength * std::abs(wind.direction.dot(normal)) * wind.direction;
  // END EXERCISE 2.4
}

}  // namespace springlab::net
