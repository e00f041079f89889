#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

void addWindForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel, const std::vector<Triangle>& triangles,
                   const std::vector<Segment>& segments, const Vec3& wind, double drag, std::vector<Vec3>& f) {
  // BEGIN EXERCISE 3.9
  // 3D: the air's velocity relative to the face, along the face's normal, over its area.
  for (const Triangle& t : triangles) {
    const Vec3 cross = (pos[t.b] - pos[t.a]).cross(pos[t.c] - pos[t.a]);
    const double twiceArea = cross.norm();
    if (twiceArea == 0.0) continue;
    const Vec3 n = cross / twiceArea;
    const Vec3 faceVelocity = (vel[t.a] + vel[t.b] + vel[t.c]) / 3.0;
    const Vec3 share = drag * 0.5 * twiceArea * (wind - faceVelocity).dot(n) * n / 3.0;
    f[t.a] += share;
    f[t.b] += share;
    f[t.c] += share;
  }
  // 2D: the same per segment, its length for the area, half to each end.
  for (const Segment& s : segments) {
    const Vec3 d = pos[s.b] - pos[s.a];
    const double length = d.norm();
    if (length == 0.0) continue;
    const Vec3 n = Vec3(d.y(), -d.x(), 0.0) / length;
    const Vec3 segmentVelocity = 0.5 * (vel[s.a] + vel[s.b]);
    const Vec3 share = 0.5 * drag * length * (wind - segmentVelocity).dot(n) * n;
    f[s.a] += share;
    f[s.b] += share;
  }
  // END EXERCISE 3.9
}

}  // namespace springlab::softbody
