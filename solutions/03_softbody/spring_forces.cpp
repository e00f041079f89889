#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

void addSpringForces(const std::vector<Vec3>& pos, const std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                     std::vector<Vec3>& f) {
  // BEGIN EXERCISE 3.1
  for (const Spring& s : springs) {
    // Direction from mass 2 to mass 1; a zero-length spring has none and exerts no force.
    const Vec3 x12 = pos[s.mass1] - pos[s.mass2];
    const double l = x12.norm();
    if (l == 0.0) continue;
    const Vec3 e = x12 / l;

    // Hooke's law plus damping along e: on mass 1, and the opposite on mass 2.
    const Vec3 f1 = -s.springConstant * (l - s.springLength) * e -
                    s.frictionConstant * (vel[s.mass1] - vel[s.mass2]).dot(e) * e;
    f[s.mass1] += f1;
    f[s.mass2] -= f1;
  }
  // END EXERCISE 3.1
}

}  // namespace springlab::softbody
