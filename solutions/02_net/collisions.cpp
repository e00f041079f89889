#include <algorithm>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

Contact sphereContact(const Vec3& x, const Vec3& center, double radius) {
  // BEGIN EXERCISE 2.5
  Contact c;
  c.pos = x;
  const Vec3 d = x - center;
  const double distance = d.norm();
  if (distance >= radius) return c;

  // Inside: out along the radius through x (straight up from the very centre).
  c.touching = true;
  c.normal = distance > 0.0 ? Vec3(d / distance) : Vec3::UnitY();
  c.pos = center + radius * c.normal;
  return c;
  // END EXERCISE 2.5
}

Contact planeContact(const Vec3& x, const Vec3& point, const Vec3& normal) {
  // BEGIN EXERCISE 2.5
  Contact c;
  c.pos = x;
  const double s = (x - point).dot(normal);  // signed distance, negative behind the plane
  if (s >= 0.0) return c;
  c.touching = true;
  c.normal = normal;
  c.pos = x - s * normal;
  return c;
  // END EXERCISE 2.5
}

Vec3 contactVelocity(const Vec3& vel, const Vec3& colliderVelocity, const Vec3& normal, double absorption,
                     double friction) {
  // BEGIN EXERCISE 2.5
  // Work in the collider's frame; a separating mass keeps its velocity.
  const Vec3 u = vel - colliderVelocity;
  const double un = u.dot(normal);
  if (un >= 0.0) return vel;

  // Normal part: lose absorption times the approaching speed.
  const Vec3 normalPart = (1.0 - absorption) * un * normal;

  // Tangential part: Coulomb friction takes friction times the normal speed change.
  Vec3 tangential = u - un * normal;
  const double speed = tangential.norm();
  if (speed > 0.0) tangential *= std::max(0.0, 1.0 - friction * absorption * -un / speed);
  return colliderVelocity + normalPart + tangential;
  // END EXERCISE 2.5
}

}  // namespace springlab::net
