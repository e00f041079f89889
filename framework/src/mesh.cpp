// Generated meshes and the closed-surface check. File readers live in mesh_io.cpp.
#include "springlab/mesh.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

namespace springlab {

namespace {

// Index of the vertex halfway along edge (a, b) on the sphere, made once per edge.
int midpoint(SurfaceMesh& m, std::map<std::pair<int, int>, int>& cache, int a, int b, double radius) {
  const std::pair<int, int> key = std::minmax(a, b);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const Vec3 p = (m.vertices[a] + m.vertices[b]).normalized() * radius;
  m.vertices.push_back(p);
  const int index = static_cast<int>(m.vertices.size()) - 1;
  cache.emplace(key, index);
  return index;
}

std::string faceText(int face, const std::vector<int>& corners, int base) {
  std::ostringstream os;
  os << "face " << face + base << " (vertices";
  for (int c : corners) os << ' ' << c + base;
  os << ')';
  return os.str();
}

}  // namespace

SurfaceMesh icosphere(double radius, int subdivisions) {
  if (!(radius > 0.0) || subdivisions < 0) throw std::invalid_argument("icosphere: radius > 0 and subdivisions >= 0");
  // The icosahedron: 12 vertices on three golden rectangles, 20 faces wound outward.
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  SurfaceMesh m;
  const std::array<Vec3, 12> corners = {Vec3(-1, t, 0), Vec3(1, t, 0),   Vec3(-1, -t, 0), Vec3(1, -t, 0),
                                        Vec3(0, -1, t), Vec3(0, 1, t),   Vec3(0, -1, -t), Vec3(0, 1, -t),
                                        Vec3(t, 0, -1), Vec3(t, 0, 1),   Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  for (const Vec3& c : corners) m.vertices.push_back(c.normalized() * radius);
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};

  // Each subdivision splits every triangle into four through its edge midpoints.
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> cache;
    std::vector<Triangle> finer;
    finer.reserve(4 * m.triangles.size());
    for (const Triangle& f : m.triangles) {
      const int ab = midpoint(m, cache, f.a, f.b, radius);
      const int bc = midpoint(m, cache, f.b, f.c, radius);
      const int ca = midpoint(m, cache, f.c, f.a, radius);
      finer.push_back({f.a, ab, ca});
      finer.push_back({f.b, bc, ab});
      finer.push_back({f.c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  return m;
}

SurfaceMesh uvSphere(double radius, int rings, int sectors) {
  if (!(radius > 0.0) || rings < 2 || sectors < 3) {
    throw std::invalid_argument("uvSphere: radius > 0, rings >= 2, sectors >= 3");
  }
  // North pole, rings - 1 circles of latitude, south pole.
  SurfaceMesh m;
  m.vertices.push_back(Vec3(0, radius, 0));
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / sectors;
      m.vertices.push_back(radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)));
    }
  }
  const int south = static_cast<int>(m.vertices.size());
  m.vertices.push_back(Vec3(0, -radius, 0));

  // Caps of triangles at the poles, quads split in two between circles; all wound outward.
  auto at = [&](int r, int s) { return 1 + (r - 1) * sectors + (s % sectors); };
  for (int s = 0; s < sectors; ++s) m.triangles.push_back({0, at(1, s), at(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < sectors; ++s) {
      m.triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  }
  for (int s = 0; s < sectors; ++s) m.triangles.push_back({south, at(rings - 1, s + 1), at(rings - 1, s)});
  return m;
}

SurfaceMesh boxMesh(const Vec3& h, int divisions) {
  if (!(h.minCoeff() > 0.0) || divisions < 1) throw std::invalid_argument("boxMesh: half extents > 0, divisions >= 1");
  SurfaceMesh m;
  // Grid points shared between faces are found again by their integer grid coordinates.
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](const std::array<int, 3>& g) {
    if (auto it = index.find(g); it != index.end()) return it->second;
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = h[k] * (2.0 * g[k] / divisions - 1.0);
    m.vertices.push_back(p);
    const int i = static_cast<int>(m.vertices.size()) - 1;
    index.emplace(g, i);
    return i;
  };
  // Each face: its normal axis and side, and (u, v) axes with u x v along the outward normal.
  struct Face { int n, u, v; bool positive; };
  const std::array<Face, 6> faces = {Face{0, 1, 2, true}, Face{0, 2, 1, false}, Face{1, 2, 0, true},
                                     Face{1, 0, 2, false}, Face{2, 0, 1, true}, Face{2, 1, 0, false}};
  for (const Face& f : faces) {
    auto grid = [&](int i, int j) {
      std::array<int, 3> g{};
      g[f.n] = f.positive ? divisions : 0;
      g[f.u] = i;
      g[f.v] = j;
      return vertex(g);
    };
    for (int i = 0; i < divisions; ++i) {
      for (int j = 0; j < divisions; ++j) {
        const int p00 = grid(i, j), p10 = grid(i + 1, j), p11 = grid(i + 1, j + 1), p01 = grid(i, j + 1);
        m.triangles.push_back({p00, p10, p11});
        m.triangles.push_back({p00, p11, p01});
      }
    }
  }
  return m;
}

SurfaceMesh ringMesh(int points, double radius) {
  if (points < 3 || !(radius > 0.0)) throw std::invalid_argument("ringMesh: points >= 3, radius > 0");
  SurfaceMesh m;
  for (int i = 0; i < points; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / points;
    m.vertices.push_back(Vec3(radius * std::cos(phi), radius * std::sin(phi), 0.0));
    m.segments.push_back({i, (i + 1) % points});
  }
  return m;
}

SurfaceMesh reversed(const SurfaceMesh& mesh) {
  SurfaceMesh r = mesh;
  for (Triangle& t : r.triangles) std::swap(t.b, t.c);
  for (Segment& s : r.segments) std::swap(s.a, s.b);
  return r;
}

void checkClosedSurface(const SurfaceMesh& mesh, const std::string& source, int base) {
  auto fail = [&](const std::string& what) { throw MeshError(source + ": " + what); };
  const int n = static_cast<int>(mesh.vertices.size());
  if (mesh.triangles.empty() == mesh.segments.empty()) {
    fail(mesh.triangles.empty() ? "has no faces (a soft body needs a closed surface)"
                                : "mixes triangles and 2D segments");
  }
  const bool planar = !mesh.segments.empty();

  // Finite vertices; a 2D curve lies in the plane z = 0. The size sets the zero-area scale.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (int i = 0; i < n; ++i) {
    const Vec3& p = mesh.vertices[i];
    if (!p.allFinite()) fail("vertex " + std::to_string(i + base) + " is not a finite point");
    if (planar && p.z() != 0.0) fail("vertex " + std::to_string(i + base) + " of a 2D curve is not in the plane z = 0");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = n > 0 ? (hi - lo).norm() : 0.0;
  const double tiny = 1e-12 * size * size;

  // Every face: indices in range, no repeated corner, a non-zero area (length in 2D).
  std::vector<std::vector<int>> faces;
  for (const Triangle& t : mesh.triangles) faces.push_back({t.a, t.b, t.c});
  for (const Segment& s : mesh.segments) faces.push_back({s.a, s.b});
  std::vector<bool> used(static_cast<size_t>(n), false);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const std::vector<int>& c = faces[f];
    for (int v : c) {
      if (v < 0 || v >= n) {
        fail(faceText(f, c, base) + ": vertex index " + std::to_string(v + base) + " is out of range (the mesh has " +
             std::to_string(n) + " vertices, numbered from " + std::to_string(base) + ")");
      }
      used[v] = true;
    }
    bool degenerate = false;
    for (size_t i = 0; i < c.size(); ++i) degenerate |= c[i] == c[(i + 1) % c.size()];
    if (!degenerate && c.size() == 3) {
      const Vec3 cross = (mesh.vertices[c[1]] - mesh.vertices[c[0]]).cross(mesh.vertices[c[2]] - mesh.vertices[c[0]]);
      degenerate = cross.norm() <= tiny;
    }
    if (!degenerate && c.size() == 2) degenerate = (mesh.vertices[c[1]] - mesh.vertices[c[0]]).norm() <= 1e-12 * size;
    if (degenerate) fail(faceText(f, c, base) + " is degenerate (" + (planar ? "zero length" : "zero area") + ")");
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) fail("vertex " + std::to_string(i + base) + " belongs to no face (it would float free)");
  }

  // Consistent winding: no directed edge is run by two faces. Closed: each directed edge
  // has its reverse in another face. (A 2D curve's segments are its edges.)
  std::map<std::pair<int, int>, int> owner;  // directed edge -> face
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const std::vector<int>& c = faces[f];
    const size_t edges = planar ? 1 : 3;
    for (size_t i = 0; i < edges; ++i) {
      const std::pair<int, int> e{c[i], c[(i + 1) % c.size()]};
      auto [it, fresh] = owner.emplace(e, f);
      if (!fresh) {
        fail(faceText(f, c, base) + " runs edge " + std::to_string(e.first + base) + " -> " +
             std::to_string(e.second + base) + " in the same direction as " + faceText(it->second, faces[it->second], base) +
             ": the winding is inconsistent (or more than two faces meet at the edge)");
      }
    }
  }
  if (planar) {
    // Each vertex starts exactly one segment and ends exactly one: closed loops.
    std::vector<int> in(static_cast<size_t>(n), 0), out(static_cast<size_t>(n), 0);
    for (const Segment& s : mesh.segments) {
      ++out[s.a];
      ++in[s.b];
    }
    for (int i = 0; i < n; ++i) {
      if (in[i] != 1 || out[i] != 1) {
        fail("vertex " + std::to_string(i + base) + " starts " + std::to_string(out[i]) + " and ends " +
             std::to_string(in[i]) + " segments: the curve is not a closed, consistently directed loop");
      }
    }
    return;
  }
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const std::vector<int>& c = faces[f];
    for (size_t i = 0; i < 3; ++i) {
      const int a = c[i], b = c[(i + 1) % 3];
      if (!owner.count({b, a})) {
        fail(faceText(f, c, base) + ": its edge " + std::to_string(a + base) + " - " + std::to_string(b + base) +
             " has no face on the other side: the surface is not closed");
      }
    }
  }
}

}  // namespace springlab
