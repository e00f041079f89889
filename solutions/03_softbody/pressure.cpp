#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double gasPressure(double nRT, double volume) {
  // BEGIN EXERCISE 3.4
  // Boyle's law at constant temperature; no gas can fill a body without volume.
  if (volume <= 0.0) return 0.0;
  return nRT / volume;
  // END EXERCISE 3.4
}

void addPressureForces(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                       const std::vector<Segment>& segments, double pressure, std::vector<Vec3>& f) {
  // BEGIN EXERCISE 3.4
  // 3D: (b - a) x (c - a) is twice the face's area along its outward normal, so
  // P A n_hat = P cross / 2, a third of it on each corner.
  for (const Triangle& t : triangles) {
    const Vec3 areaVector = 0.5 * (pos[t.b] - pos[t.a]).cross(pos[t.c] - pos[t.a]);
    const Vec3 share = pressure * areaVector / 3.0;
    f[t.a] += share;
    f[t.b] += share;
    f[t.c] += share;
  }
  // 2D: the segment d = b - a turned to its right, (d_y, -d_x), is L n_hat; half to each end.
  for (const Segment& s : segments) {
    const Vec3 d = pos[s.b] - pos[s.a];
    const Vec3 share = 0.5 * pressure * Vec3(d.y(), -d.x(), 0.0);
    f[s.a] += share;
    f[s.b] += share;
  }
  // END EXERCISE 3.4
}

}  // namespace springlab::softbody
