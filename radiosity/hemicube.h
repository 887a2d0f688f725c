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

  /// What one face draws: the clip-space vertices of the triangles that may show on it (z =
  /// near, reversed [0, 1] depth, GREATER), 3 indices into them per triangle, and each
  /// triangle's item id (the element, or an occluder id). Face 0 is the top (R×R), 1–4 the
  /// sides (R×R/2, upper half only).
  struct FaceDraw {
    std::vector<glm::vec4> clip;
    std::vector<uint32_t> indices, ids;
  };

  /// The steps of compute(), for drawing the identical item buffers with another rasteriser
  /// (benchmarks): prepare() places the cube, sets the item ids and sorts the triangles to
  /// the faces they may show on; faceDraw(f) is face f's share.
  void prepare(const glm::dvec3& x, const glm::dvec3& n, double rotation,
               const std::vector<int>& excluded = {});
  const FaceDraw& faceDraw(int face) const { return draws_[size_t(face)]; }

  /// Near plane and eye offset, as fractions of the scene size.
  static constexpr double kNearPlane = 1e-7;
  static constexpr double kEyeOffset = 1e-6;

 private:
  /// Each face's FaceDraw from ids_ and local_: the triangles reaching above the base plane
  /// and not wholly outside one of the face's frustum planes, in element order.
  void sortToFaces();
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
  std::vector<std::array<float, 3>> local_;  // per vertex, along (u, v, n) from the eye
  std::vector<uint32_t> outside_;            // per vertex, the frustum planes it is outside of
  std::vector<uint8_t> faces_of_;            // per element, the faces it may show on (bits)
  std::vector<uint8_t> needed_;              // per vertex, the faces that draw it (bits)
  std::vector<uint32_t> slot_;               // per face and vertex: its index in the face's clip
  std::array<FaceDraw, 5> draws_;
  std::vector<double> accumulator_;  // per element, then sky and back faces
  std::vector<uint64_t> seen_;       // bit set of the accumulator slots written
};

/// A deterministic rotation in [0, 1) for (seed, shooter, sample point): every run, and the
/// progressive and reference solvers alike, see the same hemicubes.
double hemicubeRotation(uint64_t seed, uint64_t shooter, uint64_t sample);

}  // namespace rad
