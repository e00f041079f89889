#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

double enclosedVolume(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles) {
  // BEGIN EXERCISE 3.3
  // Divergence theorem: each face with the origin spans a signed tetrahedron a . (b x c) / 6.
  double v = 0.0;
  for (const Triangle& t : triangles) v += pos[t.a].dot(pos[t.b].cross(pos[t.c]));
  return v / 6.0;
  // END EXERCISE 3.3
}

double enclosedArea(const std::vector<Vec3>& pos, const std::vector<Segment>& segments) {
  // BEGIN EXERCISE 3.3
  // Shoelace: each segment with the origin spans a signed triangle (x_a y_b - x_b y_a) / 2.
  double a = 0.0;
  for (const Segment& s : segments) a += pos[s.a].x() * pos[s.b].y() - pos[s.b].x() * pos[s.a].y();
  return 0.5 * a;
  // END EXERCISE 3.3
}

}  // namespace springlab::softbody
