#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace springlab::viewer {

namespace {
constexpr float kPi = 3.14159265f;
constexpr float kOrbitRadiansPerPixel = 0.008f;
}  // namespace

void Camera::frame(const glm::vec3& lo, const glm::vec3& hi, float aspect, float freeLeft, float freeRight) {
  // Fit each corner in camera axes: |x| <= (d - z) tan(fovx/2) and |y| <= (d - z) tan(fovy/2),
  // where z points from the target towards the eye. The largest d needed wins.
  target_ = 0.5f * (lo + hi);
  const glm::vec3 back = -forward();
  const glm::vec3 right = glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward());
  const float tanY = std::tan(0.5f * fovy_);
  const float freeWidth = std::clamp(freeRight - freeLeft, 0.1f, 1.0f);
  const float tanX = tanY * std::max(aspect * freeWidth, 0.1f);
  shiftX_ = std::clamp(freeLeft + freeRight - 1.0f, -0.9f, 0.9f);  // the free part's centre, in NDC
  float d = 0.1f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::vec3 r = corner - target_;
    const float z = glm::dot(r, back);
    d = std::max(d, std::abs(glm::dot(r, right)) / tanX + z);
    d = std::max(d, std::abs(glm::dot(r, up)) / tanY + z);
  }
  distance_ = 1.05f * d;  // a small margin around the box
}

void Camera::orbit(float dxPixels, float dyPixels) {
  yaw_ -= dxPixels * kOrbitRadiansPerPixel;
  pitch_ = std::clamp(pitch_ + dyPixels * kOrbitRadiansPerPixel, -0.49f * kPi, 0.49f * kPi);
}

void Camera::zoom(float factor) { distance_ = std::clamp(distance_ * factor, 0.01f, 1.0e4f); }

void Camera::pan(float dxPixels, float dyPixels, float viewportHeight) {
  // Move the target so that the point under the cursor follows it (at the target's depth).
  const float metresPerPixel = 2.0f * distance_ * std::tan(0.5f * fovy_) / std::max(viewportHeight, 1.0f);
  const glm::vec3 right = glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward());
  target_ += (-dxPixels * right + dyPixels * up) * metresPerPixel;
}

glm::vec3 Camera::forward() const {
  return -glm::vec3(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_));
}

glm::vec3 Camera::eye() const { return target_ - distance_ * forward(); }

glm::mat4 Camera::view() const { return glm::lookAt(eye(), target_, glm::vec3(0, 1, 0)); }

glm::mat4 Camera::projection(float aspect) const {
  // Near and far follow the distance so that zooming never clips the scene.
  const glm::mat4 shift = glm::translate(glm::mat4(1.0f), glm::vec3(shiftX_, 0.0f, 0.0f));
  return shift * glm::perspective(fovy_, std::max(aspect, 0.01f), 0.01f * distance_, 100.0f * distance_);
}

float Camera::pixelAngle(int h) const { return 2.0f * std::tan(0.5f * fovy_) / static_cast<float>(std::max(h, 1)); }

Ray Camera::ray(double x, double y, int w, int h) const {
  // Unproject the pixel at the near and far planes; the ray joins the two points.
  const float aspect = static_cast<float>(w) / static_cast<float>(std::max(h, 1));
  const glm::mat4 inv = glm::inverse(projection(aspect) * view());
  const float nx = static_cast<float>(2.0 * x / std::max(w, 1) - 1.0);
  const float ny = static_cast<float>(1.0 - 2.0 * y / std::max(h, 1));
  glm::vec4 a = inv * glm::vec4(nx, ny, -1.0f, 1.0f);
  glm::vec4 b = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  a /= a.w;
  b /= b.w;
  Ray r;
  r.origin = glm::vec3(a);
  r.direction = glm::normalize(glm::vec3(b - a));
  return r;
}

}  // namespace springlab::viewer
