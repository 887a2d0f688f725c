// JSON values of the scene file with their place in it.
#include "mesh/scene/readers/scene_json.h"

#include <algorithm>
#include <cmath>

#include "mesh/base/error.h"

namespace rad::scene_file {
namespace {

/// Says what a JSON value is, for "found ..." in messages.
std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return j.get<bool>() ? "true" : "false";
    case json::value_t::string: return "the string " + j.dump();
    case json::value_t::array: return "an array of " + std::to_string(j.size()) + " items";
    case json::value_t::object: return "an object";
    default: return "the number " + j.dump();
  }
}

}  // namespace

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}

void Node::fail(const std::string& expected) const {
  throw inputError(where(), expected, describe(j_));
}

void Node::failWith(const std::string& expected, const std::string& found) const {
  throw inputError(where(), expected, found);
}

void Node::expectObject(const std::vector<std::string>& accepted) const {
  if (!j_.is_object()) fail("an object");
  for (const auto& item : j_.items()) {
    if (std::find(accepted.begin(), accepted.end(), item.key()) == accepted.end())
      throw inputError(where(), "one of the keys " + join(accepted),
                       "the unknown key \"" + item.key() + "\"");
  }
}

void Node::expectArray(size_t minSize, const std::string& what) const {
  if (!j_.is_array()) fail("an array of " + what);
  if (j_.size() < minSize) fail("at least " + std::to_string(minSize) + " " + what);
}

double Node::number() const {
  if (!j_.is_number()) fail("a number");
  double x = j_.get<double>();
  if (!std::isfinite(x)) fail("a finite number");
  return x;
}

double Node::number(double lo, double hi, const std::string& range) const {
  double x = number();
  if (!(x >= lo && x <= hi)) fail("a number in " + range);
  return x;
}

double Node::wholeNumber(double lo, double hi, const std::string& range) const {
  double x = number(lo, hi, range);
  if (x != std::floor(x)) fail("a whole number");
  return x;
}

std::string Node::string() const {
  if (!j_.is_string()) fail("a string");
  return j_.get<std::string>();
}

bool Node::boolean() const {
  if (!j_.is_boolean()) fail("true or false");
  return j_.get<bool>();
}

glm::dvec3 Node::vec3() const {
  if (!j_.is_array() || j_.size() != 3) fail("an array of 3 numbers");
  return {(*this)[size_t(0)].number(), (*this)[1].number(), (*this)[2].number()};
}

glm::dvec4 Node::color() const {
  if (!j_.is_array() || (j_.size() != 3 && j_.size() != 4)) fail("an array of 3 or 4 numbers");
  glm::dvec4 c(1.0);
  for (size_t i = 0; i < j_.size(); ++i) c[int(i)] = (*this)[i].number();
  return c;
}

glm::dvec3 nonNegativeRgb(const Node& n, const std::string& what) {
  glm::dvec3 c = n.vec3();
  for (int i = 0; i < 3; ++i)
    if (c[i] < 0) n[size_t(i)].fail(what);
  return c;
}

glm::dvec3 reflectanceRgb(const Node& n) {
  glm::dvec3 c = n.vec3();
  for (int i = 0; i < 3; ++i)
    if (!(c[i] >= 0 && c[i] < 1)) n[size_t(i)].fail("a reflectance in [0, 1)");
  return c;
}

}  // namespace rad::scene_file
