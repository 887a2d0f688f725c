// Local-illumination mode: the scene meshed with its own settings and lit by OpenGL's
// fixed-function model through OSMesa (its lights, light model, materials and fog).
#include <algorithm>
#include <limits>

#include "display/viewer/viewer_internal.h"
#include "mesh/base/error.h"
#include "mesh/mesh_settings.h"
#include "mesh/scene/readers/scene_loader.h"

namespace rad::viewer {
namespace {

/// A ResultFile carrying only what camera fitting uses: the bounds and the scene's camera.
ResultFile boundsOnly(const LocalScene& local) {
  ResultFile m;
  m.path = local.scene.path;
  m.boundsMin = local.boundsMin;
  m.boundsMax = local.boundsMax;
  m.camera = local.scene.camera;
  return m;
}

/// A material's emission normalised to full brightness, E / max component (lamps show their
/// hue at full brightness; radiosity units have no fixed display scale); black without one.
glm::vec4 fullBrightnessEmission(const Material& m) {
  const double peak = internal::peakEmission(m);
  return peak > 0 ? glm::vec4(glm::vec3(m.emission / peak), 1.0f) : glm::vec4(0, 0, 0, 1);
}

/// The batch of a material: its colours, shininess, and its emission normalised to full
/// brightness.
detail::LocalBatch localBatch(const Material& m) {
  detail::LocalBatch b = internal::specularBatch(m);
  b.ambient = glm::vec4(m.ambient);
  b.diffuse = glm::vec4(m.diffuse);
  b.emission = fullBrightnessEmission(m);
  return b;
}

/// Grows the local scene's bounds to hold point p.
void includePoint(LocalScene& local, const glm::dvec3& p) {
  local.boundsMin = glm::min(local.boundsMin, p);
  local.boundsMax = glm::max(local.boundsMax, p);
}

/// Sets the local scene's bounds to the box of its meshed vertices.
void fitBounds(LocalScene& local) {
  local.boundsMin = glm::dvec3(std::numeric_limits<double>::infinity());
  local.boundsMax = -local.boundsMin;
  for (auto v : local.mesh.mesh.vertices()) includePoint(local, PatchMesh::toGlm(local.mesh.mesh.point(v)));
}

/// The local model's limits on the options: OSMesa, no --exposure or --hdr.
void checkLocalOptions(const RenderOptions& o) {
  if (o.backend != Backend::OsMesa)
    throw inputError("--mode local", "--backend osmesa (the local model is OpenGL-only)", "--backend software");
  if (o.exposure) throw inputError("--mode local", "no --exposure (lighting sets the brightness)", "--exposure");
  if (o.radiance) throw inputError("--mode local", "no --hdr (radiance is radiosity-only)", "--hdr");
}

/// The scene meshed with its own settings, and the bounds of the mesh.
LocalScene meshedScene(Scene scene) {
  LocalScene local;
  local.mesh = buildPatchMesh(scene, resolveMeshSettings(scene, {}));
  local.scene = std::move(scene);
  fitBounds(local);
  return local;
}

}  // namespace

LocalScene prepareLocalScene(Scene scene) {
  if (scene.lights.empty())
    throw inputError(scene.path, "a scene with lights for --mode local", "none");
  LocalScene local = meshedScene(std::move(scene));
  if (local.mesh.elementCount() == 0) throw inputError(local.scene.path, "a scene with surfaces", "none");
  return local;
}

namespace internal {

double peakEmission(const Material& m) { return std::max({m.emission.x, m.emission.y, m.emission.z}); }

}  // namespace internal

LocalScene loadLocalScene(const std::string& path) { return prepareLocalScene(loadScene(path)); }

Camera effectiveCamera(const LocalScene& local, const RenderOptions& options) {
  return effectiveCamera(boundsOnly(local), options);
}

namespace detail {
namespace {

/// Appends element e's three corners: positions and normals (the face normal when flat).
void appendElement(LocalDrawList& list, const PatchMesh& pm, size_t e, Shading shade) {
  const glm::vec3 faceNormal(pm.normal(int(e)));
  for (auto v : pm.mesh.fv_range(TriMesh::FaceHandle(int(e)))) {
    list.positions.push_back(glm::vec3(PatchMesh::toGlm(pm.mesh.point(v))));
    list.normals.push_back(shade == Shading::Flat ? faceNormal : glm::vec3(PatchMesh::toGlm(pm.mesh.normal(v))));
  }
}

/// The elements grouped by their scene surface, in element order.
std::vector<std::vector<size_t>> elementsBySurface(const LocalScene& local) {
  const PatchMesh& pm = local.mesh;
  return internal::groupBySurface(local.scene.surfaces.size(), size_t(pm.elementCount()),
                                  [&](size_t e) { return pm.surface(int(e)); });
}

/// Room for n vertices in each of the list's arrays.
void reserveVertices(LocalDrawList& list, size_t n) {
  list.positions.reserve(n);
  list.normals.reserve(n);
}

}  // namespace

LocalDrawList buildLocalDrawList(const LocalScene& local, Shading shade) {
  // Elements grouped by surface, one material batch per surface.
  const auto bySurface = elementsBySurface(local);
  LocalDrawList list;
  reserveVertices(list, size_t(local.mesh.elementCount()) * 3);
  internal::appendBatches(list, local.scene, bySurface, localBatch,
                          [&](size_t e) { appendElement(list, local.mesh, e, shade); });
  return list;
}

}  // namespace detail

Image renderLocal(const LocalScene& local, const RenderOptions& o) {
  internal::checkSize(o);
  checkLocalOptions(o);
  const ResultFile bounds = boundsOnly(local);
  const internal::FrameView v = internal::frameView(bounds, effectiveCamera(bounds, o), o);
  return internal::litPicture(detail::buildLocalDrawList(local, o.shade), local.scene, v, o,
                              detail::renderOsMesaLocal);
}

}  // namespace rad::viewer
