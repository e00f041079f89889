#pragma once
// Helpers every lab shares for its colliders and markers: the ground among its planes, the
// wind's arrow, and the velocity of a collider the user drags. The labs keep their own
// collider types (a net's SphereCollider, a soft body's Obstacle); these work on values.
#include <optional>

#include "springlab/math.hpp"
#include "springlab/shape.hpp"

namespace springlab {

// ---- The ground plane ---------------------------------------------------------------------

// A plane: a point on it and its unit normal, pointing to the free side.
struct PlaneGeometry {
  Vec3 point = Vec3::Zero();    // m
  Vec3 normal = Vec3::UnitY();  // unit
};

// The ground the viewer draws: which of the colliders it is and its height y = height.
struct GroundPlane {
  int index = 0;        // position among the colliders handed to findGroundPlane
  double height = 0.0;  // m
};

// Whether a plane of unit normal n faces straight up (+y within 1e-9): it can be the ground.
bool facesUp(const Vec3& normal);

// The first plane facing straight up among `colliders`. planeOf(collider) returns the
// collider's PlaneGeometry, or std::nullopt when it is not a plane.
template <class Colliders, class PlaneOf>
std::optional<GroundPlane> findGroundPlane(const Colliders& colliders, PlaneOf planeOf) {
  int index = 0;
  for (const auto& collider : colliders) {
    const std::optional<PlaneGeometry> plane = planeOf(collider);
    if (plane && facesUp(plane->normal)) return GroundPlane{index, plane->point.y()};
    ++index;
  }
  return std::nullopt;
}

// ---- The wind's arrow ---------------------------------------------------------------------

// The arrow that shows the wind over a body occupying `body`: centred above the box, along
// `direction` (any length; zero gives no arrow), `relativeLength` times the box's diagonal
// long (capped at 0.6; the diagonal counts as at least 0.5 m so that a tiny body still shows
// its wind). std::nullopt when there is nothing to show.
std::optional<Shape> windArrow(const Bounds& body, const Vec3& direction, double relativeLength);

// ---- A dragged collider -------------------------------------------------------------------

// A collider the user drags. Between steps the viewer says where the user holds it
// (holdAt); at the end of the next step the lab moves the collider there with the velocity
// of that move, (target - old centre) / dt, which contacts then see. A collider not held
// during a step stands still: its velocity is zero.
class ColliderDrag {
 public:
  // The user holds the collider at `target`; it gets there at the end of the next step.
  void holdAt(const Vec3& target) { target_ = target; }
  // The step of length dt ended: move `center` to the target held since the last step and
  // set `velocity` to the velocity of that move, or to zero when it was not held.
  void finishStep(Vec3& center, Vec3& velocity, double dt);
  // Forget a target not reached yet (after a reset).
  void clear() { target_.reset(); }

 private:
  std::optional<Vec3> target_;  // m, where the user holds the collider, until the step ends
};

}  // namespace springlab
