#include <springlab/net/exercises.hpp>

namespace springlab::net {

int limitStretch(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<Spring>& springs,
                 const std::vector<double>& inverseMass, double maxStretch, double dt, int maxPasses) {
  // TODO exercise 2.6 (stretch limiting): write this part; see handouts/02_net.md, Exercise 2.6 (physics in section 2.d, Stretch limiting).
  throw springlab::NotImplemented("2.6", "stretch limiting", "handouts/02_net.md, Exercise 2.6 (physics in section 2.d, Stretch limiting)");
}

}  // namespace springlab::net
