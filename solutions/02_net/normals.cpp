#include <springlab/net/exercises.hpp>

namespace springlab::net {

void vertexNormals(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                   std::vector<Vec3>& normals, std::vector<double>& areas) {
  // BEGIN EXERCISE 2.3
  normals.assign(pos.size(), Vec3::Zero());
  areas.assign(pos.size(), 0.0);

  // Each triangle adds its area-weighted normal (b - a) x (c - a) and a third of its area.
  for (const Triangle& t : triangles) {
    const Vec3 n = (pos[t.b] - pos[t.a]).cross(pos[t.c] - pos[t.a]);
    const double third = n.norm() / 6.0;
    for (int i : {t.a, t.b, t.c}) {
      normals[i] += n;
      areas[i] += third;
    }
  }

  // Unit normals; a mass without a surface around it keeps a zero normal.
  for (Vec3& n : normals) {
    const double length = n.norm();
    if (length > 0.0) n /= length;
  }
  // END EXERCISE 2.3
}

}  // namespace springlab::net
