#pragma once
// A scene file's JSON before it is built. The command line's `--set key=value` and the
// studies (resolution, stiffness maps) edit it; Registry::loadScene(document) then reads it
// as strictly as a file, and errors still name the file.
#include <string>

#include <nlohmann/json.hpp>

namespace springlab {

struct SceneDocument {
  std::string file;     // the path it was read from, named in every error
  nlohmann::json json;  // the scene object

  // Read a file; SceneError naming the file when it is missing or not a JSON object.
  static SceneDocument read(const std::string& path);

  // Apply "section.key=value" (a dotted path to a key the scene already has; the value is
  // JSON, or a plain string). SceneError naming the assignment for an unknown key or a
  // malformed assignment, so a typo never runs a different scene than the one asked for.
  void set(const std::string& assignment);
};

// The JSON pointer of a dotted key: "mesh.subdivisions" -> "/mesh/subdivisions".
nlohmann::json::json_pointer dottedKey(const std::string& key);

}  // namespace springlab
