#pragma once
// What a scene shows besides its masses: rigid colliders (sphere, plane, box) and markers
// (an arrow for the wind). Labs own the physics of these shapes; the viewer only draws them
// and reports the user's drags through Simulation::moveShape().
#include <string>

#include "springlab/math.hpp"

namespace springlab {

enum class ShapeType { Sphere, Plane, Box, Arrow };

struct Shape {
  ShapeType type = ShapeType::Sphere;
  Vec3 center = Vec3::Zero();  // sphere or box centre, a point on the plane, the arrow's tail
  Vec3 axis = Vec3::UnitY();   // plane: unit normal; box: half extents; arrow: the vector drawn
  double radius = 0.0;         // sphere radius, m
  bool movable = false;        // the user may drag it (Ctrl + drag in the viewer)
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
};

}  // namespace springlab
