#include <springlab/net/exercises.hpp>

namespace springlab::net {

void vertexNormals(const std::vector<Vec3>& pos, const std::vector<Triangle>& triangles,
                   std::vector<Vec3>& normals, std::vector<double>& areas) {
  // TODO exercise 2.3 (vertex normals and areas): write this part; see handouts/02_net.md, Exercise 2.3 (physics in section 2.b, Forces).
  throw springlab::NotImplemented("2.3", "vertex normals and areas", "handouts/02_net.md, Exercise 2.3 (physics in section 2.b, Forces)");
}

}  // namespace springlab::net
