// The scene file's materials, and the materials of mesh files' MTL groups.
#include <cmath>

#include "mesh/scene/material_presets.h"
#include "mesh/scene/readers/scene_sections.h"

namespace rad::scene_file {
namespace {

/// The OpenGL material table entry the "preset" key names: the local model's colours, its
/// diffuse colour as reflectance.
void applyPreset(const Node& p, Material& m) {
  const MaterialPreset* preset = findMaterialPreset(p.string());
  if (!preset) p.fail("one of " + join(materialPresetNames()));
  m.preset = preset->name;
  m.ambient = preset->ambient;
  m.diffuse = preset->diffuse;
  m.specular = preset->specular;
  m.shininess = preset->shininess;
  m.reflectance = glm::dvec3(preset->diffuse);
}

/// The diffuse colour (node d), which is the reflectance too.
void readDiffuse(const Node& d, Material& m) {
  m.diffuse = d.color();
  m.reflectance = glm::dvec3(m.diffuse);
}

/// The local model's keys given directly; a diffuse colour is the reflectance too.
void readLocalModel(const Node& n, Material& m) {
  if (n.has("diffuse")) readDiffuse(n["diffuse"], m);
  if (n.has("ambient")) m.ambient = n["ambient"].color();
  if (n.has("specular")) m.specular = n["specular"].color();
  if (n.has("shininess")) m.shininess = n["shininess"].number(0, 128, "[0, 128]");
}

/// A reflectance taken from a diffuse colour is in [0, 1) too.
void checkUsableDiffuse(const Node& n, const glm::dvec3& reflectance) {
  for (int i = 0; i < 3; ++i)
    if (!(reflectance[i] >= 0 && reflectance[i] < 1))
      n.failWith("a diffuse colour usable as reflectance, in [0, 1)", std::to_string(reflectance[i]));
}

/// The reflectance: given, or from the preset or diffuse colour, in [0, 1) either way.
void readReflectance(const Node& n, Material& m) {
  if (n.has("reflectance")) {
    m.reflectance = reflectanceRgb(n["reflectance"]);
  } else if (!n.has("preset") && !n.has("diffuse")) {
    n.failWith("\"reflectance\", \"diffuse\" or \"preset\"", "none of them");
  }
  checkUsableDiffuse(n, m.reflectance);
}

/// The local model's diffuse and ambient colours not given: the reflectance.
void defaultLocalColours(const Node& n, Material& m) {
  if (n.has("preset")) return;
  // Without a preset the local model sees the radiosity colour, as a user would expect.
  if (!n.has("diffuse")) m.diffuse = glm::dvec4(m.reflectance, 1.0);
  if (!n.has("ambient")) m.ambient = glm::dvec4(m.reflectance, 1.0);
}

/// One named material: preset, local-model colours, reflectance and emission.
Material readMaterial(const Node& n, const std::string& name) {
  n.expectObject({"reflectance", "emission", "preset", "ambient", "diffuse", "specular",
                  "shininess"});
  Material m;
  m.name = name;
  if (n.has("preset")) applyPreset(n["preset"], m);
  readLocalModel(n, m);
  readReflectance(n, m);
  defaultLocalColours(n, m);
  if (n.has("emission")) m.emission = nonNegativeRgb(n["emission"], "a finite emission >= 0");
  return m;
}

/// The MTL group's Kd (black if none), in [0, 1).
glm::dvec3 mtlReflectance(const Node& s, const MeshFileGroup& group) {
  const glm::dvec3 kd = group.kd.value_or(glm::dvec3(0.0));
  for (int i = 0; i < 3; ++i)
    if (!(kd[i] >= 0 && kd[i] < 1))
      s["mesh"].failWith("MTL Kd of \"" + group.material + "\" in [0, 1)", std::to_string(kd[i]));
  return kd;
}

/// The exitance of the MTL group's Ke (none if none), finite and >= 0. MTL Ke is radiance as
/// renderers use it; a Lambertian emitter's exitance is pi times it.
glm::dvec3 mtlExitance(const Node& s, const MeshFileGroup& group) {
  const glm::dvec3 exitance = M_PI * group.ke.value_or(glm::dvec3(0.0));
  for (int i = 0; i < 3; ++i)
    if (!(exitance[i] >= 0 && std::isfinite(exitance[i])))
      s["mesh"].failWith("MTL Ke of \"" + group.material + "\" finite and >= 0",
                         std::to_string(group.ke.value()[i]));
  return exitance;
}

/// The materials' names, in order.
std::vector<std::string> materialNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const auto& m : scene.materials) names.push_back(m.name);
  return names;
}

/// An MTL material's name in the scene: "<surface>/<MTL name>", or the MTL name alone for a
/// surface without a name.
std::string mtlMaterialName(const Node& s, const MeshFileGroup& group) {
  return s.has("name") ? s["name"].string() + "/" + group.material : group.material;
}

}  // namespace

void readMaterials(const Node& n, Scene& scene) {
  if (!n.value().is_object()) n.fail("an object of named materials");
  for (const auto& item : n.value().items())
    scene.materials.push_back(readMaterial(n[item.key().c_str()], item.key()));
}

int materialIndex(const Node& n, const Scene& scene) {
  std::string name = n.string();
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == name) return int(i);
  n.fail("a material defined in \"materials\" (" + join(materialNames(scene)) + ")");
}

int addMtlMaterial(const Node& s, const MeshFileGroup& group, Scene& scene) {
  Material m;
  m.name = mtlMaterialName(s, group);
  m.reflectance = mtlReflectance(s, group);
  m.emission = mtlExitance(s, group);
  m.diffuse = m.ambient = glm::dvec4(m.reflectance, 1.0);
  scene.materials.push_back(m);
  return int(scene.materials.size()) - 1;
}

}  // namespace rad::scene_file
