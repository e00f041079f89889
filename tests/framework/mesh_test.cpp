// Meshes for soft bodies: generated ones are closed and wound outward; files are read, and
// a surface that cannot hold a gas is refused with the file and the first bad element named.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <string>

#include <springlab/mesh.hpp>

namespace springlab {
namespace {

// Every face of a convex mesh around the origin turns its normal away from the origin.
void expectOutward(const SurfaceMesh& m, const std::string& what) {
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.vertices[t.a], b = m.vertices[t.b], c = m.vertices[t.c];
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0.0) << what << ": a face is wound inward";
  }
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

// A file in the test's temporary folder.
std::string write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("springlab_mesh_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(Mesh, GeneratedSpheresAndBoxesAreClosedAndWoundOutward) {
  for (int s = 0; s <= 3; ++s) {
    const SurfaceMesh m = icosphere(2.0, s);
    EXPECT_EQ(m.vertices.size(), 10u * (1u << (2 * s)) + 2u) << "an icosphere has 10 4^s + 2 vertices";
    EXPECT_EQ(m.triangles.size(), 20u * (1u << (2 * s)));
    for (const Vec3& v : m.vertices) EXPECT_NEAR(v.norm(), 2.0, 1e-12) << "icosphere vertices lie on the sphere";
    EXPECT_NO_THROW(checkClosedSurface(m, "icosphere"));
    expectOutward(m, "icosphere");
  }
  const SurfaceMesh uv = uvSphere(1.0, 6, 9), box = boxMesh(Vec3(1, 2, 3), 3);
  EXPECT_NO_THROW(checkClosedSurface(uv, "uv sphere"));
  EXPECT_NO_THROW(checkClosedSurface(box, "box"));
  expectOutward(uv, "uv sphere");
  expectOutward(box, "box");
  EXPECT_EQ(box.vertices.size(), 6u * 9u + 2u) << "a box split 3 x 3 per face has 6 * 3^2 + 2 vertices";
}

TEST(Mesh, RingRunsCounterClockwiseInThePlane) {
  const SurfaceMesh ring = ringMesh(17, 30.0);
  ASSERT_EQ(ring.segments.size(), 17u);
  EXPECT_NO_THROW(checkClosedSurface(ring, "ring"));
  for (const Segment& s : ring.segments) {
    const Vec3 a = ring.vertices[s.a], b = ring.vertices[s.b];
    EXPECT_GT(a.cross(b).z(), 0.0) << "the ring must run counter-clockwise";
    EXPECT_EQ(a.z(), 0.0);
  }
}

TEST(MeshFiles, ShippedObjOfQuadsIsSplitIntoAClosedSurface) {
  const SurfaceMesh m = loadMesh(std::string(SPRINGLAB_SOURCE_DIR) + "/scenes/meshes/pillow.obj");
  EXPECT_EQ(m.vertices.size(), 218u);
  EXPECT_EQ(m.triangles.size(), 2u * 216u) << "each quad of the OBJ becomes two triangles";
}

TEST(MeshFiles, Shipped3DStudioAsciiCubeIsRead) {
  const SurfaceMesh m = loadMesh(std::string(SPRINGLAB_SOURCE_DIR) + "/scenes/meshes/cube.asc");
  EXPECT_EQ(m.vertices.size(), 26u);
  EXPECT_EQ(m.triangles.size(), 48u);
  EXPECT_EQ(m.vertices[0], Vec3(1.0, -1.0, -1.0)) << "Vertex 0: X:1.0 Y:-1.0 Z:-1.0";
  expectOutward(m, "cube.asc");
}

// A tetrahedron in 3D Studio ASCII with its faces given as text.
std::string ascTetrahedron(const std::string& faces, int faceCount = 4) {
  return "Named object: \"Tet\"\nTri-mesh, Vertices: 4 Faces: " + std::to_string(faceCount) +
         "\nVertex list:\nVertex 0: X:0 Y:0 Z:0\nVertex 1: X:1 Y:0 Z:0\nVertex 2: X:0 Y:1 Z:0\n"
         "Vertex 3: X:0 Y:0 Z:1\nFace list:\n" + faces;
}
const std::string kGoodFaces = "Face 0: A:0 B:2 C:1\nFace 1: A:0 B:1 C:3\nFace 2: A:0 B:3 C:2\nFace 3: A:1 B:2 C:3\n";

TEST(MeshCheck, AcceptsAClosedTetrahedron) {
  EXPECT_NO_THROW(loadMesh(write("good.asc", ascTetrahedron(kGoodFaces))));
  EXPECT_NO_THROW(loadMesh(write("good.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")));
}

TEST(MeshCheck, RefusesAnOpenSurfaceNamingTheFace) {
  const std::string path = write("open.asc", ascTetrahedron("Face 0: A:0 B:2 C:1\nFace 1: A:0 B:1 C:3\nFace 2: A:0 B:3 C:2\n", 3));
  const std::string msg = messageOf([&] { loadMesh(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << "the message must name the file: " << msg;
  EXPECT_NE(msg.find("face 0 (vertices 0 2 1)"), std::string::npos) << "the message must name the first open face: " << msg;
  EXPECT_NE(msg.find("not closed"), std::string::npos) << msg;
}

TEST(MeshCheck, RefusesInconsistentWindingNamingTheFace) {
  // Face 3 turned over: it runs its edges the same way as its neighbours.
  const std::string path = write("wound.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n");
  const std::string msg = messageOf([&] { loadMesh(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << "the message must name the file: " << msg;
  EXPECT_NE(msg.find("face 4 (vertices 2 4 3)"), std::string::npos)
      << "the message must name the first face wound the other way, numbered as OBJ numbers faces: " << msg;
  EXPECT_NE(msg.find("winding is inconsistent"), std::string::npos) << msg;
}

TEST(MeshCheck, RefusesADegenerateTriangle) {
  const std::string path = write("flat.asc", ascTetrahedron("Face 0: A:0 B:2 C:1\nFace 1: A:0 B:1 C:1\nFace 2: A:0 B:3 C:2\nFace 3: A:1 B:2 C:3\n"));
  const std::string msg = messageOf([&] { loadMesh(path); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("face 1 (vertices 0 1 1) is degenerate"), std::string::npos) << msg;
  // Three distinct corners on one line have no area either.
  SurfaceMesh line = icosphere(1.0, 0);
  line.vertices[line.triangles[5].c] = 0.5 * (line.vertices[line.triangles[5].a] + line.vertices[line.triangles[5].b]);
  const std::string msg2 = messageOf([&] { checkClosedSurface(line, "line"); });
  EXPECT_NE(msg2.find("degenerate"), std::string::npos) << "a face with collinear corners must be refused: " << msg2;
}

TEST(MeshCheck, RefusesAnIndexOutOfRange) {
  const std::string obj = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 9\nf 1 4 3\nf 2 3 4\n");
  const std::string msg = messageOf([&] { loadMesh(obj); });
  EXPECT_NE(msg.find(obj), std::string::npos) << msg;
  EXPECT_NE(msg.find("face 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("vertex index 9 is out of range"), std::string::npos) << msg;
  const std::string asc = write("range.asc", ascTetrahedron("Face 0: A:0 B:2 C:1\nFace 1: A:0 B:1 C:3\nFace 2: A:0 B:7 C:2\nFace 3: A:1 B:2 C:3\n"));
  const std::string msg2 = messageOf([&] { loadMesh(asc); });
  EXPECT_NE(msg2.find("face 2 (vertices 0 7 2): vertex index 7 is out of range"), std::string::npos) << msg2;
}

// A polygon with a bad index: tinyobjloader drops it silently, and the surface check would
// then blame a neighbour ("not closed"); the loader names the file, line and index instead.
TEST(MeshCheck, RefusesAQuadWithAnIndexOutOfRangeNamingTheLine) {
  const std::string path = write("quad_range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 999 4\nf 4 3 2 1\n");
  const std::string msg = messageOf([&] { loadMesh(path); });
  EXPECT_NE(msg.find(path + ":5: face 1 (f 1 2 999 4): vertex index 999 is out of range"), std::string::npos)
      << "the message must name the file, line, face and index: " << msg;
  EXPECT_EQ(msg.find("not closed"), std::string::npos) << msg;
  const std::string relative = write("relative_range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -4\n");
  EXPECT_NE(messageOf([&] { loadMesh(relative); }).find(":4: face 1 (f -1 -2 -4): vertex index -4 is out of range"),
            std::string::npos);
}

TEST(MeshFiles, RefuseMalformedFilesNamingTheLine) {
  const std::string bad = write("bad.asc", ascTetrahedron("Face 0: A:0 B:2\n" + kGoodFaces));
  const std::string msg = messageOf([&] { loadMesh(bad); });
  EXPECT_NE(msg.find(bad + ":9:"), std::string::npos) << "the message must name the file and line: " << msg;
  const std::string counts = write("counts.asc", ascTetrahedron(kGoodFaces, 5));
  EXPECT_NE(messageOf([&] { loadMesh(counts); }).find("announces 4 vertices and 5 faces"), std::string::npos);
  EXPECT_NE(messageOf([&] { loadMesh(write("x.stl", "solid")); }).find("unknown mesh format"), std::string::npos);
  EXPECT_NE(messageOf([&] { loadMesh("/no/such/file.obj"); }).find("cannot open"), std::string::npos);
}

TEST(Mesh, ReversedTurnsEveryFaceOver) {
  const SurfaceMesh m = icosphere(1.0, 1), r = reversed(m);
  ASSERT_EQ(r.triangles.size(), m.triangles.size());
  EXPECT_NO_THROW(checkClosedSurface(r, "reversed"));
  const Triangle& a = m.triangles[3];
  const Triangle& b = r.triangles[3];
  EXPECT_TRUE(a.a == b.a && a.b == b.c && a.c == b.b);
}

}  // namespace
}  // namespace springlab
