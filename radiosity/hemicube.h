#pragma once
// Hemicube form factors (Cohen & Greenberg 1985) on the raster core: from a point with a
// normal to every element it sees, as item buffers on five faces.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace raster {
struct Target;
}

namespace rad {

class PatchMesh;

/// The triangles a hemicube draws: element e has corners indices[3e..3e+2] (counter-clockwise
/// seen from its lit side) and unit normal normals[e].
struct HemicubeGeometry {
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> indices;
  std::vector<glm::dvec3> normals;

  size_t elementCount() const { return normals.size(); }
  /// The elements of a patch mesh (element e = face e).
  static HemicubeGeometry fromMesh(const PatchMesh& mesh);
  /// Adds one triangle as a new element; returns its index.
  int addTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
};

/// Sparse form factors from one point: factors[k] to elements[k] (ascending), plus what the
/// hemicube saw of nothing (sky) and of back faces (which occlude but receive nothing).
/// Σ factors + sky + backFaces = 1 to round-off.
struct FormFactors {
  std::vector<int> elements;
  std::vector<double> factors;
  double sky = 0, backFaces = 0;

  double sum() const;
};

/// Delta form factors of a hemicube of resolution R (half-width 1 at height 1): the exact
/// integral over each pixel (the point-to-polygon factor of the pixel), normalised so that
/// the five faces sum to 1. top: R×R; side: R×R/2, row 0 on the base plane.
struct DeltaFormFactors {
  int resolution = 0;
  std::vector<double> top, side;
  double exactSum = 0;  ///< the sum of the exact pixel integrals before normalising (1 − ε)

  static const DeltaFormFactors& forResolution(int resolution);
};

/// A hemicube over fixed geometry, reused from point to point (not thread-safe: one per thread).
class Hemicube {
 public:
  /// resolution: pixels across the top face (even, ≥ 2). sceneSize: the scene diagonal; the
  /// near plane and the eye offset are fixed fractions of it.
  Hemicube(const HemicubeGeometry& geometry, int resolution, double sceneSize);
  ~Hemicube();
  Hemicube(const Hemicube&) = delete;
  Hemicube& operator=(const Hemicube&) = delete;

  /// Form factors from point x with unit normal n. `rotation` in [0, 1) turns the cube about n
  /// by 2π·rotation. Elements listed in `excluded` (the shooter's own) receive nothing.
  void compute(const glm::dvec3& x, const glm::dvec3& n, double rotation, FormFactors& out,
               const std::vector<int>& excluded = {});

  int resolution() const { return resolution_; }

  /// The steps of compute(), for drawing the identical item buffers with another rasteriser
  /// (benchmarks): prepare() places the cube and sets the item ids; faceClip() gives face f's
  /// clip-space vertices (0 top R×R; 1–4 sides R×R/2, upper half only; z = near, reversed
  /// [0, 1] depth, GREATER).
  void prepare(const glm::dvec3& x, const glm::dvec3& n, double rotation,
               const std::vector<int>& excluded = {});
  void faceClip(int face, std::vector<glm::vec4>& clip) const;
  /// The triangles prepare() found above the base plane (the others show on no face):
  /// 3 vertex indices each, and their item ids (the element, or an occluder id).
  const std::vector<uint32_t>& drawIndices() const { return drawIndices_; }
  const std::vector<uint32_t>& drawIds() const { return drawIds_; }

  /// Near plane and eye offset, as fractions of the scene size.
  static constexpr double kNearPlane = 1e-7;
  static constexpr double kEyeOffset = 1e-6;

 private:
  /// The triangles reaching above the base plane, the only ones any face can show:
  /// drawIndices_ and drawIds_ from ids_ and local_.
  void keepAboveBase();
  /// Draws the five faces' item buffers.
  void renderFaces();
  /// Sums each face's delta form factors per item into `out` (elements ascending).
  void accumulate(FormFactors& out);

  const HemicubeGeometry& geometry_;
  int resolution_;
  double near_, eyeOffset_;
  const DeltaFormFactors& delta_;
  std::array<std::unique_ptr<raster::Target>, 5> faces_;  // top, +u, -u, +v, -v
  std::vector<uint32_t> ids_;
  std::vector<uint32_t> drawIndices_, drawIds_;  // the triangles above the base plane
  std::vector<std::array<float, 3>> local_;
  std::vector<glm::vec4> clip_;
  std::vector<double> accumulator_;  // per element, then sky and back faces
  std::vector<uint64_t> seen_;       // bit set of the accumulator slots written
};

/// A deterministic rotation in [0, 1) for (seed, shooter, sample point): every run, and the
/// progressive and reference solvers alike, see the same hemicubes.
double hemicubeRotation(uint64_t seed, uint64_t shooter, uint64_t sample);

}  // namespace rad
