#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include <springlab/softbody/exercises.hpp>

namespace springlab::softbody {

namespace {

// A spring between a and b at rest at their distance in the mesh.
[[maybe_unused]] Spring restingSpring(const SurfaceMesh& mesh, int a, int b, double k, double kd, SpringKind kind) {
  return Spring{a, b, k, (mesh.vertices[a] - mesh.vertices[b]).norm(), kd, kind};
}

}  // namespace

std::vector<Spring> edgeSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant) {
  // TODO exercise 3.2 (springs from the mesh): write this part; see handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.2", "springs from the mesh", "handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics)");
}

std::vector<Spring> oppositeSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant) {
  // TODO exercise 3.2 (springs from the mesh): write this part; see handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.2", "springs from the mesh", "handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics)");
}

std::vector<Spring> secondRingSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant) {
  // TODO exercise 3.2 (springs from the mesh): write this part; see handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics).
  throw springlab::NotImplemented("3.2", "springs from the mesh", "handouts/03_softbody.md, Exercise 3.2 (physics in section 2, The physics)");
}

}  // namespace springlab::softbody
