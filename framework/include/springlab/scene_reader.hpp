#pragma once
// Reads one JSON scene file strictly: every key a scene needs must be present, every key
// present must be known, and every number must be finite and in range. Errors name the
// file and the key ("scenes/rope.json: rope.spring_constant: must be > 0, got -3").
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "springlab/math.hpp"

namespace springlab {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SceneReader {
 public:
  // Parse a file; a missing file or malformed JSON raises SceneError naming the file.
  static SceneReader fromFile(const std::string& path);
  // Read from JSON text already in memory (tests); `file` names it in messages.
  static SceneReader fromText(const std::string& text, const std::string& file);
  // Read a document already parsed (a SceneDocument after its --set edits), without printing
  // and parsing it again; SceneError naming `file` when it is not a JSON object.
  static SceneReader fromJson(nlohmann::json root, const std::string& file);

  // Typed reads of one key of this object; each marks the key as known.
  double number(const std::string& key);            // any finite number
  double positive(const std::string& key);          // > 0
  double nonNegative(const std::string& key);       // >= 0
  int integer(const std::string& key, int minimum); // integer >= minimum
  bool boolean(const std::string& key);
  std::string string(const std::string& key);
  Vec3 vec3(const std::string& key);                // [x, y, z], finite
  SceneReader object(const std::string& key);       // nested object
  std::vector<std::string> strings(const std::string& key);  // array of strings, may be empty
  // Array of objects, may be empty; each reads like object() and names itself "key[i]".
  std::vector<SceneReader> objects(const std::string& key);
  bool has(const std::string& key) const;

  // Raise SceneError for the first key of this object that no read asked for.
  void rejectUnknownKeys() const;

  // Raise SceneError about `key` with the file and path prefixed.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  const std::string& file() const { return *file_; }

 private:
  SceneReader(std::shared_ptr<const nlohmann::json> root, const nlohmann::json* node,
              std::shared_ptr<const std::string> file, std::string path);
  const nlohmann::json& require(const std::string& key);
  std::string where(const std::string& key) const;

  std::shared_ptr<const nlohmann::json> root_;  // keeps the parsed document alive
  const nlohmann::json* node_;                  // the object this reader reads
  std::shared_ptr<const std::string> file_;
  std::string path_;                            // "rope.ground" for nested objects
  std::shared_ptr<std::set<std::string>> used_;
};

}  // namespace springlab
