#include <springlab/rope/exercises.hpp>

namespace springlab::rope {

RopeLayout buildRope(const RopeParameters& p) {
  // BEGIN EXERCISE 1.7
  RopeLayout rope;
  const int n = p.numOfMasses;

  // Masses on a straight line from the connection point, at rest; the first is fixed.
  for (int i = 0; i < n; ++i) {
    rope.masses.push_back(Mass{p.mass, i == 0});
    rope.pos.push_back(p.ropeConnectionPos + i * p.springLength * p.direction);
    rope.vel.push_back(Vec3::Zero());
  }

  // One spring between each pair of neighbours, at its rest length.
  for (int i = 0; i + 1 < n; ++i) {
    rope.springs.push_back(Spring{i, i + 1, p.springConstant, p.springLength, p.springFrictionConstant});
  }
  return rope;
  // END EXERCISE 1.7
}

}  // namespace springlab::rope
