#include "radiosity/formfactors/hemicube.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "display/raster/raster.h"
#include "mesh/base/error.h"
#include "mesh/patch_mesh.h"
#include "radiosity/formfactors/element_hierarchy.h"
#include "radiosity/formfactors/flat_regions.h"
#include "radiosity/formfactors/hemicube_culling.h"
#include "radiosity/formfactors/point_polygon.h"

namespace rad {
namespace {

static_assert(Hemicube::kOccluder == raster::kNoItem - 1, "the occluders' id is the one below no item");
/// The probe cubes of Hemicube::cullingPays: how many, and their resolution.
constexpr size_t kProbes = 8;
constexpr int kProbeResolution = 32;

/// Guards the geometries' hierarchies and culling decisions.
std::mutex& geometryMutex() {
  static std::mutex mutex;
  return mutex;
}

/// The top face's R×R pixels: each pixel's factor is the exact factor of its square, seen
/// from the origin (normal +z).
std::vector<double> topPixelFactors(int R) {
  const glm::dvec3 origin(0.0), up(0, 0, 1);
  const double h = 2.0 / R;
  std::vector<double> top(size_t(R) * R);
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < R; ++i) {
      double x0 = -1 + i * h, y0 = -1 + j * h;
      top[size_t(j) * R + i] = pointPolygonFormFactor(
          origin, up, {{x0, y0, 1}, {x0 + h, y0, 1}, {x0 + h, y0 + h, 1}, {x0, y0 + h, 1}});
    }
  return top;
}

/// A side face's R×R/2 pixels, row 0 on the base plane, exact as on the top face.
std::vector<double> sidePixelFactors(int R) {
  const glm::dvec3 origin(0.0), up(0, 0, 1);
  const double h = 2.0 / R;
  std::vector<double> side(size_t(R) * R / 2);
  for (int j = 0; j < R / 2; ++j)
    for (int i = 0; i < R; ++i) {
      double x0 = -1 + i * h, z0 = j * h;  // side face x = 1 ... mirrored faces share the table
      side[size_t(j) * R + i] = pointPolygonFormFactor(
          origin, up, {{1, x0, z0}, {1, x0 + h, z0}, {1, x0 + h, z0 + h}, {1, x0, z0 + h}});
    }
  return side;
}

/// Where the delta form factors go: the elements' sums (and which are in use), then sky and
/// back faces (every item id past the elements but the sky's is an occluder's back).
struct Slots {
  double* acc;
  IndexSet& seen;
  uint32_t n;
  double sky = 0, back = 0;

  void add(uint32_t id, double value) {
    if (id < n) {
      acc[id] += value;
      seen.insert(id);
    } else {
      (id == raster::kNoItem ? sky : back) += value;
    }
  }
};

#if defined(__SSE2__)
/// Adds each pixel's delta form factor (delta[k]) to the slot of the item it shows (item[k]).
inline void accumulateFace(const uint32_t* item, const double* delta, size_t count, Slots& slots) {
  // Neighbouring pixels mostly see the same element: while four pixels at a time continue
  // the current run, sum them in two independent partial sums; a chunk where the run ends
  // flushes the run and adds its own pixels one by one.
  size_t k = 0;
  uint32_t run = item[0];
  __m128d part0 = _mm_setzero_pd(), part1 = _mm_setzero_pd();
  auto flush = [&] {
    alignas(16) double lanes[4];
    _mm_store_pd(lanes, part0);
    _mm_store_pd(lanes + 2, part1);
    slots.add(run, (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]));
    part0 = part1 = _mm_setzero_pd();
  };
  __m128i runs = _mm_set1_epi32(int(run));
  for (; k + 4 <= count; k += 4) {
    const __m128i ids = _mm_loadu_si128(reinterpret_cast<const __m128i*>(item + k));
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(ids, runs)) == 0xFFFF) {
      part0 = _mm_add_pd(part0, _mm_loadu_pd(delta + k));
      part1 = _mm_add_pd(part1, _mm_loadu_pd(delta + k + 2));
      continue;
    }
    flush();
    for (size_t i = k; i < k + 4; ++i) slots.add(item[i], delta[i]);
    run = item[k + 3];
    runs = _mm_set1_epi32(int(run));
  }
  flush();
  for (; k < count; ++k) slots.add(item[k], delta[k]);  // the last 0-3 pixels
}
#else
/// Adds each pixel's delta form factor (delta[k]) to the slot of the item it shows (item[k]),
/// a run of equal items at a time.
inline void accumulateFace(const uint32_t* item, const double* delta, size_t count, Slots& slots) {
  uint32_t run = item[0];
  double sum = 0;
  for (size_t k = 0; k < count; ++k) {
    if (item[k] != run) {
      slots.add(run, sum);
      run = item[k];
      sum = 0;
    }
    sum += delta[k];
  }
  slots.add(run, sum);
}
#endif

}  // namespace

double FormFactors::sum() const {
  double s = sky + backFaces;
  for (double f : factors) s += f;
  return s;
}

std::shared_ptr<const ElementHierarchy> HemicubeGeometry::hierarchy() const {
  std::lock_guard<std::mutex> lock(geometryMutex());
  const bool current = hierarchy_ && hierarchy_->elementCount() == elementCount() &&
                       hierarchy_->vertexCount() == positions.size();
  if (current || elementCount() == 0) return hierarchy_;
  hierarchy_ = std::make_shared<const ElementHierarchy>(positions, indices, normals);
  cullingPays_ = -1;
  return hierarchy_;
}

const DeltaFormFactors& DeltaFormFactors::forResolution(int R) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<DeltaFormFactors>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[R];
  if (slot) return *slot;
  RAD_CHECK(R >= 2 && R % 2 == 0);
  auto d = std::make_unique<DeltaFormFactors>();
  d->resolution = R;
  d->top = topPixelFactors(R);
  d->side = sidePixelFactors(R);
  // The exact integrals sum to 1 up to round-off; normalise so that it holds to 1e-15.
  double sum = 0;
  for (double f : d->top) sum += f;
  for (double f : d->side) sum += 4 * f;
  d->exactSum = sum;
  for (double& f : d->top) f /= sum;
  for (double& f : d->side) f /= sum;
  // Pixel centres' directions: the top's (x, y, 1), a side's (1, x, z) with z up from the base.
  const double h = 2.0 / R;
  d->topPerLength.resize(d->top.size());
  d->sidePerLength.resize(d->side.size());
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < R; ++i) {
      const double x = -1 + (i + 0.5) * h, y = -1 + (j + 0.5) * h;
      const size_t k = size_t(j) * size_t(R) + size_t(i);
      d->topPerLength[k] = float(1 / std::sqrt(1 + x * x + y * y));
      if (j < R / 2) d->sidePerLength[k] = float(1 / std::sqrt(1 + x * x + ((j + 0.5) * h) * ((j + 0.5) * h)));
    }
  slot = std::move(d);
  return *slot;
}

Hemicube::Hemicube(const HemicubeGeometry& geometry, int resolution, double sceneSize)
    : geometry_(geometry), hierarchy_(geometry.hierarchy()), resolution_(resolution),
      near_(kNearPlane * sceneSize), eyeOffset_(kEyeOffset * sceneSize),
      delta_(DeltaFormFactors::forResolution(resolution)) {
  RAD_CHECK(sceneSize > 0);
  faces_[0] = std::make_unique<raster::Target>(resolution, resolution, true, false);
  for (int f = 1; f < 5; ++f)
    faces_[f] = std::make_unique<raster::Target>(resolution, resolution / 2, true, false);
  const size_t elements = geometry.elementCount();
  excluded_.assign(elements, 0);
  accumulator_.assign(elements, 0.0);
  seen_.resize(elements);
}

Hemicube::Hemicube(const FlatRegions& regions, int resolution, double sceneSize)
    : Hemicube(regions.drawn(), resolution, sceneSize) {
  regions_ = &regions;
  accumulator_.assign(regions.elementCount(), 0.0);
  seen_.resize(regions.elementCount());
}

Hemicube::~Hemicube() = default;

void Hemicube::setCulling(HemicubeCulling culling) {
  if (culling == HemicubeCulling::Auto)
    culling = hierarchy_ && cullingPays(geometry_, near_ / kNearPlane) ? HemicubeCulling::Hidden
                                                                        : HemicubeCulling::None;
  if (culling != HemicubeCulling::None) RAD_CHECK(hierarchy_ != nullptr || geometry_.elementCount() == 0);
  culling_ = culling;
  const size_t elements = geometry_.elementCount();
  if (culling_ != HemicubeCulling::None && pendingAt_.size() != elements) {
    pendingAt_.resize(elements);
    pendingSet_.resize(elements);
  }
}

bool Hemicube::cullingPays(const HemicubeGeometry& geometry, double sceneSize) {
  {
    std::lock_guard<std::mutex> lock(geometryMutex());
    if (geometry.cullingPays_ >= 0) return geometry.cullingPays_ == 1;
  }
  // Probe cubes from element centroids spread evenly over the element numbers (surface by
  // surface), each its own element excluded, as a shooter's.
  Hemicube probe(geometry, kProbeResolution, sceneSize);
  probe.setCulling(HemicubeCulling::Hidden);
  const size_t elements = geometry.elementCount();
  FormFactors ff;
  double sorted = 0;
  for (size_t k = 0; k < kProbes; ++k) {
    const size_t e = (2 * k + 1) * elements / (2 * kProbes);
    const uint32_t* c = geometry.indices.data() + 3 * e;
    const glm::dvec3 centroid = (geometry.positions[c[0]] + geometry.positions[c[1]] + geometry.positions[c[2]]) / 3.0;
    probe.compute(centroid, geometry.normals[e], hemicubeRotation(0, e, 0), ff, {int(e)});
    sorted += double(probe.sortedCount_);
  }
  const bool pays = sorted < kCullingPaysBelow * double(kProbes) * double(elements);
  std::lock_guard<std::mutex> lock(geometryMutex());
  geometry.cullingPays_ = pays;
  return pays;
}

void Hemicube::compute(const glm::dvec3& x, const glm::dvec3& n, double rotation,
                       FormFactors& out, const std::vector<int>& excluded) {
  prepare(x, n, rotation, excluded);
  drawBatches(false);
  if (regions_)
    accumulateLocated(out);
  else
    accumulate(out);
}

double Hemicube::nearest() const {
  // Reversed depth is near/w, w the distance along the face's axis: the nearest shows the
  // largest depth over the direction's length. The sky's pixels keep depth 0.
  float largest = 0;
  for (size_t f = 0; f < 5; ++f) {
    const raster::Target& face = *faces_[f];
    const float* perLength = (f == 0 ? delta_.topPerLength : delta_.sidePerLength).data();
    for (size_t k = 0; k < face.depth.size(); ++k) largest = std::max(largest, perLength[k] * face.depth[k]);
  }
  return largest > 0 ? near_ / double(largest) : std::numeric_limits<double>::infinity();
}

void Hemicube::prepare(const glm::dvec3& x, const glm::dvec3& n, double rotation,
                       const std::vector<int>& excluded) {
  if (culling_ == HemicubeCulling::Auto) setCulling(HemicubeCulling::Auto);
  frame_ = HemicubeFrame::make(x, n, rotation, eyeOffset_);
  if (++stamp_ == 0) {  // wrapped: forget every old stamp
    std::fill(excluded_.begin(), excluded_.end(), 0u);
    stamp_ = 1;
  }
  if (regions_)
    excludedElements_ = excluded;
  else
    for (int e : excluded) excluded_[size_t(e)] = stamp_;
  counts_ = HemicubeCounts();
  for (int f = 0; f < 5; ++f) {
    FaceDraw& draw = draws_[size_t(f)];
    draw.clip.clear(), draw.indices.clear(), draw.ids.clear(), draw.batches.clear();
    drawnBatches_[size_t(f)] = 0;
    faces_[f]->clearDepth(0.0f);
    faces_[f]->clearItem();
  }
  pending_.clear();
  sortedCount_ = 0;
  if (culling_ == HemicubeCulling::None)
    sortAll();
  else if (hierarchy_)
    traverse();
  for (const FaceDraw& draw : draws_) counts_.drawn += draw.ids.size();
  counts_.batches = draws_[0].batches.size();
}

uint32_t Hemicube::facesShowing(uint32_t shared) {
  if (shared & kBelowBase) return 0;
  uint32_t faces = 0;
  for (int f = 0; f < 5; ++f) faces |= uint32_t(((shared >> (5 * f)) & 31u) == 0) << f;
  return faces;
}

bool Hemicube::twinShows(uint32_t e, const glm::dvec3& normal, const glm::dvec3& corner) const {
  return !geometry_.twoSided.empty() && geometry_.twoSided[e] && !(glm::dot(normal, frame_.eye - corner) > 0);
}

uint32_t Hemicube::itemId(uint32_t e, const glm::dvec3& normal, const glm::dvec3& corner) const {
  // Elements seen from behind occlude but receive nothing; so do the excluded ones.
  if (excluded_[e] == stamp_) return kOccluder;
  return glm::dot(normal, frame_.eye - corner) > 0 ? e : kOccluder;
}

void Hemicube::sortAll() {
  // Often half the scene is behind the point, and most of the rest shows on one face only.
  // Three linear passes: the faces of each triangle (and so of its corners), then each
  // face's vertices, then its indices.
  const auto& P = geometry_.positions;
  const auto& I = geometry_.indices;
  const size_t elements = geometry_.elementCount(), vertices = P.size();
  if (local_.size() != vertices) {
    local_.resize(vertices), outside_.resize(vertices), needed_.assign(vertices, 0);
    slot_.resize(5 * vertices), facesOf_.resize(elements);
  }
  for (size_t i = 0; i < vertices; ++i) {
    const glm::dvec3 p = frame_.local(P[i]);
    local_[i] = {float(p.x), float(p.y), float(p.z)};
    outside_[i] = outsidePlanes(local_[i][0], local_[i][1], local_[i][2]);
  }
  std::array<size_t, 5> triangles{};
  for (size_t e = 0; e < elements; ++e) {
    const uint32_t a = I[3 * e], b = I[3 * e + 1], c = I[3 * e + 2];
    uint32_t faces = facesShowing(outside_[a] & outside_[b] & outside_[c]);
    if (faces && twinShows(uint32_t(e), geometry_.normals[e], P[a])) faces = 0;
    for (int f = 0; f < 5; ++f) triangles[size_t(f)] += (faces >> f) & 1u;
    facesOf_[e] = uint8_t(faces);
    needed_[a] |= uint8_t(faces), needed_[b] |= uint8_t(faces), needed_[c] |= uint8_t(faces);
  }
  placeNeeded();
  emitAll(triangles);
  sortedCount_ = elements;
}

void Hemicube::placeNeeded() {
  const float near = float(near_);
  const size_t vertices = local_.size();
  for (size_t v = 0; v < vertices; ++v) {
    if (!needed_[v]) continue;
    for (uint32_t faces = needed_[v]; faces; faces &= faces - 1) {
      const int f = __builtin_ctz(faces);
      FaceDraw& draw = draws_[size_t(f)];
      slot_[size_t(f) * vertices + v] = uint32_t(draw.clip.size());
      const std::array<float, 3>& p = local_[v];
      draw.clip.push_back(faceClip(f, p[0], p[1], p[2], near));
    }
    needed_[v] = 0;
  }
}

void Hemicube::emitAll(const std::array<size_t, 5>& triangles) {
  const auto& P = geometry_.positions;
  const auto& I = geometry_.indices;
  const size_t vertices = local_.size();
  std::array<uint32_t*, 5> index;
  std::array<uint32_t*, 5> id;
  for (size_t f = 0; f < 5; ++f) {
    draws_[f].indices.resize(3 * triangles[f]);
    draws_[f].ids.resize(triangles[f]);
    draws_[f].batches.push_back({0, 0});
    index[f] = draws_[f].indices.data();
    id[f] = draws_[f].ids.data();
  }
  for (size_t e = 0; e < facesOf_.size(); ++e) {
    if (!facesOf_[e]) continue;
    const uint32_t item = itemId(uint32_t(e), geometry_.normals[e], P[I[3 * e]]);
    for (uint32_t faces = facesOf_[e]; faces; faces &= faces - 1) {
      const size_t f = size_t(__builtin_ctz(faces));
      const uint32_t* slot = slot_.data() + f * vertices;
      *index[f]++ = slot[I[3 * e]];
      *index[f]++ = slot[I[3 * e + 1]];
      *index[f]++ = slot[I[3 * e + 2]];
      *id[f]++ = item;
    }
  }
}

void Hemicube::drawBatches(bool forTests) {
  raster::State state;
  state.depthFunc = raster::DepthFunc::Greater;
  state.clipDepth = raster::ClipDepth::ZeroToOne;
  for (size_t f = 0; f < 5; ++f) {
    const FaceDraw& draw = draws_[f];
    raster::Target& target = *faces_[f];
    const size_t before = drawnBatches_[f];
    for (size_t& b = drawnBatches_[f]; b < draw.batches.size(); ++b) {
      const FaceDraw::Batch& batch = draw.batches[b];
      const bool last = b + 1 == draw.batches.size();
      const size_t vertexEnd = last ? draw.clip.size() : draw.batches[b + 1].firstVertex;
      const size_t triangleEnd = last ? draw.ids.size() : draw.batches[b + 1].firstTriangle;
      if (triangleEnd == batch.firstTriangle) continue;
      const uint32_t* indices = draw.indices.empty() ? nullptr : draw.indices.data() + 3 * size_t(batch.firstTriangle);
      raster::drawTriangles(target, state, draw.clip.data() + batch.firstVertex, vertexEnd - batch.firstVertex,
                            indices, triangleEnd - batch.firstTriangle, draw.ids.data() + batch.firstTriangle);
    }
    if (forTests && drawnBatches_[f] != before)
      pyramids_[f].build(target.depth.data(), target.width, target.height);
  }
}

void Hemicube::accumulate(FormFactors& out) {
  out.elements.clear();
  out.factors.clear();
  Slots slots{accumulator_.data(), seen_, uint32_t(geometry_.elementCount())};
  for (int f = 0; f < 5; ++f)
    accumulateFace(faces_[f]->item.data(), (f == 0 ? delta_.top : delta_.side).data(),
                   faces_[f]->item.size(), slots);
  out.sky = slots.sky;
  out.backFaces = slots.back;
  takeAccumulated(out);
}

void Hemicube::accumulateLocated(FormFactors& out) {
  out.elements.clear();
  out.factors.clear();
  const uint32_t drawn = uint32_t(geometry_.elementCount());
  double sky = 0, back = 0;
  uint32_t hint = 0;  // where the last search ended
  for (int f = 0; f < 5; ++f) {
    const raster::Target& face = *faces_[f];
    const double* delta = (f == 0 ? delta_.top : delta_.side).data();
    // The world direction of pixel (i, j) is affine in its centre's device coordinates.
    auto world = [&](const glm::dvec3& d) { return frame_.u * d.x + frame_.v * d.y + frame_.n * d.z; };
    const glm::dvec3 origin = world(faceDirection(f, 0.0, 0.0));
    const glm::dvec3 dx = world(faceDirection(f, 1.0, 0.0)) - origin, dy = world(faceDirection(f, 0.0, 1.0)) - origin;
    const double sx = 2.0 / face.width, sy = 2.0 / face.height;
    const glm::dvec3 step = dx * sx;
    // A run starts its search from the element found in the row below.
    below_.assign(size_t(face.width), 0);
    for (int j = 0, k = 0; j < face.height; ++j) {
      const glm::dvec3 rowStart = origin + dy * ((j + 0.5) * sy - 1) + dx * (0.5 * sx - 1);
      // Along the row, a run of pixels of one region walks its plane (RowWalk).
      int32_t run = 0;
      int runStart = 0;
      FlatRegions::RowWalk walk{};
      for (int i = 0; i < face.width; ++i, ++k) {
        const uint32_t id = face.item[size_t(k)];
        if (id >= drawn) {
          (id == raster::kNoItem ? sky : back) += delta[k];
          continue;
        }
        const int32_t shows = regions_->shows(id);
        uint32_t e = uint32_t(shows);
        if (shows < 0) {
          if (shows != run) {
            run = shows, runStart = i;
            walk = regions_->rowWalk(shows, frame_.eye, rowStart + step * double(i), step);
            hint = below_[size_t(i)];
          }
          const FlatRegions::Located found = regions_->locate(shows, walk.at(i - runStart), hint);
          e = found.element;
          below_[size_t(i)] = hint = found.slot;
          ++counts_.located;
        }
        accumulator_[e] += delta[k];
        seen_.insert(e);
      }
    }
  }
  // The excluded elements (a shooter's own) receive nothing: what they were given is seen
  // as from behind.
  for (int e : excludedElements_) {
    back += accumulator_[size_t(e)];
    accumulator_[size_t(e)] = 0;
  }
  out.sky = sky;
  out.backFaces = back;
  takeAccumulated(out);
}

void Hemicube::takeAccumulated(FormFactors& out) {
  seen_.drain([&](uint32_t e) {
    if (accumulator_[e] != 0) {
      out.elements.push_back(int(e));
      out.factors.push_back(accumulator_[e]);
    }
    accumulator_[e] = 0;
  });
}

double hemicubeRotation(uint64_t seed, uint64_t shooter, uint64_t sample) {
  // SplitMix64 finaliser over the three keys: cheap, well mixed, and the same everywhere.
  auto mix = [](uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  uint64_t h = mix(mix(mix(seed) ^ shooter) ^ sample);
  return double(h >> 11) * 0x1.0p-53;
}

}  // namespace rad
