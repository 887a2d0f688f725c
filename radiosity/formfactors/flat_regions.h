#pragma once
// A mesh's elements as a hemicube draws them: each flat region (elements of one surface side
// that meet edge to edge in one plane: a wall, a block's face, a tabletop) as the constrained
// triangulation of its outline, a few large triangles instead of its hundreds of elements, and
// each pixel's element found afterwards under the pixel centre's ray, by a grid over the
// region. The item buffer then shows the element whose triangle holds the point the pixel
// centre's ray meets, which is what drawing every element shows (up to the raster's
// sub-pixel snapping of element edges), while the raster's cost follows the outlines, not the
// elements: a finely meshed room costs about what its coarse model costs.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mesh/scene/geometry.h"
#include "radiosity/formfactors/hemicube.h"

namespace rad {

class PatchMesh;

class FlatRegions {
 public:
  /// The regions of `mesh`'s elements. sceneSize: the scene diagonal (flatness tolerance).
  FlatRegions(const PatchMesh& mesh, double sceneSize);

  /// The triangles drawn: regions' outline triangles, and the elements of regions left as
  /// they are (one element; an outline that would not triangulate into fewer triangles, or not
  /// cover the elements' area; a grid that would grow too large).
  const HemicubeGeometry& drawn() const { return drawn_; }
  size_t elementCount() const { return elementCount_; }
  size_t regionCount() const { return regions_.size(); }

  /// What drawn triangle t shows: an element (≥ 0), or -1 - r for region r's outline, whose
  /// element at a pixel locate() finds.
  int32_t shows(uint32_t t) const { return drawnElement_[t]; }
  /// Where the rays eye + s·(d + k·step), k = 0, 1, 2, ... (a row of pixel centres) meet
  /// region r's plane, in the region's frame: a projective map of k.
  struct RowWalk {
    double wu, wv, height;  // the eye in the region's frame, its height above the plane
    double towards, u, v;   // the ray direction's components along the normal, u and v at k = 0
    double dTowards, du, dv;  // and their steps per k
    glm::dvec2 at(int k) const {
      const double t = towards + k * dTowards;
      const double s = t < 0 ? -height / t : 0;  // ≥ 0 but for rounding at grazing rays
      return {wu + s * (u + k * du), wv + s * (v + k * dv)};
    }
  };
  /// The RowWalk of region r (shows() of one of its triangles) from `eye`.
  RowWalk rowWalk(int32_t shows, const glm::dvec3& eye, const glm::dvec3& d, const glm::dvec3& step) const;
  /// Where locate() ended: the element, and its slot (the next search's hint).
  struct Located {
    uint32_t element, slot;
  };
  /// The element of region r that holds point p of its frame, or the nearest one (a ray
  /// may miss by rounding at the outline). `hint`: where the last search ended (any value to
  /// begin with), walked from first, as neighbouring pixels mostly show one element. (Hint
  /// and slot go by value: a walk's steps are its latency, and a hint by reference went
  /// through memory at each.)
  Located locate(int32_t shows, const glm::dvec2& p, uint32_t hint) const {
    const Region& r = regions_[size_t(-1 - shows)];
    // A grazing ray may meet the plane far off the region: no farther than its extent beyond it.
    const glm::dvec2 margin = r.hi - r.lo, q = glm::clamp(p, r.lo - margin, r.hi + margin);
    const float x = float(q.x), y = float(q.y);
    if (hint - r.firstSlot < r.slotCount)  // walk from the last pixel's element
      for (int step = 0; step <= kWalk && hint != kNone; ++step) {
        const uint32_t beyond = outside(hint, x, y);
        if (!beyond) {
          // The next pixel's element is mostly this one or across one of its edges: the
          // walk's loads are its latency, so those slots are fetched ahead.
          const Slot& found = slots_[hint];
          for (uint32_t next : found.across)
            if (next != kNone) __builtin_prefetch(&slots_[next]);
          return {found.element, hint};
        }
        hint = slots_[hint].across[size_t(__builtin_ctz(beyond))];
      }
    return search(r, q);
  }

 private:
  /// A region drawn by its outline: its plane frame, its elements' corners in that frame and
  /// a grid of the elements over their bounding box.
  struct Region {
    PlaneFrame frame;  ///< u × v is the normal, towards the lit side
    glm::dvec2 lo{0.0}, hi{0.0};  ///< its elements' bounding box in its frame
    double inverseCell = 0;
    int columns = 1, rows = 1;
    uint32_t firstCell = 0;  ///< its cell (row, column) is cellStart_[firstCell + row·columns + column]
    uint32_t firstSlot = 0, slotCount = 0;  ///< its elements' slots
  };
  /// An element of a region: its edges' lines a·x + b·y + c in the region's frame (unit
  /// normal (a, b), ≥ 0 inside; edge k from corner k to corner k + 1; lane 3 never outside),
  /// in single precision (a pixel's point is found to about 1e-7 of the region, far below its
  /// elements' size), the slot across each edge (kNone: none) and its element: a cache line.
  struct alignas(64) Slot {
    std::array<float, 4> a, b, c;
    std::array<uint32_t, 3> across;
    uint32_t element;
  };
  static constexpr uint32_t kNone = ~0u;
  /// Steps from slot to slot across an edge the point lies beyond, from a neighbouring pixel's
  /// element, before the grid is searched instead.
  static constexpr int kWalk = 4;

  /// The edges of slot s's triangle that point (x, y) lies beyond (bit k: edge k).
  uint32_t outside(uint32_t s, float x, float y) const {
    const Slot& slot = slots_[s];
#if defined(__SSE2__)
    const __m128 e = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(slot.a.data()), _mm_set1_ps(x)),
                                           _mm_mul_ps(_mm_load_ps(slot.b.data()), _mm_set1_ps(y))),
                                _mm_load_ps(slot.c.data()));
    return uint32_t(_mm_movemask_ps(_mm_cmplt_ps(e, _mm_setzero_ps())));
#else
    uint32_t bits = 0;
    for (size_t k = 0; k < 3; ++k) bits |= uint32_t(slot.a[k] * x + slot.b[k] * y + slot.c[k] < 0) << k;
    return bits;
#endif
  }
  /// locate() by the region's grid, from the cell of point q.
  Located search(const Region& r, const glm::dvec2& q) const;
  /// Adds the slots of a region's elements (`group`, flat group g; their vertices' frame
  /// coordinates in `at`), each with its neighbours across its edges (slotOf: per element).
  void addSlots(const PatchMesh& mesh, const std::vector<int>& group, int g, const std::vector<int>& groupOf,
                const std::vector<glm::dvec2>& at, std::vector<uint32_t>& slotOf, Region& region);
  /// Adds the grid over a region's slots: about one cell per element, each listing the slots
  /// whose boxes overlap it. False (nothing added) if that would list more than
  /// kMaxGridEntriesPerElement slots per element.
  bool addGrid(const PatchMesh& mesh, const std::vector<glm::dvec2>& at, Region& region);
  /// How far inside slot s's triangle point (x, y) lies: its smallest edge value (< 0
  /// outside; computed as outside() computes it).
  float inside(uint32_t s, float x, float y) const {
    const Slot& slot = slots_[s];
    float least = slot.a[0] * x + slot.b[0] * y + slot.c[0];
    for (size_t k = 1; k < 3; ++k) least = std::min(least, slot.a[k] * x + slot.b[k] * y + slot.c[k]);
    return least;
  }

  HemicubeGeometry drawn_;
  size_t elementCount_ = 0;
  std::vector<int32_t> drawnElement_;   ///< per drawn triangle: its element, or -1 - its region
  std::vector<Region> regions_;
  std::vector<Slot> slots_;
  std::vector<uint32_t> cellStart_;     ///< per cell of every region, its first entry in cellSlots_ (+ one end)
  std::vector<uint32_t> cellSlots_;
};

}  // namespace rad
