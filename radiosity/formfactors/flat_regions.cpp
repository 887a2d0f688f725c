#include "radiosity/formfactors/flat_regions.h"

#include <cmath>
#include <exception>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/polygon_mesher.h"
#include "mesh/scene/geometry.h"

namespace rad {
namespace {

/// Two elements across an edge are in one plane when their normals differ by less than this
/// (1 − cos of about 4e-6 rad: rounding of one plane's normal, not a tessellated curve)...
constexpr double kFlatCosine = 1e-11;
/// ...and every corner lies this close (relative to the scene size) to the region's plane,
/// so that a region cannot creep round a gentle curve.
constexpr double kFlatDistance = 1e-9;
/// A boundary vertex is dropped from the outline when it lies this close (relative to its
/// neighbours' distances) to the line between them: a point that split a straight edge.
constexpr double kCollinear = 1e-9;
/// A region's outline triangles must cover its elements' area to this (relative).
constexpr double kSameArea = 1e-9;
/// A region's grid may list at most this many slots per element in all (a fan of long
/// slivers would list each in most cells): beyond, the region is drawn as its elements.
constexpr size_t kMaxGridEntriesPerElement = 32;

/// The elements grouped into flat regions (connected across edges, one plane).
std::vector<std::vector<int>> flatGroups(const PatchMesh& mesh, double sceneSize, std::vector<int>& groupOf) {
  const TriMesh& m = mesh.mesh;
  const int n = mesh.elementCount();
  groupOf.assign(size_t(n), -1);
  std::vector<std::vector<int>> groups;
  std::vector<int> stack;
  for (int seed = 0; seed < n; ++seed) {
    if (groupOf[size_t(seed)] >= 0) continue;
    const int g = int(groups.size());
    std::vector<int>& group = groups.emplace_back();
    const glm::dvec3 normal = mesh.normal(seed), origin = mesh.corners(seed)[0];
    auto flat = [&](int e) {
      if (1 - glm::dot(mesh.normal(e), normal) > kFlatCosine) return false;
      for (const glm::dvec3& c : mesh.corners(e))
        if (std::abs(glm::dot(c - origin, normal)) > kFlatDistance * sceneSize) return false;
      return true;
    };
    groupOf[size_t(seed)] = g;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      group.push_back(e);
      for (auto h : m.fh_range(TriMesh::FaceHandle(e))) {
        const auto other = m.opposite_face_handle(h);
        if (!other.is_valid() || groupOf[size_t(other.idx())] >= 0 || !flat(other.idx())) continue;
        groupOf[size_t(other.idx())] = g;
        stack.push_back(other.idx());
      }
    }
  }
  return groups;
}

/// Loops that pass a vertex twice, split there into loops that do not.
std::vector<std::vector<int>> splitAtPinches(std::vector<std::vector<int>> loops) {
  std::vector<std::vector<int>> out;
  while (!loops.empty()) {
    std::vector<int> loop = std::move(loops.back());
    loops.pop_back();
    std::unordered_map<int, size_t> at;
    bool split = false;
    for (size_t k = 0; k < loop.size() && !split; ++k) {
      const auto [it, added] = at.emplace(loop[k], k);
      if (added) continue;
      // loop[it->second .. k) is a loop of its own; the rest goes on without it.
      loops.emplace_back(loop.begin() + std::ptrdiff_t(it->second), loop.begin() + std::ptrdiff_t(k));
      loop.erase(loop.begin() + std::ptrdiff_t(it->second), loop.begin() + std::ptrdiff_t(k));
      loops.push_back(std::move(loop));
      split = true;
    }
    if (!split && loop.size() >= 3) out.push_back(std::move(loop));
  }
  return out;
}

/// The loop without its vertices that lie on the straight line between their neighbours, but
/// those `kept(v)` holds (a pinch, which another loop passes too; a corner of a neighbour drawn
/// as its elements, which would leave a T-junction in the raster).
template <class Keep>
std::vector<int> withoutCollinear(const std::vector<int>& loop, const std::vector<glm::dvec2>& at, const Keep& keep) {
  std::vector<int> kept;
  const size_t n = loop.size();
  for (size_t k = 0; k < n; ++k) {
    if (keep(loop[k])) {
      kept.push_back(loop[k]);
      continue;
    }
    const glm::dvec2 a = at[size_t(kept.empty() ? loop[(k + n - 1) % n] : kept.back())];
    const glm::dvec2 b = at[size_t(loop[k])], c = at[size_t(loop[(k + 1) % n])];
    const glm::dvec2 ab = b - a, bc = c - b;
    const double cross = ab.x * bc.y - ab.y * bc.x;
    const bool onLine = std::abs(cross) <= kCollinear * glm::length(ab) * glm::length(bc) && glm::dot(ab, bc) > 0;
    if (!onLine) kept.push_back(loop[k]);
  }
  return kept;
}

/// The line through a and b as (A, B, C) with A·x + B·y + C the signed distance, positive
/// on the left (inside a counter-clockwise triangle); zero for a point.
glm::dvec3 edgeLine(const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 d = b - a;
  const double length = glm::length(d);
  if (length == 0) return glm::dvec3(0.0);
  const double A = -d.y / length, B = d.x / length;
  return {A, B, -(A * a.x + B * a.y)};
}

/// Edge k's line into lane k of a slot.
void setEdge(std::array<float, 4>& a, std::array<float, 4>& b, std::array<float, 4>& c, size_t k, const glm::dvec3& line) {
  a[k] = float(line.x), b[k] = float(line.y), c[k] = float(line.z);
}


/// Positions as hash keys (-0 folded into 0 by the caller).
struct PositionHash {
  size_t operator()(const glm::dvec3& p) const {
    const std::hash<double> h;
    return h(p.x) * 73856093u ^ h(p.y) * 19349663u ^ h(p.z) * 83492791u;
  }
};

/// Twice the area of triangle (a, b, c) in the plane, signed (counter-clockwise positive).
double area2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// The constrained triangulation of a region's outline (its vertices' frame coordinates in
/// `at`), if it closes, triangulates, covers the region's area and takes fewer triangles than
/// the region has elements; else empty (the region is drawn as its elements). `pinned(v)`:
/// vertex v must stay a corner.
template <class Pinned>
Triangulation2 outlineTriangulation(const PatchMesh& mesh, const std::vector<int>& group, int g,
                                    const std::vector<int>& groupOf, const std::vector<glm::dvec2>& at,
                                    const Pinned& pinned) {
  const auto loops = splitAtPinches(mesh.boundaryLoops(group, [&](int e) { return groupOf[size_t(e)] == g; }));
  std::unordered_map<int, int> passes;  // per vertex, how many times the loops pass it
  for (const auto& loop : loops)
    for (int v : loop) ++passes[v];
  Polygon2 outline;
  for (const auto& loop : loops) {
    const std::vector<int> corners = withoutCollinear(loop, at, [&](int v) { return passes[v] > 1 || pinned(v); });
    if (corners.size() < 3) continue;
    auto& ring = outline.rings.emplace_back();
    for (int v : corners) ring.push_back(at[size_t(v)]);
    outline.ids.push_back(corners);
  }
  Triangulation2 triangles;
  try {
    if (!outline.rings.empty()) triangles = triangulatePolygon(outline, "flat region");
  } catch (const std::exception&) {
    return {};  // rings that cross by rounding
  }
  if (triangles.triangles.empty() || triangles.triangles.size() >= group.size()) return {};
  for (int id : triangles.ids)
    if (id < 0) return {};
  // The outline's triangles cover exactly the elements (an inside-out nesting would not).
  double covered = 0, elements = 0;
  for (const auto& t : triangles.triangles)
    covered += std::abs(area2(triangles.points[size_t(t[0])], triangles.points[size_t(t[1])], triangles.points[size_t(t[2])]));
  for (int e : group) {
    std::array<glm::dvec2, 3> c;
    size_t k = 0;
    for (auto v : mesh.mesh.fv_range(TriMesh::FaceHandle(e))) c[k++] = at[size_t(v.idx())];
    elements += std::abs(area2(c[0], c[1], c[2]));
  }
  if (std::abs(covered - elements) > kSameArea * elements) return {};
  return triangles;
}

}  // namespace

FlatRegions::FlatRegions(const PatchMesh& mesh, double sceneSize) {
  const TriMesh& m = mesh.mesh;
  elementCount_ = size_t(mesh.elementCount());
  std::vector<int> groupOf;
  const std::vector<std::vector<int>> groups = flatGroups(mesh, sceneSize, groupOf);
  std::vector<int> placed(m.n_vertices(), -1);  // mesh vertex → drawn position
  std::vector<int> drawnSurface;
  auto draw = [&](const std::array<int, 3>& corners, const glm::dvec3& normal, int32_t shows, int surface) {
    for (int v : corners) {
      if (placed[size_t(v)] < 0) {
        placed[size_t(v)] = int(drawn_.positions.size());
        drawn_.positions.push_back(PatchMesh::toGlm(m.point(TriMesh::VertexHandle(v))));
      }
      drawn_.indices.push_back(uint32_t(placed[size_t(v)]));
    }
    drawn_.normals.push_back(normal);
    drawnElement_.push_back(shows);
    drawnSurface.push_back(surface);
  };
  auto drawElement = [&](int e) {
    std::array<int, 3> corners;
    int k = 0;
    for (auto v : m.fv_range(TriMesh::FaceHandle(e))) corners[size_t(k++)] = v.idx();
    draw(corners, mesh.normal(e), e, mesh.surface(e));
  };
  // The corners of one-element regions, drawn as they are: an outline keeps them.
  std::unordered_set<glm::dvec3, PositionHash> singleCorners;
  for (const auto& group : groups)
    if (group.size() == 1)
      for (const glm::dvec3& c : mesh.corners(group[0])) singleCorners.insert(c + glm::dvec3(0.0));
  auto pinned = [&](int v) {
    return !singleCorners.empty() && singleCorners.count(PatchMesh::toGlm(m.point(TriMesh::VertexHandle(v))) + glm::dvec3(0.0));
  };
  std::vector<glm::dvec2> at(m.n_vertices());  // the current region's vertices in its frame
  std::vector<uint32_t> slotOf(elementCount_, kNone);
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::vector<int>& group = groups[g];
    if (group.size() == 1) {
      drawElement(group[0]);
      continue;
    }
    // The region's frame (planeFrame's u × v is its normal) and its vertices in it.
    Region region;
    region.frame = planeFrame(mesh.corners(group[0])[0], mesh.normal(group[0]));
    for (int e : group)
      for (auto v : m.fv_range(TriMesh::FaceHandle(e))) at[size_t(v.idx())] = region.frame.project(PatchMesh::toGlm(m.point(v)));
    // Its outline's triangles, its elements' slots and the grid over them; or its elements.
    const Triangulation2 outline = outlineTriangulation(mesh, group, int(g), groupOf, at, pinned);
    bool byOutline = !outline.triangles.empty();
    if (byOutline) {
      addSlots(mesh, group, int(g), groupOf, at, slotOf, region);
      byOutline = addGrid(mesh, at, region);
      if (!byOutline) slots_.resize(region.firstSlot);
    }
    if (!byOutline) {
      for (int e : group) drawElement(e);
      continue;
    }
    const int32_t code = -1 - int32_t(regions_.size());
    for (const auto& t : outline.triangles)
      draw({outline.ids[size_t(t[0])], outline.ids[size_t(t[1])], outline.ids[size_t(t[2])]}, region.frame.normal, code,
           mesh.surface(group[0]));
    regions_.push_back(region);
  }
  cellStart_.push_back(uint32_t(cellSlots_.size()));
  drawn_.markTwoSided(mesh, drawnSurface);
}

void FlatRegions::addSlots(const PatchMesh& mesh, const std::vector<int>& group, int g, const std::vector<int>& groupOf,
                           const std::vector<glm::dvec2>& at, std::vector<uint32_t>& slotOf, Region& region) {
  const TriMesh& m = mesh.mesh;
  region.firstSlot = uint32_t(slots_.size());
  region.slotCount = uint32_t(group.size());
  for (size_t k = 0; k < group.size(); ++k) slotOf[size_t(group[k])] = region.firstSlot + uint32_t(k);
  for (int e : group) {
    Slot slot{};
    slot.element = uint32_t(e);
    std::array<glm::dvec2, 3> c;
    size_t k = 0;
    for (auto h : m.fh_range(TriMesh::FaceHandle(e))) {  // edge k: corner k to corner k + 1
      c[k] = at[size_t(m.from_vertex_handle(h).idx())];
      const auto other = m.opposite_face_handle(h);
      slot.across[k++] = other.is_valid() && groupOf[size_t(other.idx())] == g ? slotOf[size_t(other.idx())] : kNone;
    }
    for (k = 0; k < 3; ++k) setEdge(slot.a, slot.b, slot.c, k, edgeLine(c[k], c[(k + 1) % 3]));
    setEdge(slot.a, slot.b, slot.c, 3, glm::dvec3(0, 0, std::numeric_limits<float>::max()));
    slots_.push_back(slot);
  }
}

bool FlatRegions::addGrid(const PatchMesh& mesh, const std::vector<glm::dvec2>& at, Region& region) {
  // Each slot's box in the frame; the grid over them has about one cell per element.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::pair<glm::dvec2, glm::dvec2>> boxes;
  glm::dvec2 lo(inf), hi(-inf);
  for (uint32_t s = region.firstSlot; s < region.firstSlot + region.slotCount; ++s) {
    glm::dvec2 a(inf), b(-inf);
    for (auto v : mesh.mesh.fv_range(TriMesh::FaceHandle(int(slots_[s].element))))
      a = glm::min(a, at[size_t(v.idx())]), b = glm::max(b, at[size_t(v.idx())]);
    boxes.emplace_back(a, b);
    lo = glm::min(lo, a), hi = glm::max(hi, b);
  }
  const double n = double(region.slotCount);
  const glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(1e-300));
  region.lo = lo;
  region.inverseCell = 1 / std::max({std::sqrt(extent.x * extent.y / n), extent.x / n, extent.y / n});
  region.columns = std::max(1, int(std::ceil(extent.x * region.inverseCell)));
  region.rows = std::max(1, int(std::ceil(extent.y * region.inverseCell)));
  region.hi = hi;
  region.firstCell = uint32_t(cellStart_.size());
  auto cell = [&](double x, double lo, int count) { return std::clamp(int((x - lo) * region.inverseCell), 0, count - 1); };
  size_t entries = 0;
  for (const auto& [a, b] : boxes)
    entries += size_t(cell(b.y, lo.y, region.rows) - cell(a.y, lo.y, region.rows) + 1) *
               size_t(cell(b.x, lo.x, region.columns) - cell(a.x, lo.x, region.columns) + 1);
  if (entries > kMaxGridEntriesPerElement * boxes.size()) return false;
  std::vector<std::vector<uint32_t>> lists(size_t(region.columns) * size_t(region.rows));
  for (uint32_t k = 0; k < region.slotCount; ++k) {
    const auto& [a, b] = boxes[k];
    for (int r = cell(a.y, lo.y, region.rows); r <= cell(b.y, lo.y, region.rows); ++r)
      for (int c = cell(a.x, lo.x, region.columns); c <= cell(b.x, lo.x, region.columns); ++c)
        lists[size_t(r) * size_t(region.columns) + size_t(c)].push_back(region.firstSlot + k);
  }
  for (const auto& list : lists) {
    cellStart_.push_back(uint32_t(cellSlots_.size()));
    cellSlots_.insert(cellSlots_.end(), list.begin(), list.end());
  }
  return true;
}

FlatRegions::RowWalk FlatRegions::rowWalk(int32_t shows, const glm::dvec3& eye, const glm::dvec3& d,
                                          const glm::dvec3& step) const {
  const Region& r = regions_[size_t(-1 - shows)];
  const PlaneFrame& f = r.frame;
  const glm::dvec3 w = eye - f.origin;
  return {glm::dot(w, f.u),        glm::dot(w, f.v),        glm::dot(w, f.normal),
          glm::dot(d, f.normal),    glm::dot(d, f.u),        glm::dot(d, f.v),
          glm::dot(step, f.normal), glm::dot(step, f.u),     glm::dot(step, f.v)};
}

FlatRegions::Located FlatRegions::search(const Region& r, const glm::dvec2& q) const {
  const float x = float(q.x), y = float(q.y);
  const int column = std::clamp(int((q.x - r.lo.x) * r.inverseCell), 0, r.columns - 1);
  const int row = std::clamp(int((q.y - r.lo.y) * r.inverseCell), 0, r.rows - 1);
  const size_t cell = r.firstCell + size_t(row) * size_t(r.columns) + size_t(column);
  uint32_t best = r.firstSlot;
  float bestInside = -std::numeric_limits<float>::infinity();
  auto consider = [&](uint32_t s) {
    const float d = inside(s, x, y);
    if (d > bestInside) bestInside = d, best = s;
    return d >= 0;
  };
  for (uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k)
    if (consider(cellSlots_[k])) return {slots_[cellSlots_[k]].element, cellSlots_[k]};
  if (cellStart_[cell] == cellStart_[cell + 1])  // an empty cell (a hole), reached by rounding
    for (uint32_t s = r.firstSlot; s < r.firstSlot + r.slotCount; ++s) consider(s);
  return {slots_[best].element, best};
}

}  // namespace rad
