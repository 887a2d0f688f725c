#pragma once
// The classic OpenGL material table (ambient, diffuse, specular, shininess on 0-128).
#include <string>
#include <vector>

#include <glm/vec4.hpp>

namespace rad {

struct MaterialPreset {
  const char* name;
  glm::dvec4 ambient, diffuse, specular;
  double shininess;
};

/// The preset of that name, or nullptr.
const MaterialPreset* findMaterialPreset(const std::string& name);

/// Every preset name, in table order.
std::vector<std::string> materialPresetNames();

}  // namespace rad
