#include "springlab/scene_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace springlab {

SceneReader::SceneReader(std::shared_ptr<const nlohmann::json> root, const nlohmann::json* node,
                         std::shared_ptr<const std::string> file, std::string path)
    : root_(std::move(root)),
      node_(node),
      file_(std::move(file)),
      path_(std::move(path)),
      used_(std::make_shared<std::set<std::string>>()) {}

SceneReader SceneReader::fromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return fromText(text.str(), path);
}

SceneReader SceneReader::fromText(const std::string& text, const std::string& file) {
  // Parse here so the message can name the file. JSON has no NaN literal, so a "NaN" in a
  // scene file is reported as malformed JSON.
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw SceneError(file + ": malformed JSON: " + e.what());
  }
  return fromJson(std::move(root), file);
}

SceneReader SceneReader::fromJson(nlohmann::json root, const std::string& file) {
  if (!root.is_object()) throw SceneError(file + ": the scene must be a JSON object {...}");
  auto shared = std::make_shared<const nlohmann::json>(std::move(root));
  const nlohmann::json* node = shared.get();
  return SceneReader(std::move(shared), node, std::make_shared<const std::string>(file), "");
}

std::string SceneReader::where(const std::string& key) const {
  return *file_ + ": " + (path_.empty() ? key : path_ + "." + key);
}

void SceneReader::fail(const std::string& key, const std::string& message) const {
  throw SceneError(where(key) + ": " + message);
}

bool SceneReader::has(const std::string& key) const { return node_->contains(key); }

const nlohmann::json& SceneReader::require(const std::string& key) {
  used_->insert(key);
  if (!node_->contains(key)) fail(key, "missing key (every scene parameter must be given)");
  return (*node_)[key];
}

double SceneReader::number(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite, got " + v.dump());
  return x;
}

double SceneReader::positive(const std::string& key) {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be > 0, got " + require(key).dump());
  return x;
}

double SceneReader::nonNegative(const std::string& key) {
  const double x = number(key);
  if (!(x >= 0.0)) fail(key, "must be >= 0, got " + require(key).dump());
  return x;
}

int SceneReader::integer(const std::string& key, int minimum) {
  const auto& v = require(key);
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + v.dump());
  const long long x = v.get<long long>();
  if (x < minimum) fail(key, "must be >= " + std::to_string(minimum) + ", got " + v.dump());
  if (x > 100000000) fail(key, "is too large, got " + v.dump());
  return static_cast<int>(x);
}

bool SceneReader::boolean(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_boolean()) fail(key, "must be true or false, got " + v.dump());
  return v.get<bool>();
}

std::string SceneReader::string(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_string()) fail(key, "must be a string, got " + v.dump());
  return v.get<std::string>();
}

Vec3 SceneReader::vec3(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_array() || v.size() != 3) fail(key, "must be an array of 3 numbers, got " + v.dump());
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail(key, "must be an array of 3 numbers, got " + v.dump());
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "must be finite, got " + v.dump());
  }
  return out;
}

SceneReader SceneReader::object(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_object()) fail(key, "must be an object {...}, got " + v.dump());
  return SceneReader(root_, &v, file_, path_.empty() ? key : path_ + "." + key);
}

std::vector<std::string> SceneReader::strings(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_array()) fail(key, "must be an array of strings, got " + v.dump());
  std::vector<std::string> out;
  for (const auto& item : v) {
    if (!item.is_string()) fail(key, "must be an array of strings, got " + v.dump());
    out.push_back(item.get<std::string>());
  }
  return out;
}

std::vector<SceneReader> SceneReader::objects(const std::string& key) {
  const auto& v = require(key);
  if (!v.is_array()) fail(key, "must be an array of objects [{...}, ...], got " + v.dump());
  std::vector<SceneReader> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string name = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) fail(name, "must be an object {...}, got " + v[i].dump());
    out.push_back(SceneReader(root_, &v[i], file_, path_.empty() ? name : path_ + "." + name));
  }
  return out;
}

void SceneReader::rejectUnknownKeys() const {
  for (const auto& item : node_->items()) {
    if (!used_->count(item.key())) fail(item.key(), "unknown key (misspelt, or not a parameter of this scene)");
  }
}

}  // namespace springlab
