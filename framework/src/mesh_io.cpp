// Mesh files: Wavefront OBJ through tinyobjloader, and the 3D Studio ASCII format read here.
// Both check the surface they read (checkClosedSurface) before handing it out.
#include <filesystem>
#include <fstream>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

#include <tiny_obj_loader.h>

#include "springlab/mesh.hpp"

namespace springlab {

namespace {

// tinyobjloader drops a polygon with an index out of range without a word (the surface check
// then names a neighbouring face): every "f" line's vertex indices are checked here first,
// naming the file, the line, the face and the index. Positive indices count from 1 over the
// file's vertices, negative ones back from the last vertex read.
void checkObjFaceIndices(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshError(path + ": cannot open the mesh file");
  long total = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0 || line.rfind("v\t", 0) == 0) ++total;
  }
  in.clear();
  in.seekg(0);
  long lineNumber = 0, seen = 0, face = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNumber;
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "v") ++seen;
    if (word != "f") continue;
    ++face;
    for (std::string corner; words >> corner;) {
      const long index = std::strtol(corner.c_str(), nullptr, 10);
      const bool valid = index > 0 ? index <= total : index < 0 && -index <= seen;
      if (!valid) {
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
        throw MeshError(path + ":" + std::to_string(lineNumber) + ": face " + std::to_string(face) + " (" + line +
                        "): vertex index " + corner.substr(0, corner.find('/')) + " is out of range (the file has " +
                        std::to_string(total) + " vertices, numbered from 1)");
      }
    }
  }
}

}  // namespace

SurfaceMesh loadObj(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw MeshError(path + ": cannot open the mesh file");
  checkObjFaceIndices(path);
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

namespace {

// The number after `key` ("X:", "Faces:") where the key starts a word, or nothing.
std::optional<double> valueAfter(const std::string& line, const std::string& key, bool integer) {
  for (size_t at = line.find(key); at != std::string::npos; at = line.find(key, at + 1)) {
    if (at > 0 && !std::isspace(static_cast<unsigned char>(line[at - 1]))) continue;
    const char* begin = line.c_str() + at + key.size();
    char* end = nullptr;
    const double v = integer ? static_cast<double>(std::strtol(begin, &end, 10)) : std::strtod(begin, &end);
    if (end == begin || (*end != '\0' && !std::isspace(static_cast<unsigned char>(*end)))) return std::nullopt;
    return v;
  }
  return std::nullopt;
}

// "Vertex 12: ..." or "Face 3: ...": the number after the word, when the line is one.
std::optional<long> numberedLine(const std::string& line, const std::string& word) {
  size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line.compare(i, word.size(), word) != 0) return std::nullopt;
  i = line.find_first_not_of(" \t", i + word.size());
  if (i == std::string::npos || !std::isdigit(static_cast<unsigned char>(line[i]))) return std::nullopt;
  return std::strtol(line.c_str() + i, nullptr, 10);
}

}  // namespace

SurfaceMesh loadAsc(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshError(path + ": cannot open the mesh file");
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
    if (line.find("Tri-mesh,") != std::string::npos) {
      if (vertices >= 0) fail("a second Tri-mesh: one object per file");
      const auto v = valueAfter(line, "Vertices:", true), f = valueAfter(line, "Faces:", true);
      if (!v || !f || *v < 0 || *f < 0) fail("cannot read the header (expected \"Tri-mesh, Vertices: n Faces: m\")");
      vertices = static_cast<long>(*v);
      faces = static_cast<long>(*f);
    } else if (const auto i = numberedLine(line, "Vertex")) {
      if (vertices < 0) fail("a vertex before the \"Tri-mesh, Vertices: n Faces: m\" header");
      const auto x = valueAfter(line, "X:", false), y = valueAfter(line, "Y:", false), z = valueAfter(line, "Z:", false);
      if (!x || !y || !z) fail("cannot read this vertex line (expected \"Vertex i: X: x Y: y Z: z\")");
      if (*i != static_cast<long>(m.vertices.size())) {
        fail("vertex numbered " + std::to_string(*i) + ", expected " + std::to_string(m.vertices.size()));
      }
      m.vertices.push_back(Vec3(*x, *y, *z));
    } else if (const auto j = numberedLine(line, "Face")) {
      if (vertices < 0) fail("a face before the \"Tri-mesh, Vertices: n Faces: m\" header");
      const auto a = valueAfter(line, "A:", true), b = valueAfter(line, "B:", true), c = valueAfter(line, "C:", true);
      if (!a || !b || !c) fail("cannot read this face line (expected \"Face i: A: a B: b C: c\")");
      if (*j != static_cast<long>(m.triangles.size())) {
        fail("face numbered " + std::to_string(*j) + ", expected " + std::to_string(m.triangles.size()));
      }
      auto index = [](double v) { return std::abs(v) > 1e9 ? -1 : static_cast<int>(v); };
      m.triangles.push_back({index(*a), index(*b), index(*c)});
    }
  }
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
