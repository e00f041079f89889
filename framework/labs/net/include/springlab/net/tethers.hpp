#pragma once
// Long-range attachments ("tethers"; Kim, Chentanez and Mueller, SCA 2012), given code run by
// the Net before the student's stretch limit (exercise 2.6). A Gauss-Seidel pass over the
// springs moves a correction about one spring along the cloth, so the sag of an r x r cloth
// hanging from its corners needs on the order of r^2 passes to take back. A tether bounds each
// free mass's distance from each pinned mass directly: no farther than (1 + maxStretch) times
// their distance in the rest shape (on the flat grid, the shortest path along the cloth). One
// pass, O(masses x pins), no iteration; the spring passes after it fix the local strain.
#include <vector>

#include <springlab/math.hpp>

namespace springlab::net {

class Tethers {
 public:
  // The rest shape: the flat grid the net is built as. [n] m.
  explicit Tethers(std::vector<Vec3> restPositions = {}) : rest_(std::move(restPositions)) {}

  // One pass: each free mass (inverseMass > 0) farther from a pinned mass p (inverseMass 0)
  // than (1 + maxStretch) |rest_i - rest_p| moves straight back onto that sphere around p
  // (p is fixed, so the whole move is the free mass's); its velocity changes by move / dt,
  // as in exercise 2.6. Returns the number of masses moved.
  int apply(std::vector<Vec3>& pos, std::vector<Vec3>& vel, const std::vector<double>& inverseMass,
            double maxStretch, double dt);

 private:
  std::vector<Vec3> rest_;  // [n] m, rest shape
  std::vector<int> pins_;   // [pins] masses with inverse mass 0 this step (scratch)

};

}  // namespace springlab::net
