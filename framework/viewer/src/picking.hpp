#pragma once
// Choosing a mass with the mouse and dragging it in a plane facing the screen.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "camera.hpp"
#include "springlab/math.hpp"
#include "springlab/shape.hpp"

namespace springlab::viewer {

// The mass whose centre is nearest to the ray, at most maxPixels from it on screen;
// pixelAngle is the angle one pixel spans (Camera::pixelAngle). nullopt when none is close.
std::optional<int> pickMass(const std::vector<Vec3>& positions, const Ray& ray, float pixelAngle,
                            float maxPixels);

// The movable shape the ray hits first (spheres by their surface, boxes by their bounding
// sphere), or nullopt.
std::optional<int> pickShape(const std::vector<Shape>& shapes, const Ray& ray);

// Where the ray meets the plane through `point` whose normal is `normal` (the camera's
// forward direction); `point` itself when the ray runs parallel to the plane.
glm::vec3 intersectPlane(const Ray& ray, const glm::vec3& point, const glm::vec3& normal);

}  // namespace springlab::viewer
