// The scene file's surfaces: polygons (with holes) and mesh files (with transforms), checked
// to be meshable.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "mesh/base/error.h"
#include "mesh/scene/geometry.h"
#include "mesh/scene/readers/scene_sections.h"

namespace rad::scene_file {
namespace {

/// Coordinates beyond this magnitude (scene units) are refused: squared areas and the
/// mesher's predicates overflow double precision long before 1e77.
constexpr double kMaxCoordinate = 1e15;
/// A scene smaller than this (its bounding box's diagonal, scene units) is refused: squared
/// lengths would fall into denormals.
constexpr double kMinSceneSize = 1e-12;

/// Whether a polygon of this area and diameter (`size`) has an area to speak of.
bool hasArea(double area, double size) { return area > kMinRelativeArea * size * size; }

/// A ring of at least three points (`what` names them for messages).
Ring readRing(const Node& n, const std::string& what) {
  n.expectArray(3, what);
  Ring ring;
  for (size_t i = 0; i < n.size(); ++i) ring.push_back(n[i].vec3());
  return ring;
}

/// A scale: one number or three, none zero.
glm::dvec3 readScale(const Node& s) {
  const glm::dvec3 scale = s.value().is_array() ? s.vec3() : glm::dvec3(s.number());
  for (int i = 0; i < 3; ++i)
    if (scale[i] == 0) s.fail("a non-zero scale");
  return scale;
}

/// The transform of a mesh file: scale, then rotations about x, y, z, then translation.
glm::dmat4 readTransform(const Node& n) {
  n.expectObject({"scale", "rotate_deg", "translate"});
  glm::dvec3 scale(1.0), rotate(0.0), translate(0.0);
  if (n.has("scale")) scale = readScale(n["scale"]);
  if (n.has("rotate_deg")) rotate = n["rotate_deg"].vec3();
  if (n.has("translate")) translate = n["translate"].vec3();
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

/// A hole's vertex q (node v) lies in the plane of the polygon's outer ring, inside it.
void checkHoleVertex(const Ring& outer, const glm::dvec3& q, const PlaneFrame& frame, double size,
                     const Node& v) {
  const double off = glm::dot(q - frame.origin, frame.normal);
  if (std::abs(off) > kPlanarity * size)
    v.failWith("a hole vertex in the plane of its polygon", "a point " + std::to_string(off) + " away from it");
  if (!insideRing(frame, outer, q)) v.failWith("a hole vertex inside its polygon", "a point outside it");
}

/// Hole h of the polygon (node s) has an area and lies in the polygon's plane, inside it.
void validateHole(const Polygon& polygon, size_t h, const PlaneFrame& frame, double size,
                  const Node& s) {
  Node hole = s["holes"][h];
  const Ring& ring = polygon.holes[h];
  double holeArea = polygonArea(Polygon{ring, {}});
  if (!hasArea(holeArea, size))
    hole.failWith("a hole of non-zero area", "area " + std::to_string(holeArea));
  for (size_t k = 0; k < ring.size(); ++k) checkHoleVertex(polygon.outer, ring[k], frame, size, hole[k]);
}

/// The polygon (node s) has an area, and so has each hole, which lies inside it.
void validatePolygon(const Polygon& polygon, const Node& s) {
  double area = polygonArea(Polygon{polygon.outer, {}});
  double size = ringDiameter(polygon.outer);
  if (!hasArea(area, size))
    s["polygon"].failWith("a polygon of non-zero area", "area " + std::to_string(area));
  PlaneFrame frame = planeFrame(polygon.outer);
  for (size_t h = 0; h < polygon.holes.size(); ++h) validateHole(polygon, h, frame, size, s);
}

/// Every vertex of the surface (the faces of mesh file s) is finite.
void checkFinite(const Surface& surface, const Node& s) {
  for (const auto& p : surface.polygons)
    for (const auto& q : p.outer)
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        s["mesh"].failWith("finite vertex coordinates", "NaN or infinity");
}

/// Fewer than three corners, or no area to speak of.
bool isDegenerate(const Polygon& p) {
  double size = ringDiameter(p.outer);
  return p.outer.size() < 3 || !hasArea(polygonArea(p), size);
}

/// Mesh files often carry a few zero-area faces; they carry no light, so they are dropped,
/// and the loader says so. False when nothing is left: a downloaded scene's sliver object (the
/// whole of a mesh, collinear) is left out with a warning rather than refusing the scene.
bool dropDegenerateFaces(Surface& surface, const Node& s, std::vector<std::string>& warnings) {
  checkFinite(surface, s);
  size_t before = surface.polygons.size();
  surface.polygons.erase(
      std::remove_if(surface.polygons.begin(), surface.polygons.end(), isDegenerate),
      surface.polygons.end());
  if (surface.polygons.empty()) {
    warnings.push_back(s.where() + " (" + surface.name + "): every one of its " + std::to_string(before) +
                       " faces has no area (collinear corners); the surface is left out");
    return false;
  }
  if (surface.polygons.size() != before)
    warnings.push_back(s.where() + ": dropped " +
                       std::to_string(before - surface.polygons.size()) + " degenerate faces");
  return true;
}

/// The rings of "holes".
std::vector<Ring> readHoles(const Node& holes) {
  holes.expectArray(0, "holes");
  std::vector<Ring> rings;
  for (size_t h = 0; h < holes.size(); ++h) rings.push_back(readRing(holes[h], "vertices [x, y, z]"));
  return rings;
}

/// A polygon surface (node s): `surface` has its name, place and sides.
void readPolygonSurface(const Node& s, Surface surface, Scene& scene) {
  if (s.has("transform")) s["transform"].failWith("no transform on a polygon surface",
                                                   "a transform");
  if (!s.has("material")) s.failWith("a \"material\" key", "none");
  surface.material = materialIndex(s["material"], scene);
  Polygon polygon;
  polygon.outer = readRing(s["polygon"], "vertices [x, y, z]");
  if (s.has("holes")) polygon.holes = readHoles(s["holes"]);
  validatePolygon(polygon, s);
  surface.polygons.push_back(std::move(polygon));
  scene.surfaces.push_back(std::move(surface));
}

/// The groups as one group of all their faces (one material for the whole mesh).
std::vector<MeshFileGroup> merged(std::vector<MeshFileGroup> groups) {
  MeshFileGroup all;
  for (auto& g : groups)
    for (auto& f : g.faces) all.faces.push_back(std::move(f));
  return {std::move(all)};
}

/// The surface of one group of a mesh file (named by node s), its faces moved by
/// `transform`: of material `fixedMaterial`, or else of the group's MTL material.
void addGroupSurface(const Node& s, Surface surface, MeshFileGroup& group, int fixedMaterial,
                     const glm::dmat4& transform, Scene& scene) {
  surface.fromMeshFile = true;
  if (fixedMaterial >= 0) {
    surface.material = fixedMaterial;
  } else if (!group.material.empty()) {
    // Named after its object too where that says more (archives name objects after materials).
    const bool objectNamed = !group.object.empty() && group.object != group.material;
    surface.name += "/" + (objectNamed ? group.object + "/" : std::string()) + group.material;
    surface.material = addMtlMaterial(s, group, scene);
  } else {
    s.failWith("a \"material\" key or MTL materials on every face of " + s["mesh"].string(),
               "faces without a material");
  }
  for (auto& face : group.faces) {
    for (auto& p : face.outer) p = glm::dvec3(transform * glm::dvec4(p, 1.0));
    surface.polygons.push_back(std::move(face));
  }
  if (dropDegenerateFaces(surface, s, scene.warnings)) scene.surfaces.push_back(std::move(surface));
}

/// The key of a face as a set of corners with a facing: equal for a face repeated with the
/// same corners (in any order of start) facing the same way.
std::vector<double> faceKey(const Polygon& face) {
  std::vector<std::array<double, 3>> corners;
  for (const auto& p : face.outer) corners.push_back({p.x, p.y, p.z});
  std::sort(corners.begin(), corners.end());
  const glm::dvec3 n = newellNormal(face.outer);
  const int axis = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0 : std::abs(n.y) >= std::abs(n.z) ? 1 : 2;
  std::vector<double> key{n[axis] > 0 ? 1.0 : -1.0};
  for (const auto& c : corners) key.insert(key.end(), c.begin(), c.end());
  return key;
}

/// Drops the faces that repeat an earlier face of the file (same corners, same facing: two
/// coincident copies would fight in every hemicube and double the area). A copy in the same
/// material changes nothing and is noted; one in another material, whose colour is lost, is
/// warned about.
void dropRepeatedFaces(std::vector<MeshFileGroup>& groups, const Node& s, Scene& scene) {
  std::map<std::vector<double>, std::string> seen;  // face -> its material
  size_t same = 0, other = 0;
  std::set<std::string> sameIn, otherIn;
  std::vector<bool> emptied;
  for (auto& group : groups) {
    const std::string material = group.material.empty() ? std::string("no material") : group.material;
    auto repeated = [&](const Polygon& f) {
      if (isDegenerate(f)) return false;
      const auto [at, added] = seen.emplace(faceKey(f), material);
      if (added) return false;
      (at->second == material ? sameIn : otherIn).insert(material);
      ++(at->second == material ? same : other);
      return true;
    };
    const size_t before = group.faces.size();
    group.faces.erase(std::remove_if(group.faces.begin(), group.faces.end(), repeated), group.faces.end());
    emptied.push_back(before > 0 && group.faces.empty());
  }
  // A group all of whose faces repeat earlier ones goes with them.
  for (size_t g = groups.size(); g-- > 0;)
    if (emptied[g]) groups.erase(groups.begin() + long(g));
  auto listed = [](const std::set<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  };
  const std::string file = s.where() + " (" + s["mesh"].string() + "): ";
  if (same)
    scene.notes.push_back(file + "dropped " + std::to_string(same) + " exact repeat(s) of a face (in " +
                          listed(sameIn) + ")");
  if (other)
    scene.warnings.push_back(file + "dropped " + std::to_string(other) +
                             " face(s) repeating an earlier face of another material with the same corners and facing (in " +
                             listed(otherIn) + "; the first one's material is kept); remove the copies from the file to silence this");
}

/// A mesh file surface (node s), one surface per material group unless the surface names
/// a material.
void readMeshSurface(const Node& s, const Surface& surface, const std::string& baseDir,
                     Scene& scene) {
  if (s.has("holes")) s["holes"].failWith("no holes on a mesh surface", "holes");
  std::string file = s["mesh"].string();
  std::filesystem::path full = std::filesystem::path(baseDir) / file;
  glm::dmat4 transform = s.has("transform") ? readTransform(s["transform"]) : glm::dmat4(1.0);
  std::vector<std::string> notes;
  auto groups = readMeshFile(full.string(), s["mesh"].where(), notes);
  for (const std::string& note : notes) scene.warnings.push_back(s.where() + " (" + file + "): " + note);
  dropRepeatedFaces(groups, s, scene);
  int fixedMaterial = s.has("material") ? materialIndex(s["material"], scene) : -1;
  if (fixedMaterial >= 0) groups = merged(std::move(groups));
  for (auto& group : groups) addGroupSurface(s, surface, group, fixedMaterial, transform, scene);
}

/// Surface i (node s) with its name (unique among `names`), place and sides.
Surface namedSurface(const Node& s, size_t i, std::set<std::string>& names) {
  Surface surface;
  // Unnamed: a mesh file's surfaces take its name (CornellBox-Original/floor), others a number.
  const std::string fallback = s.has("mesh") ? std::filesystem::path(s["mesh"].string()).stem().string()
                                             : "surface" + std::to_string(i);
  surface.name = s.has("name") ? s["name"].string() : fallback;
  if (!names.insert(surface.name).second) s["name"].fail("a name no other surface has");
  surface.twoSided = s.has("two_sided") && s["two_sided"].boolean();
  surface.where = s.where();
  return surface;
}

/// A coordinate beyond ±kMaxCoordinate, said as where it is.
[[noreturn]] void tooFar(const Surface& s, const glm::dvec3& q) {
  char found[96];
  std::snprintf(found, sizeof found, "the point (%g, %g, %g)", q.x, q.y, q.z);
  throw inputError(s.where + " (" + s.name + ")",
                   "coordinates within ±1e15 scene units (choose larger units or scale the surface down)",
                   found);
}

}  // namespace

void readSurfaces(const Node& n, const std::string& baseDir, Scene& scene) {
  n.expectArray(1, "surfaces");
  std::set<std::string> names;
  for (size_t i = 0; i < n.size(); ++i) {
    Node s = n[i];
    s.expectObject({"name", "material", "polygon", "holes", "two_sided", "mesh", "transform"});
    Surface surface = namedSurface(s, i, names);
    if (s.has("polygon") == s.has("mesh"))
      s.failWith("exactly one of \"polygon\" and \"mesh\"", s.has("polygon") ? "both" : "neither");
    if (s.has("polygon"))
      readPolygonSurface(s, std::move(surface), scene);
    else
      readMeshSurface(s, surface, baseDir, scene);
  }
}

void checkScale(const Scene& scene) {
  for (const auto& s : scene.surfaces)
    for (const auto& p : s.polygons)
      for (const auto& q : p.outer)
        if (std::abs(q.x) > kMaxCoordinate || std::abs(q.y) > kMaxCoordinate || std::abs(q.z) > kMaxCoordinate)
          tooFar(s, q);
  if (!scene.surfaces.empty() && !(scene.diagonal() >= kMinSceneSize))
    throw inputError(scene.path + ": surfaces", "a scene at least 1e-12 scene units across (choose smaller units)",
                     "one " + std::to_string(scene.diagonal()) + " across");
}

}  // namespace rad::scene_file
