#include "springlab/scene_shapes.hpp"

#include <algorithm>

namespace springlab {

bool facesUp(const Vec3& normal) { return normal.y() > 1.0 - 1e-9; }

std::optional<Shape> windArrow(const Bounds& body, const Vec3& direction, double relativeLength) {
  // No wind, no arrow.
  const double speed = direction.norm();
  if (!(relativeLength > 0.0) || !(speed > 0.0)) return std::nullopt;
  // Above the box's top by a fifth of its size, centred, pointing along the wind.
  const double size = std::max((body.hi - body.lo).norm(), 0.5);
  const Vec3 vector = std::min(relativeLength, 0.6) * size * (direction / speed);
  const Vec3 middle(0.5 * (body.lo.x() + body.hi.x()), body.hi.y() + 0.2 * size, 0.5 * (body.lo.z() + body.hi.z()));
  return Shape::arrowFrom(middle - 0.5 * vector, vector);
}

void ColliderDrag::finishStep(Vec3& center, Vec3& velocity, double dt) {
  // Held: jump to the target at the velocity that takes. Not held: stand still.
  if (target_) {
    velocity = dt > 0.0 ? Vec3((*target_ - center) / dt) : Vec3(Vec3::Zero());
    center = *target_;
  } else {
    velocity.setZero();
  }
  target_.reset();
}

}  // namespace springlab
