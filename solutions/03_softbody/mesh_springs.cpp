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
  // BEGIN EXERCISE 3.2
  // Each undirected edge once, in the order the faces first name it.
  std::vector<Spring> springs;
  std::set<std::pair<int, int>> seen;
  auto add = [&](int a, int b) {
    if (seen.insert(std::minmax(a, b)).second) {
      springs.push_back(restingSpring(mesh, a, b, springConstant, frictionConstant, SpringKind::Structural));
    }
  };
  for (const Triangle& t : mesh.triangles) {
    add(t.a, t.b);
    add(t.b, t.c);
    add(t.c, t.a);
  }
  for (const Segment& s : mesh.segments) add(s.a, s.b);
  return springs;
  // END EXERCISE 3.2
}

std::vector<Spring> oppositeSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant) {
  // BEGIN EXERCISE 3.2
  // The farthest vertex of each vertex (the first of equals), each pair once.
  std::vector<Spring> springs;
  std::set<std::pair<int, int>> seen;
  const int n = static_cast<int>(mesh.vertices.size());
  for (int i = 0; i < n; ++i) {
    int far = -1;
    double best = -1.0;
    for (int j = 0; j < n; ++j) {
      const double d = (mesh.vertices[i] - mesh.vertices[j]).squaredNorm();
      if (j != i && d > best) {
        best = d;
        far = j;
      }
    }
    if (far >= 0 && seen.insert(std::minmax(i, far)).second) {
      springs.push_back(restingSpring(mesh, i, far, springConstant, frictionConstant, SpringKind::Extra));
    }
  }
  return springs;
  // END EXERCISE 3.2
}

std::vector<Spring> secondRingSprings(const SurfaceMesh& mesh, double springConstant, double frictionConstant) {
  // BEGIN EXERCISE 3.2
  std::vector<Spring> springs;
  std::set<std::pair<int, int>> seen;
  auto add = [&](int a, int b) {
    if (a != b && seen.insert(std::minmax(a, b)).second) {
      springs.push_back(restingSpring(mesh, a, b, springConstant, frictionConstant, SpringKind::Bend));
    }
  };
  // 3D: the corner opposite each directed edge; the reverse edge's face holds the other one.
  std::map<std::pair<int, int>, int> opposite;
  for (const Triangle& t : mesh.triangles) {
    opposite[{t.a, t.b}] = t.c;
    opposite[{t.b, t.c}] = t.a;
    opposite[{t.c, t.a}] = t.b;
  }
  for (const Triangle& t : mesh.triangles) {
    for (const auto& [a, b, c] : {std::tuple{t.a, t.b, t.c}, std::tuple{t.b, t.c, t.a}, std::tuple{t.c, t.a, t.b}}) {
      if (auto other = opposite.find({b, a}); other != opposite.end()) add(c, other->second);
    }
  }
  // 2D: each vertex to the one two segments further along its loop.
  std::map<int, int> next;
  for (const Segment& s : mesh.segments) next[s.a] = s.b;
  for (const Segment& s : mesh.segments) {
    if (auto it = next.find(s.b); it != next.end()) add(s.a, it->second);
  }
  return springs;
  // END EXERCISE 3.2
}

}  // namespace springlab::softbody
