#pragma once
// An orbit camera: it circles a target point at a distance, with yaw and pitch angles.
// Left-drag orbits, right-drag and the wheel zoom, middle-drag pans (see viewer.cpp).
#include <glm/glm.hpp>

namespace springlab::viewer {

// A ray from the eye through a pixel, in world coordinates.
struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

class Camera {
 public:
  // Place the target at the box's centre and move back until every corner is in view in the
  // part of the window from freeLeft to freeRight (fractions of its width, left of the
  // control panel and right of the HUD), which the lens is shifted to centre on.
  void frame(const glm::vec3& lo, const glm::vec3& hi, float aspect, float freeLeft = 0.0f, float freeRight = 1.0f);

  void orbit(float dxPixels, float dyPixels);
  void zoom(float factor);  // distance *= factor
  void pan(float dxPixels, float dyPixels, float viewportHeight);

  glm::vec3 eye() const;
  glm::vec3 forward() const;  // unit, from the eye to the target
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;

  // The ray through window point (x, y) (pixels, origin top-left) of a w x h window.
  Ray ray(double x, double y, int w, int h) const;
  // Tangent of the angle one pixel spans at the centre of a window h pixels high.
  float pixelAngle(int h) const;

 private:
  glm::vec3 target_{0.0f};
  float distance_ = 5.0f;  // m
  float yaw_ = 0.25f;      // rad, around +y; 0 looks along -z
  float pitch_ = 0.3f;     // rad, above the horizon
  float fovy_ = 0.7854f;   // rad (45 degrees)
  float shiftX_ = 0.0f;    // lens shift: where the target appears, in normalised device x
};

}  // namespace springlab::viewer
