#include <cmath>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

Penetration planePenetration(const Vec3& x, const Vec3& point, const Vec3& normal) {
  // BEGIN EXERCISE 3.6
  // Signed distance to the plane; behind it, the way out is along the normal.
  const double s = (x - point).dot(normal);
  if (s >= 0.0) return {};
  return {true, -s, normal};
  // END EXERCISE 3.6
}

Penetration spherePenetration(const Vec3& x, const Vec3& center, double radius) {
  // BEGIN EXERCISE 3.6
  // Out along the radius through the point; the centre itself leaves upwards.
  const Vec3 d = x - center;
  const double r = d.norm();
  if (r >= radius) return {};
  return {true, radius - r, r > 0.0 ? Vec3(d / r) : Vec3(Vec3::UnitY())};
  // END EXERCISE 3.6
}

Penetration boxPenetration(const Vec3& x, const Vec3& center, const Vec3& halfExtents) {
  // BEGIN EXERCISE 3.6
  // Inside when within the half extent on every axis; out through the face nearest the point.
  const Vec3 d = x - center;
  Penetration p;
  for (int k = 0; k < 3; ++k) {
    const double depth = halfExtents[k] - std::abs(d[k]);
    if (depth <= 0.0) return {};
    if (!p.touching || depth < p.depth) {
      p.touching = true;
      p.depth = depth;
      p.normal = Vec3::Unit(k) * (d[k] >= 0.0 ? 1.0 : -1.0);
    }
  }
  return p;
  // END EXERCISE 3.6
}

}  // namespace springlab::softbody
