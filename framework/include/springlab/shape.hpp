#pragma once
// What a scene shows besides its masses: rigid colliders (sphere, plane, box) and markers
// (an arrow for the wind). Labs own the physics of these shapes; the viewer only draws them
// and reports the user's drags through Simulation::moveShape(). Each field means one thing;
// the fields a type does not use keep their defaults. Build shapes with the named makers.
#include <string>

#include "springlab/math.hpp"

namespace springlab {

enum class ShapeType { Sphere, Plane, Box, Arrow };

struct Shape {
  ShapeType type = ShapeType::Sphere;
  Vec3 center = Vec3::Zero();       // m: sphere or box centre, a point on the plane, the arrow's tail
  Vec3 normal = Vec3::UnitY();      // plane: unit normal, pointing to the free side
  Vec3 halfExtents = Vec3::Zero();  // box: half its edge lengths along x, y and z (m)
  Vec3 arrow = Vec3::Zero();        // arrow: the vector drawn from the tail to the tip (m)
  double radius = 0.0;              // sphere: radius (m)
  bool movable = false;             // the user may drag it (Ctrl + drag in the viewer)

  static Shape sphere(const Vec3& center, double radius, bool movable = false) {
    Shape s;
    s.type = ShapeType::Sphere;
    s.center = center;
    s.radius = radius;
    s.movable = movable;
    return s;
  }
  static Shape plane(const Vec3& point, const Vec3& normal) {
    Shape s;
    s.type = ShapeType::Plane;
    s.center = point;
    s.normal = normal;
    return s;
  }
  static Shape box(const Vec3& center, const Vec3& halfExtents, bool movable = false) {
    Shape s;
    s.type = ShapeType::Box;
    s.center = center;
    s.halfExtents = halfExtents;
    s.movable = movable;
    return s;
  }
  static Shape arrowFrom(const Vec3& tail, const Vec3& vector) {
    Shape s;
    s.type = ShapeType::Arrow;
    s.center = tail;
    s.arrow = vector;
    return s;
  }
};

// A named scalar a scene reports: the HUD lists it, `sim` records it and the resolution
// study measures it ("volume" in m^3, "pressure" in Pa, "sag" in m).
struct Observable {
  std::string name;
  std::string unit;
  double value = 0.0;
};

// An axis-aligned box, for framing the camera.
struct Bounds {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();

  // Grow the box to hold x.
  void include(const Vec3& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
};

}  // namespace springlab
