// Hybrid mode: the result's radiosity as the diffuse part plus the specular highlights of the
// scene's lights and materials, through OSMesa.
#include "display/viewer/viewer_internal.h"
#include "mesh/base/error.h"

namespace rad::viewer {
namespace {

/// The unit normal of face f of the mesh ((0, 0, 1) for a degenerate face).
glm::vec3 faceNormal(const ResultFile& mesh, size_t f) {
  const auto& face = mesh.faces[f];
  const glm::vec3 p0 = mesh.positions[size_t(face[0])], p1 = mesh.positions[size_t(face[1])],
                  p2 = mesh.positions[size_t(face[2])];
  const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(n);
  return len > 0 ? n / len : glm::vec3(0, 0, 1);
}

/// What hybrid mode refuses: the software backend, the radiance image, a result without
/// surfaces of the scene, and a scene without lights.
void checkHybridInputs(const ResultFile& mesh, const Scene& scene, const RenderOptions& o) {
  if (o.backend != Backend::OsMesa)
    throw inputError("--mode hybrid", "--backend osmesa (the hybrid model is OpenGL-only)", "--backend software");
  if (o.radiance) throw inputError("--mode hybrid", "no --hdr (radiance is radiosity-only)", "--hdr");
  internal::checkFaceSurfaces(mesh, scene, "--mode hybrid");
  if (scene.lights.empty()) throw inputError(scene.path, "a scene with lights for --mode hybrid", "none");
}

/// Throws unless face f's surface is one of the scene's.
void checkSurfaceIndex(const ResultFile& mesh, const Scene& scene, size_t f) {
  if (mesh.faceSurface[f] < 0 || size_t(mesh.faceSurface[f]) >= scene.surfaces.size())
    throw inputError(mesh.path + ": face " + std::to_string(f) + ": surface",
                     "a surface index of " + scene.path + " (0.." +
                         std::to_string(int(scene.surfaces.size()) - 1) + ")",
                     std::to_string(mesh.faceSurface[f]));
}

}  // namespace

namespace internal {

detail::LocalBatch specularBatch(const Material& m) {
  detail::LocalBatch b;
  b.specular = glm::vec4(m.specular);
  b.shininess = float(m.shininess);
  return b;
}

void checkFaceSurfaces(const ResultFile& mesh, const Scene& scene, const std::string& where) {
  if (mesh.faceSurface.size() != mesh.faces.size())
    throw inputError(mesh.path, "a result with the face property `surface` (for " + where + ")", "none");
  for (size_t f = 0; f < mesh.faceSurface.size(); ++f) checkSurfaceIndex(mesh, scene, f);
}

}  // namespace internal

namespace detail {
namespace {

/// Appends face f's three corners from the radiosity draw list `base`: position, colour and
/// normal (the vertex normal when vertexNormals, else the face's).
void appendFace(HybridDrawList& list, const DrawList& base, const ResultFile& mesh, size_t f,
                bool vertexNormals) {
  const glm::vec3 normal = faceNormal(mesh, f);
  for (size_t corner = 0; corner < 3; ++corner) {
    const size_t k = 3 * f + corner;
    list.positions.push_back(base.positions[k]);
    list.colours.push_back(base.display[k]);
    list.normals.push_back(vertexNormals ? mesh.vertexNormal[size_t(mesh.faces[f][corner])] : normal);
  }
}

/// Room for n vertices in each of the list's arrays.
void reserveVertices(HybridDrawList& list, size_t n) {
  list.positions.reserve(n);
  list.normals.reserve(n);
  list.colours.reserve(n);
}

/// Whether the corners take the file's vertex normals: smooth shading and a file that has them.
bool usesVertexNormals(const ResultFile& mesh, Shading shade) {
  return shade == Shading::Smooth && !mesh.vertexNormal.empty();
}

/// The faces grouped by their scene surface, in face order.
std::vector<std::vector<size_t>> facesBySurface(const ResultFile& mesh, const Scene& scene) {
  return internal::groupBySurface(scene.surfaces.size(), mesh.faces.size(),
                                  [&](size_t f) { return mesh.faceSurface[f]; });
}

}  // namespace

HybridDrawList buildHybridDrawList(const ResultFile& mesh, const Scene& scene, Shading shade,
                                   double exposure, bool storedColours) {
  const DrawList base = buildDrawList(mesh, shade, exposure, storedColours);
  const auto bySurface = facesBySurface(mesh, scene);
  HybridDrawList list;
  reserveVertices(list, base.positions.size());
  const bool vertexNormals = usesVertexNormals(mesh, shade);
  internal::appendBatches(list, scene, bySurface, internal::specularBatch,
                          [&](size_t f) { appendFace(list, base, mesh, f, vertexNormals); });
  return list;
}

}  // namespace detail

Image renderHybrid(const ResultFile& mesh, const Scene& scene, const RenderOptions& o) {
  internal::checkSize(o);
  checkHybridInputs(mesh, scene, o);
  const internal::FrameView v = internal::frameView(mesh, effectiveCamera(mesh, o), o);
  const detail::HybridDrawList list = detail::buildHybridDrawList(
      mesh, scene, o.shade, effectiveExposure(mesh, o), internal::showsStoredColours(mesh, o));
  return internal::litPicture(list, scene, v, o, detail::renderOsMesaHybrid);
}

}  // namespace rad::viewer
