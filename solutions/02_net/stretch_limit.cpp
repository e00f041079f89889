#include <springlab/net/exercises.hpp>

namespace springlab::net {

int limitStretch(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                 const std::vector<double>& inverseMass, double maxStretch, double dt, int maxPasses) {
  // BEGIN EXERCISE 2.6
  const double inverseDt = 1.0 / dt;
  int passes = 0;
  while (passes < maxPasses) {
    ++passes;
    bool stretched = false;  // a spring was over its limit by more than a relative 1e-9
    for (const Spring& s : springs) {
      const double w1 = inverseMass[s.mass1], w2 = inverseMass[s.mass2];
      if (w1 + w2 == 0.0) continue;
      // Most springs are within the limit: compare squared lengths, no square root.
      const Vec3 d = pos[s.mass1] - pos[s.mass2];
      const double limit = (1.0 + maxStretch) * s.springLength;
      if (d.squaredNorm() <= limit * limit) continue;
      const double l = d.norm();
      if (l - limit > 1e-9 * limit) stretched = true;

      // Shorten to the limit along the spring (d / l), the lighter end moving more.
      const Vec3 correction = ((l - limit) / ((w1 + w2) * l)) * d;
      pos[s.mass1] -= w1 * correction;
      pos[s.mass2] += w2 * correction;
      vel[s.mass1] -= (w1 * inverseDt) * correction;
      vel[s.mass2] += (w2 * inverseDt) * correction;
    }
    if (!stretched) break;
  }
  return passes;
  // END EXERCISE 2.6
}

}  // namespace springlab::net
