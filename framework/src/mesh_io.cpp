// Mesh files: Wavefront OBJ through tinyobjloader, and the 3D Studio ASCII format read here.
// Both check the surface they read (checkClosedSurface) before handing it out.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <tiny_obj_loader.h>

#include "springlab/mesh.hpp"

namespace springlab {

SurfaceMesh loadObj(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw MeshError(path + ": cannot open the mesh file");
  // tinyobjloader splits polygons into triangles; materials are not needed.
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    throw MeshError(path + ": not a readable OBJ file: " + reader.Error());
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  SurfaceMesh m;
  for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3) {
    m.vertices.push_back(Vec3(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]));
  }
  // Every object ("o"/"g") of the file joins one surface; a face that is still not a triangle
  // after splitting (fewer than 3 corners) is kept so the check names it.
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (const unsigned char corners : shape.mesh.num_face_vertices) {
      if (corners != 3) {
        throw MeshError(path + ": face " + std::to_string(m.triangles.size() + 1) + " has " +
                        std::to_string(corners) + " corners after splitting polygons into triangles");
      }
      const auto& idx = shape.mesh.indices;
      m.triangles.push_back({idx[offset].vertex_index, idx[offset + 1].vertex_index, idx[offset + 2].vertex_index});
      offset += corners;
    }
  }
  checkClosedSurface(m, path, 1);
  return m;
}

SurfaceMesh loadAsc(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshError(path + ": cannot open the mesh file");
  const std::string number = R"(([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?))";
  const std::regex header(R"(^\s*Tri-mesh,\s*Vertices:\s*(\d+)\s+Faces:\s*(\d+)\s*$)");
  const std::regex vertex(R"(^\s*Vertex\s+(\d+)\s*:\s*X:\s*)" + number + R"(\s+Y:\s*)" + number + R"(\s+Z:\s*)" +
                          number + R"(\s*$)");
  const std::regex face(R"(^\s*Face\s+(\d+)\s*:\s*A:\s*(\d+)\s+B:\s*(\d+)\s+C:\s*(\d+)(\s+.*)?$)");
  const std::regex vertexLike(R"(^\s*Vertex\s+\d)"), faceLike(R"(^\s*Face\s+\d)");

  SurfaceMesh m;
  long vertices = -1, faces = -1;
  std::string line;
  int lineNumber = 0;
  auto fail = [&](const std::string& what) {
    throw MeshError(path + ":" + std::to_string(lineNumber) + ": " + what);
  };
  // Header, then numbered vertex and face lines; materials, smoothing and the like are skipped.
  while (std::getline(in, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch g;
    if (std::regex_match(line, g, header)) {
      if (vertices >= 0) fail("a second Tri-mesh: one object per file");
      vertices = std::stol(g[1]);
      faces = std::stol(g[2]);
    } else if (std::regex_match(line, g, vertex)) {
      if (vertices < 0) fail("a vertex before the \"Tri-mesh, Vertices: n Faces: m\" header");
      if (std::stol(g[1]) != static_cast<long>(m.vertices.size())) {
        fail("vertex numbered " + g[1].str() + ", expected " + std::to_string(m.vertices.size()));
      }
      m.vertices.push_back(Vec3(std::stod(g[2]), std::stod(g[3]), std::stod(g[4])));
    } else if (std::regex_match(line, g, face)) {
      if (vertices < 0) fail("a face before the \"Tri-mesh, Vertices: n Faces: m\" header");
      if (std::stol(g[1]) != static_cast<long>(m.triangles.size())) {
        fail("face numbered " + g[1].str() + ", expected " + std::to_string(m.triangles.size()));
      }
      auto index = [&](int k) {
        const long v = std::stol(g[k]);
        return v > 1000000000L ? -1 : static_cast<int>(v);
      };
      m.triangles.push_back({index(2), index(3), index(4)});
    } else if (std::regex_search(line, vertexLike)) {
      fail("cannot read this vertex line (expected \"Vertex i: X: x Y: y Z: z\")");
    } else if (std::regex_search(line, faceLike)) {
      fail("cannot read this face line (expected \"Face i: A: a B: b C: c\")");
    }
  }
  lineNumber = 0;
  if (vertices < 0) throw MeshError(path + ": no \"Tri-mesh, Vertices: n Faces: m\" header: not a 3D Studio ASCII mesh");
  if (static_cast<long>(m.vertices.size()) != vertices || static_cast<long>(m.triangles.size()) != faces) {
    throw MeshError(path + ": the header announces " + std::to_string(vertices) + " vertices and " +
                    std::to_string(faces) + " faces, the file lists " + std::to_string(m.vertices.size()) +
                    " and " + std::to_string(m.triangles.size()));
  }
  checkClosedSurface(m, path, 0);
  return m;
}

SurfaceMesh loadMesh(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".obj" || ext == ".OBJ") return loadObj(path);
  if (ext == ".asc" || ext == ".ASC") return loadAsc(path);
  throw MeshError(path + ": unknown mesh format \"" + ext + "\" (use .obj or .asc)");
}

}  // namespace springlab
