#pragma once
// Hemicube form factors (Cohen & Greenberg 1985) on the raster core: from a point with a
// normal to every element it sees, as item buffers on five faces.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/formfactors/hemicube_depth_pyramid.h"
#include "radiosity/formfactors/hemicube_frame.h"
#include "radiosity/formfactors/hemicube_index_set.h"

namespace raster {
struct Target;
}

namespace rad {

class FlatRegions;
class PatchMesh;

/// The triangles a hemicube draws: element e has corners indices[3e..3e+2] (counter-clockwise
/// seen from its lit side) and unit normal normals[e].
struct HemicubeGeometry {
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> indices;
  std::vector<glm::dvec3> normals;
  /// Per element, or empty for none: the element has a twin side in the same place (a two-sided
  /// surface's), so seen from behind it is not drawn at all and the twin, facing the hemicube
  /// from there, shows instead. Drawn, the two sides would tie in depth and the back (which
  /// receives nothing) would win about half the pixels: light into a two-sided wall was lost.
  std::vector<uint8_t> twoSided;

  size_t elementCount() const { return normals.size(); }
  /// The elements of a patch mesh (element e = face e).
  static HemicubeGeometry fromMesh(const PatchMesh& mesh);
  /// Sets `twoSided` from the surface each element lies on (`surfaceOf[e]`), if any of the mesh's
  /// surfaces is two-sided.
  void markTwoSided(const PatchMesh& mesh, const std::vector<int>& surfaceOf);
  /// Adds one triangle as a new element; returns its index.
  int addTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
  /// The bounding-volume hierarchy over the elements, built by the first call (thread-safe)
  /// and shared by every hemicube; rebuilt if elements or vertices were added since. Moving
  /// existing vertices afterwards is not seen: finish the geometry before drawing it.
  std::shared_ptr<const ElementHierarchy> hierarchy() const;

 private:
  friend class Hemicube;
  mutable std::shared_ptr<const ElementHierarchy> hierarchy_;
  mutable int cullingPays_ = -1;  // Hemicube::cullingPays once measured (0 or 1)
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
  /// One over the length of each pixel centre's direction at unit distance along its face's
  /// axis: a pixel's 1/distance is this times 1/(distance along the axis).
  std::vector<float> topPerLength, sidePerLength;
  double exactSum = 0;  ///< the sum of the exact pixel integrals before normalising (1 − ε)

  static const DeltaFormFactors& forResolution(int resolution);
};

/// Which elements a hemicube sorts to its faces. None: every one, each vertex placed once (the
/// reference, and the fastest where a cube sees most of the scene, as in an open box).
/// Hidden: those of the element hierarchy's subtrees that are neither below the cube's base
/// plane nor hidden behind what it has already drawn. Auto: Hidden where that pays for the
/// geometry (see Hemicube::kCullingPaysBelow), else None. Both give the same item buffers
/// (see compute() for the exceptions).
enum class HemicubeCulling { Auto, None, Hidden };

/// What the last prepare() or compute() did: elements skipped with their subtree (below the
/// base plane, hidden), subtrees tested for being hidden, triangles drawn (summed over the
/// faces) and the batches they were drawn in; drawing flat regions, the pixels resolved to
/// their elements.
struct HemicubeCounts {
  size_t belowBase = 0, hidden = 0, tested = 0, drawn = 0, batches = 0, located = 0;
};

/// A hemicube over fixed geometry, reused from point to point (not thread-safe: one per thread).
class Hemicube {
 public:
  /// resolution: pixels across the top face (even, ≥ 2). sceneSize: the scene diagonal; the
  /// near plane and the eye offset are fixed fractions of it.
  Hemicube(const HemicubeGeometry& geometry, int resolution, double sceneSize);
  /// A hemicube that draws the regions' triangles and gives the factors of their elements,
  /// each pixel's found under its centre (see FlatRegions). `regions` must outlive it.
  Hemicube(const FlatRegions& regions, int resolution, double sceneSize);
  ~Hemicube();
  Hemicube(const Hemicube&) = delete;
  Hemicube& operator=(const Hemicube&) = delete;

  /// Form factors from point x with unit normal n. `rotation` in [0, 1) turns the cube about n
  /// by 2π·rotation. Elements listed in `excluded` (the shooter's own) receive nothing.
  /// A pixel centre shows the nearest triangle there, and of two at exactly the same depth
  /// the one drawn first. Without culling that is the lower element; with it the elements are
  /// drawn in batches (near subtrees first), each in element order. A skipped hidden subtree
  /// could only have won a pixel through the raster's depth overshoot: a sub-pixel sliver
  /// seen edge-on, whose depth extrapolated to a pixel centre just outside it (inside it only
  /// once snapped) can lie far nearer than its corners.
  void compute(const glm::dvec3& x, const glm::dvec3& n, double rotation, FormFactors& out,
               const std::vector<int>& excluded = {});

  int resolution() const { return resolution_; }
  /// The distance from the eye to the nearest surface (either side) a pixel centre showed in
  /// the last compute(), or infinity: the light arriving from place to place changes over
  /// distances like this (Tabellion & Lamorlette 2004 take it for Ward's harmonic mean
  /// distance). Asked for, not computed with every cube: the shooters' need none of it.
  double nearest() const;
  /// Which elements the following computes sort to the faces (default Auto, which the first
  /// compute resolves).
  void setCulling(HemicubeCulling culling);
  HemicubeCulling culling() const { return culling_; }
  const HemicubeCounts& counts() const { return counts_; }
  /// The elements the last compute sorted to its faces (every element without culling): what
  /// its cost follows.
  size_t sorted() const { return sortedCount_; }

  /// What one face draws: the clip-space vertices of the triangles that may show on it (z =
  /// near, reversed [0, 1] depth, GREATER), 3 indices per triangle into them (or none: three
  /// vertices per triangle) and each triangle's item id (the element, or an occluder id), in
  /// batches drawn one after the other (a batch's indices count from its first vertex). Face
  /// 0 is the top (R×R), 1–4 the sides (R×R/2, upper half only).
  struct FaceDraw {
    struct Batch {
      uint32_t firstVertex = 0, firstTriangle = 0;
    };
    std::vector<glm::vec4> clip;
    std::vector<uint32_t> indices, ids;
    std::vector<Batch> batches;
  };

  /// The steps of compute(), for drawing the identical item buffers with another rasteriser
  /// (benchmarks): prepare() places the cube, sets the item ids and sorts the triangles to
  /// the faces they may show on; faceDraw(f) is face f's share. Culling hidden subtrees,
  /// prepare() also draws every batch but the last into the cube's own faces.
  void prepare(const glm::dvec3& x, const glm::dvec3& n, double rotation,
               const std::vector<int>& excluded = {});
  const FaceDraw& faceDraw(int face) const { return draws_[size_t(face)]; }

  /// Near plane and eye offset, as fractions of the scene size.
  static constexpr double kNearPlane = 1e-7;
  static constexpr double kEyeOffset = 1e-6;
  /// Auto culls hidden subtrees when probe cubes (see cullingPays) sort fewer than this
  /// share of the elements to their faces: below it, visiting the hierarchy costs less than
  /// placing every vertex.
  static constexpr double kCullingPaysBelow = 0.2;
  /// Item id of a triangle that occludes but receives nothing (seen from behind, or
  /// excluded): raster::kNoItem - 1.
  static constexpr uint32_t kOccluder = 0xFFFFFFFEu;

 private:
  /// Whether culling hidden subtrees pays over `geometry`: the share of its elements that
  /// cubes culling them still sort to their faces, from a few element centroids spread over
  /// it, is below kCullingPaysBelow. Measured once per geometry, so the same everywhere.
  static bool cullingPays(const HemicubeGeometry& geometry, double sceneSize);
  /// Every element's triangle to the faces it may show on, as one indexed batch: each vertex
  /// placed once, then the triangles in element order.
  void sortAll();
  /// Each face's share of the vertices sortAll() found needed, in vertex order.
  void placeNeeded();
  /// Each face's indices and ids of the triangles sortAll() sorted to it (counted per face).
  void emitAll(const std::array<size_t, 5>& triangles);
  /// Visits the hierarchy near subtrees first, skipping the culled ones and collecting the
  /// elements of the others into batches (all but the last drawn when culling hidden ones).
  void traverse();
  /// Whether the subtree of node k can be skipped (its elements counted in counts_).
  bool culled(uint32_t k);
  /// Pushes node k's children, the nearer on top.
  void pushChildren(uint32_t k);
  /// Places a leaf's vertices and adds each of its elements that may show on a face to the
  /// pending batch.
  void collect(const ElementHierarchy::Node& leaf);
  /// Whether to draw the pending batch before testing a subtree of `count` elements.
  bool worthDrawingFirst(uint32_t count) const;
  /// Sorts the pending elements, in element order, to the faces they may show on as a batch.
  void sortBatch();
  /// Draws the batches not drawn yet and, if `forTests`, rebuilds the faces' depth pyramids.
  void drawBatches(bool forTests);
  /// Sums each face's delta form factors per item into `out` (elements ascending).
  void accumulate(FormFactors& out);
  /// accumulate() drawing flat regions: each pixel's delta form factor to the element its
  /// centre's ray meets.
  void accumulateLocated(FormFactors& out);
  /// The accumulator's non-zero sums into `out` (elements ascending), emptying it.
  void takeAccumulated(FormFactors& out);
  /// The item id of element e with this normal and corner: itself if seen from its lit side
  /// and not excluded.
  uint32_t itemId(uint32_t e, const glm::dvec3& normal, const glm::dvec3& corner) const;
  /// Whether element e, with this normal and corner, is not drawn because its twin on a
  /// two-sided surface's other side faces the hemicube (HemicubeGeometry::twoSided).
  bool twinShows(uint32_t e, const glm::dvec3& normal, const glm::dvec3& corner) const;
  /// The faces that may show a triangle whose corners share the outside planes `shared`
  /// (bits), none if it lies below the base plane.
  static uint32_t facesShowing(uint32_t shared);

  const HemicubeGeometry& geometry_;
  const FlatRegions* regions_ = nullptr;  // what the drawn triangles stand for, if not themselves
  std::vector<int> excludedElements_;      // with regions_: the excluded elements
  std::vector<uint32_t> below_;            // with regions_: per column, where its last search ended
  std::shared_ptr<const ElementHierarchy> hierarchy_;
  int resolution_;
  double near_, eyeOffset_;
  const DeltaFormFactors& delta_;
  HemicubeCulling culling_ = HemicubeCulling::Auto;
  HemicubeCounts counts_;
  HemicubeFrame frame_;
  std::array<std::unique_ptr<raster::Target>, 5> faces_;  // top, +u, -u, +v, -v
  std::array<DepthPyramid, 5> pyramids_;
  std::array<size_t, 5> drawnBatches_{};  // per face, the batches already drawn
  /// An element of the pending batch: its corners' local coordinates (float, as drawn), its
  /// item id and the faces it may show on (bits).
  struct Pending {
    std::array<std::array<float, 3>, 3> corners;
    uint32_t id, faces;
  };
  uint32_t stamp_ = 0;                // the current compute's: excluded_[e] == stamp_
  std::vector<uint32_t> excluded_;    // per element
  std::vector<Pending> pending_;      // in the order collected
  std::vector<uint32_t> pendingAt_;   // per element in pending_, its index there
  IndexSet pendingSet_;               // the elements in pending_, for element order
  size_t sortedCount_ = 0;            // elements sorted to the faces in earlier batches
  // Sorting every element (no culling): per vertex its local coordinates, outside planes,
  // the faces that draw it and its index in each face's vertices; per element its faces.
  std::vector<std::array<float, 3>> local_;
  std::vector<uint32_t> outside_, slot_;
  std::vector<uint8_t> needed_, facesOf_;
  std::vector<uint32_t> stack_;              // nodes still to visit
  std::array<FaceDraw, 5> draws_;
  std::vector<double> accumulator_;  // per element
  IndexSet seen_;                    // the elements with a sum in the accumulator
};

/// A deterministic rotation in [0, 1) for (seed, shooter, sample point): every run, and the
/// progressive and reference solvers alike, see the same hemicubes.
double hemicubeRotation(uint64_t seed, uint64_t shooter, uint64_t sample);

}  // namespace rad
