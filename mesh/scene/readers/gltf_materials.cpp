// glTF materials ▸ what a diffuse solver keeps of them: the base colour (times its texture's
// mean colour), the emitted radiance, and a warning for each kind of what was approximated.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "mesh/base/error.h"
#include "mesh/scene/readers/gltf_internal.h"
#include "mesh/scene/readers/texture_mean.h"

namespace rad::gltf {
namespace {

/// A material whose metallicFactor is above this is a metal: radiosity keeps its diffuse part.
constexpr double kMetallic = 0.5;
/// A base colour of 1 (white) would reflect all light and the solve never converge: its
/// brightest channel becomes this, the others in proportion.
constexpr double kMaxReflectance = 0.95;

/// baseColorFactor's RGB (white when absent), each in [0, 1].
glm::dvec3 baseColourFactor(const tinygltf::PbrMetallicRoughness& pbr, const std::string& where) {
  checkNumbers(pbr.baseColorFactor, 4, where);
  if (pbr.baseColorFactor.empty()) return glm::dvec3(1.0);
  for (int c = 0; c < 3; ++c)
    if (!(pbr.baseColorFactor[size_t(c)] >= 0 && pbr.baseColorFactor[size_t(c)] <= 1))
      throw inputError(where, "numbers in [0, 1]", std::to_string(pbr.baseColorFactor[size_t(c)]));
  return glm::make_vec3(pbr.baseColorFactor.data());
}

/// The number `key` of the material's extension `extension` (`otherwise` when absent), finite
/// and >= 0.
double extensionNumber(const tinygltf::Material& m, const std::string& extension, const std::string& key,
                       double otherwise, const std::string& where) {
  const auto found = m.extensions.find(extension);
  if (found == m.extensions.end() || !found->second.Has(key)) return otherwise;
  const tinygltf::Value& v = found->second.Get(key);
  const double x = v.IsNumber() ? v.GetNumberAsDouble() : -1;
  if (!(std::isfinite(x) && x >= 0))
    throw inputError(where + ": " + extension + "." + key, "a finite number >= 0",
                     v.IsNumber() ? std::to_string(x) : "not a number");
  return x;
}

/// The emitted radiance: emissiveFactor × KHR_materials_emissive_strength's emissiveStrength.
glm::dvec3 emittedRadiance(const tinygltf::Material& m, const std::string& where) {
  checkNumbers(m.emissiveFactor, 3, where + ": emissiveFactor");
  const glm::dvec3 factor = m.emissiveFactor.empty() ? glm::dvec3(0.0) : glm::make_vec3(m.emissiveFactor.data());
  if (!(factor.x >= 0 && factor.y >= 0 && factor.z >= 0))
    throw inputError(where + ": emissiveFactor", "numbers >= 0", "a negative one");
  return factor * extensionNumber(m, "KHR_materials_emissive_strength", "emissiveStrength", 1.0, where);
}

/// A base colour of 1 or more in some channel scaled so that its brightest is kMaxReflectance;
/// whether it was.
bool capWhite(glm::dvec3& kd) {
  const double brightest = std::max({kd.x, kd.y, kd.z});
  if (brightest < 1) return false;
  kd *= kMaxReflectance / brightest;
  return true;
}

/// The items in a list: a, b.
std::string joined(const std::set<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// A list of names in quotes: 'a', 'b'.
std::string quoted(const std::set<std::string>& names) {
  std::set<std::string> inQuotes;
  for (const auto& n : names) inQuotes.insert("'" + n + "'");
  return joined(inQuotes);
}

}  // namespace

/// Material `index` (-1: glTF's default, white), read on first use.
const GltfMaterial& GltfReader::material(int index) {
  auto found = materials_.find(index);
  if (found == materials_.end()) found = materials_.emplace(index, readMaterial(index)).first;
  return found->second;
}

/// Material `index` as a diffuse solver sees it: reflectance, emitted radiance, and what it
/// approximates.
GltfMaterial GltfReader::readMaterial(int index) const {
  GltfMaterial out;
  if (index < 0) {
    out.name = "default";
    out.white = capWhite(out.kd);
    return out;
  }
  const tinygltf::Material& m = item(model_.materials, index, "material", path_ + ": primitive material");
  out.name = nameOr(m.name, "material", index);
  const std::string where = path_ + ": material '" + out.name + "'";
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  out.kd = baseColourFactor(pbr, where + ": baseColorFactor");
  if (pbr.baseColorTexture.index >= 0) applyTexture(pbr.baseColorTexture.index, where + ": baseColorTexture", out);
  out.white = capWhite(out.kd);
  out.ke = emittedRadiance(m, where);
  out.metallic = pbr.metallicFactor > kMetallic;
  out.transmissive = extensionNumber(m, "KHR_materials_transmission", "transmissionFactor", 0.0, where) > 0;
  return out;
}

/// The encoded bytes of texture `texture`'s image (a file, a data URI or a buffer view; none
/// when its file could not be read), and its name for messages in `label`.
Bytes GltfReader::imageBytes(int texture, const std::string& where, std::string& label) const {
  const tinygltf::Texture& t = item(model_.textures, texture, "texture", where);
  const std::string at = where + ": texture " + std::to_string(texture) + ": source";
  const tinygltf::Image& image = item(model_.images, t.source, "PNG or JPEG image", at);
  label = image.uri.empty() ? "image " + std::to_string(t.source) : "'" + image.uri + "'";
  if (image.bufferView >= 0) return viewBytes(image.bufferView, path_ + ": " + label + ": bufferView");
  return {image.image.data(), image.image.size()};
}

/// The material's base colour times the linear mean colour of texture `texture`; when the image
/// cannot be read or decoded (a texture missing beside a downloaded file), the factor alone,
/// and why in `unreadTexture`. A texture the file names wrongly is an error.
void GltfReader::applyTexture(int texture, const std::string& where, GltfMaterial& m) const {
  std::string label;
  const Bytes bytes = imageBytes(texture, where, label);
  try {
    if (bytes.size == 0) throw inputError(label, "an image file beside the glTF file", "none that could be read");
    m.kd *= meanLinearColour(bytes.data, bytes.size, label);
    m.textured = true;
  } catch (const InputError& e) {
    m.unreadTexture = e.what();
  }
}

std::vector<std::string> GltfReader::warnings() const {
  std::set<std::string> textured, unread, white, approximated;
  size_t approximatedFaces = 0;
  for (const auto& [index, m] : materials_) {
    if (m.textured) textured.insert(m.name);
    if (!m.unreadTexture.empty()) unread.insert("'" + m.name + "' (" + m.unreadTexture + ")");
    if (m.white) white.insert(m.name);
    if (m.metallic || m.transmissive) approximatedFaces += facesOf_.at(index);
    if (m.metallic) approximated.insert(m.name + " (metallic)");
    if (m.transmissive) approximated.insert(m.name + " (transmissive)");
  }
  std::vector<std::string> out;
  if (!textured.empty())
    out.push_back("materials " + quoted(textured) + ": reflectance is the mean colour of the base-colour texture "
                  "times baseColorFactor (a radiosity solve keeps no texture detail)");
  if (!unread.empty())
    out.push_back("materials " + joined(unread) + ": base-colour texture not read, baseColorFactor alone is the "
                  "reflectance (put the image beside the glTF file)");
  if (!approximated.empty())
    out.push_back(std::to_string(approximatedFaces) + " faces of materials " + quoted(approximated) +
                  " treated as diffuse with their base colour (radiosity has no mirrors or glass; set metallicFactor "
                  "to 0 and leave out KHR_materials_transmission to say so in the file)");
  if (!white.empty())
    out.push_back("materials " + quoted(white) + ": base colour 1 (white) would reflect all light; taken as "
                  "reflectance 0.95 (hue kept); give a baseColorFactor below 1 to choose");
  if (leftOut_)
    out.push_back("left out " + std::to_string(leftOut_) + " primitives drawn as points or lines (not "
                  "surfaces) in meshes " + quoted(pointsAndLines_));
  return out;
}

}  // namespace rad::gltf
