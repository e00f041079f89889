#include <algorithm>
#include <cmath>
#include <cstdint>

#include <springlab/net/exercises.hpp>

namespace springlab::net {

std::vector<std::pair<int, int>> closePairs(const std::vector<Vec3>& pos, double distance) {
  // TODO exercise 2.10 (self-collision): write this part; see handouts/02_net.md, Exercise 2.10 (physics in section 2.e, Self-collision (advanced)).
  throw springlab::NotImplemented("2.10", "self-collision", "handouts/02_net.md, Exercise 2.10 (physics in section 2.e, Self-collision (advanced))");
}

void separatePair(Vec3& x1, Vec3& x2, Vec3& v1, Vec3& v2, double w1, double w2, double thickness) {
  // TODO exercise 2.10 (self-collision): write this part; see handouts/02_net.md, Exercise 2.10 (physics in section 2.e, Self-collision (advanced)).
  throw springlab::NotImplemented("2.10", "self-collision", "handouts/02_net.md, Exercise 2.10 (physics in section 2.e, Self-collision (advanced))");
}

}  // namespace springlab::net
