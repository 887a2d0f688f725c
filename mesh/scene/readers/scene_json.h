#pragma once
// Internal to the scene loader: JSON values that know their place in the scene file, so that
// every message says where ("scene.json: surfaces[3].polygon"), what was expected and what
// was found.
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

namespace rad::scene_file {

using json = nlohmann::ordered_json;

/// The items joined by ", ".
std::string join(const std::vector<std::string>& items);

/// A JSON value with its location ("scene.json: surfaces[3].polygon") for messages.
class Node {
 public:
  Node(const json& j, std::string file, std::string path)
      : j_(j), file_(std::move(file)), path_(std::move(path)) {}

  const json& value() const { return j_; }
  std::string where() const { return path_.empty() ? file_ : file_ + ": " + path_; }
  /// Throws "<where>: expected <expected>, found <what this value is>".
  [[noreturn]] void fail(const std::string& expected) const;
  [[noreturn]] void failWith(const std::string& expected, const std::string& found) const;

  bool has(const char* key) const { return j_.contains(key); }
  Node operator[](const char* key) const {
    return Node(j_.at(key), file_, path_.empty() ? key : path_ + "." + key);
  }
  Node operator[](size_t i) const {
    return Node(j_.at(i), file_, path_ + "[" + std::to_string(i) + "]");
  }
  size_t size() const { return j_.size(); }

  /// Requires an object whose keys are all among `accepted`.
  void expectObject(const std::vector<std::string>& accepted) const;
  /// Requires an array of at least minSize items (`what` names them for messages).
  void expectArray(size_t minSize, const std::string& what) const;
  /// A finite number; within [lo, hi] (said as `range`) for the second form.
  double number() const;
  double number(double lo, double hi, const std::string& range) const;
  /// A whole number within [lo, hi] (said as `range`).
  double wholeNumber(double lo, double hi, const std::string& range) const;
  std::string string() const;
  bool boolean() const;
  glm::dvec3 vec3() const;
  /// An RGB colour; OpenGL's RGBA also accepted, alpha 1 by default.
  glm::dvec4 color() const;

 private:
  const json& j_;
  std::string file_, path_;
};

/// Three numbers, each >= 0 (`what` says so in messages).
glm::dvec3 nonNegativeRgb(const Node& n, const std::string& what);

/// Three reflectances, each in [0, 1).
glm::dvec3 reflectanceRgb(const Node& n);

}  // namespace rad::scene_file
