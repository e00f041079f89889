#include <algorithm>

#include "net.hpp"

namespace springlab::net {

int limitStretch(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                 const std::vector<double>& inverseMass, double maxStretch, double dt, int maxPasses) {
  // BEGIN EXERCISE 2.6
  int passes = 0;
  while (passes < maxPasses) {
    ++passes;
    double worst = 0.0;  // largest relative excess over the limit seen in this pass
    for (const Spring& s : springs) {
      const double w1 = inverseMass[s.mass1], w2 = inverseMass[s.mass2];
      if (w1 + w2 == 0.0) continue;
      const Vec3 d = pos[s.mass1] - pos[s.mass2];
      const double l = d.norm();
      const double limit = (1.0 + maxStretch) * s.springLength;
      if (l <= limit) continue;
      worst = std::max(worst, (l - limit) / limit);

      // Shorten to the limit along the spring, the lighter end moving more.
      const Vec3 correction = (l - limit) / (w1 + w2) * (d / l);
      pos[s.mass1] -= w1 * correction;
      pos[s.mass2] += w2 * correction;
      vel[s.mass1] -= w1 * correction / dt;
      vel[s.mass2] += w2 * correction / dt;
    }
    if (worst <= 1e-9) break;
  }
  return passes;
  // END EXERCISE 2.6
}

}  // namespace springlab::net
