#pragma once
// Closed surfaces a soft body is made of: generated (icosphere, UV sphere, box, 2D ring) or
// read from a file (Wavefront OBJ, 3D Studio ASCII). Every mesh handed to a lab has passed
// checkClosedSurface(): indices in range, no degenerate element, every edge shared by exactly
// two faces that run it in opposite directions. Which way the faces turn (outward or inward)
// is for the lab to find out: that takes the enclosed volume, an exercise of Lab 3.
#include <stdexcept>
#include <string>
#include <vector>

#include "springlab/math.hpp"
#include "springlab/simulation.hpp"

namespace springlab {

// A directed edge of a closed 2D curve, a -> b; the inside lies to its left.
struct Segment {
  int a, b;
};

struct SurfaceMesh {
  std::vector<Vec3> vertices;       // [n] m
  std::vector<Triangle> triangles;  // [t] a closed 3D surface (empty in 2D)
  std::vector<Segment> segments;    // [s] a closed 2D curve in the plane z = 0 (empty in 3D)
};

// A mesh that cannot bound a soft body; what() names the file and the first bad element.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---- generated meshes: counter-clockwise seen from outside, centred at the origin ---------
// Icosahedron split `subdivisions` times (each split makes every triangle four), vertices on
// the sphere: 10 * 4^s + 2 vertices, 20 * 4^s triangles of nearly equal area.
SurfaceMesh icosphere(double radius, int subdivisions);
// Latitude-longitude sphere: `rings` >= 2 bands from pole to pole, `sectors` >= 3 around.
SurfaceMesh uvSphere(double radius, int rings, int sectors);
// Box of the given half extents, each face split into divisions x divisions squares.
SurfaceMesh boxMesh(const Vec3& halfExtents, int divisions);
// n >= 3 points on a circle in the plane z = 0, counter-clockwise, joined into a loop.
SurfaceMesh ringMesh(int points, double radius);

// ---- files -----------------------------------------------------------------------------
// Wavefront OBJ (through tinyobjloader; polygons are split into triangles). Faces are
// numbered from 1 in messages, as OBJ numbers its vertices.
SurfaceMesh loadObj(const std::string& path);
// 3D Studio ASCII: "Tri-mesh, Vertices: n Faces: m", then "Vertex i: X: x Y: y Z: z" and
// "Face i: A: a B: b C: c ..." lines; other lines (materials, smoothing) are skipped.
SurfaceMesh loadAsc(const std::string& path);
// By extension: .obj or .asc; throws MeshError for any other.
SurfaceMesh loadMesh(const std::string& path);

// Throws MeshError, naming `source` and the first offending element, unless the mesh is a
// closed, consistently wound triangle surface (3D) or a set of closed loops (2D).
// `firstFaceNumber` is how the source numbers its faces in messages (0 or 1).
void checkClosedSurface(const SurfaceMesh& mesh, const std::string& source, int firstFaceNumber = 0);

// The same mesh with every face turned over (a -> b becomes b -> a).
SurfaceMesh reversed(const SurfaceMesh& mesh);

}  // namespace springlab
