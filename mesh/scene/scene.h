#pragma once
// The scene as the user describes it (DESIGN.md, "Scene file"): materials, surfaces,
// camera, the display-only local lighting model, and solver defaults.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace rad {

/// A diffuse material. Radiosity uses reflectance and emission; the viewer's local
/// (OpenGL fixed-function) model uses ambient, diffuse, specular and shininess.
struct Material {
  std::string name;
  glm::dvec3 reflectance{0.0};  ///< rho per channel, in [0, 1)
  glm::dvec3 emission{0.0};     ///< exitance, power per unit area (radiosity units), >= 0
  glm::dvec4 ambient{0.0, 0.0, 0.0, 1.0};
  glm::dvec4 diffuse{0.0, 0.0, 0.0, 1.0};
  glm::dvec4 specular{0.0, 0.0, 0.0, 1.0};
  double shininess = 0.0;  ///< OpenGL's 0-128 scale
  std::string preset;      ///< the OpenGL material table entry it came from, if any

  bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
};

/// A closed loop of points; the outer ring of a polygon is counter-clockwise seen from
/// its lit side.
using Ring = std::vector<glm::dvec3>;

/// A polygon, possibly non-planar, with optional holes (which may wind either way).
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

/// A surface: one material, one or more polygons (a JSON polygon, or the faces of a mesh
/// file after its transform).
struct Surface {
  std::string name;
  int material = -1;  ///< index into Scene::materials
  bool twoSided = false;
  bool fromMeshFile = false;  ///< faces of a mesh file (kept as they are when small enough)
  std::vector<Polygon> polygons;
  std::string where;  ///< "scene.json: surfaces[3]" for messages about this surface
};

/// A pinhole camera, as gluLookAt + gluPerspective take it.
struct Camera {
  glm::dvec3 eye{0.0, 0.0, 1.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovYDeg = 45.0;
};

/// glLightModel state.
struct LightModel {
  glm::dvec4 ambient{0.2, 0.2, 0.2, 1.0};
  bool localViewer = false;
  bool twoSided = false;
};

/// One OpenGL fixed-function light (display only; radiosity light comes from emitters).
struct Light {
  enum class Type { Directional, Point, Spot };
  Type type = Type::Point;
  glm::dvec3 position{0.0};   ///< point and spot
  glm::dvec3 direction{0.0};  ///< directional: towards the light; spot: the spot axis
  glm::dvec4 ambient{0.0, 0.0, 0.0, 1.0};
  glm::dvec4 diffuse{1.0, 1.0, 1.0, 1.0};
  glm::dvec4 specular{1.0, 1.0, 1.0, 1.0};
  glm::dvec3 attenuation{1.0, 0.0, 0.0};  ///< kc, kl, kq
  double cutoffDeg = 180.0;               ///< spot: in [0, 90]
  double exponent = 0.0;                  ///< spot: in [0, 128]
};

/// glFog state; absent from a scene means no fog.
struct Fog {
  enum class Mode { Linear, Exp, Exp2 };
  Mode mode = Mode::Exp;
  glm::dvec4 color{0.0, 0.0, 0.0, 0.0};
  double start = 0.0, end = 1.0, density = 1.0;
};

/// What a solve spends for accuracy, as the defaults of the settings it moves (mesh/mesh_settings.h,
/// radiosity/settings.h): a quick look, the default balance, or the most accurate answer.
enum class Quality { Draft, Default, Final };

/// The scene's `solver` block: defaults that command-line flags override. Unset values
/// take defaults relative to the scene size (see resolveSettings).
struct SolverBlock {
  std::optional<Quality> quality;
  std::optional<double> maxElementEdge, maxPatchEdge, tolerance, timeLimit, overshoot, exposure;
  std::optional<double> factorCacheMb, proximitySamples, gatherAccuracy;
  std::optional<int> hemicubeResolution, emitterHemicubeResolution, emitterSamples, shooterSamples;
  std::optional<int> gatherResolution;
  std::optional<long> maxShots;
  std::optional<unsigned> seed;
  std::optional<bool> cutContacts, fixFacing, adaptive, vertexDirect, finalGather, clusterShooters, resolutionFollowsPower;
  std::optional<double> minElementEdge, contrast;
  std::optional<long> maxElements;
};

struct Scene {
  std::string path;   ///< the scene file as given
  std::string units;  ///< informative only ("mm", "m", ...)
  std::vector<Material> materials;
  std::vector<Surface> surfaces;  ///< in file order, mesh material groups expanded in place
  std::optional<Camera> camera;
  LightModel lightModel;
  std::vector<Light> lights;
  std::optional<Fog> fog;
  SolverBlock solver;
  std::vector<std::string> warnings;  ///< repairs the loader made ("dropped 3 degenerate faces")
  /// What the loader did that changes no light (a face repeated exactly, material and all,
  /// kept once): `radiosity info` lists them, `solve` does not warn.
  std::vector<std::string> notes;

  bool hasEmitter() const;
  /// The diagonal of the axis-aligned bounding box of every surface.
  double diagonal() const;
};

}  // namespace rad
