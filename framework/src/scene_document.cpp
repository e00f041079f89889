#include "springlab/scene_document.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "springlab/scene_reader.hpp"

namespace springlab {

SceneDocument SceneDocument::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  SceneDocument doc;
  doc.file = path;
  try {
    doc.json = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw SceneError(path + ": malformed JSON: " + e.what());
  }
  if (!doc.json.is_object()) throw SceneError(path + ": the scene must be a JSON object {...}");
  return doc;
}

void SceneDocument::set(const std::string& assignment) {
  // Split "a.b.c=value".
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError(file + ": --set " + assignment + ": expected KEY=VALUE, e.g. rope.masses=40");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);

  // Walk to the key; every part must exist already.
  nlohmann::json* node = &json;
  std::stringstream parts(path);
  std::string part;
  while (std::getline(parts, part, '.')) {
    if (!node->is_object() || !node->contains(part)) {
      throw SceneError(file + ": --set " + assignment + ": the scene has no key " + path);
    }
    node = &(*node)[part];
  }

  // The value as JSON (numbers, arrays, true/false); anything else is a string.
  try {
    *node = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error&) {
    *node = text;
  }
}

nlohmann::json::json_pointer dottedKey(const std::string& key) {
  std::string pointer = "/" + key;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  return nlohmann::json::json_pointer(pointer);
}

}  // namespace springlab
