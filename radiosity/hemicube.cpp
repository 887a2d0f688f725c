#include "radiosity/hemicube.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "display/raster.h"
#include "mesh/error.h"
#include "mesh/patch_mesh.h"
#include "radiosity/point_polygon.h"

namespace rad {
namespace {

/// Item id of a triangle that occludes but receives nothing (seen from behind, or excluded).
constexpr uint32_t kOccluder = raster::kNoItem - 1;

/// Face f's clip-space coordinates of a point with local coordinates (a, b, c) along (u, v, n).
/// Depth is reversed with z in [0, w] (z = near, so depth = near/distance, test GREATER): a
/// 32-bit float then resolves distance to ~1e-7 relative at every range, so the near plane can
/// sit very close. Side faces show only the upper half (c ≥ 0): y maps c ∈ [0, w] onto [-w, w].
inline glm::vec4 faceClip(int f, const std::array<float, 3>& p, float near) {
  float a = p[0], b = p[1], c = p[2];
  switch (f) {
    case 0: return {a, b, near, c};
    case 1: return {b, 2 * c - a, near, a};
    case 2: return {-b, 2 * c + a, near, -a};
    case 3: return {-a, 2 * c - b, near, b};
    default: return {a, 2 * c + b, near, -b};
  }
}

/// The frustum planes of the five faces that local point (a, b, c) lies strictly outside of:
/// bits 5f..5f+4 for face f. A triangle whose corners share a bit of face f shows nothing on
/// it (its projection lies beyond that edge of the face, or behind the eye), so the face need
/// not draw it. Face f's planes are those of faceClip(f): |x| ≤ w, |y| ≤ w, w > 0.
inline uint32_t outsidePlanes(const std::array<float, 3>& p) {
  const float a = p[0], b = p[1], c = p[2];
  auto face = [](float x, float w, float c) {  // a side face: |x| ≤ w, 0 ≤ c ≤ w
    return uint32_t(x > w) | uint32_t(-x > w) << 1 | uint32_t(c > w) << 2 | uint32_t(c < 0) << 3 |
           uint32_t(w <= 0) << 4;
  };
  const uint32_t top = uint32_t(a > c) | uint32_t(-a > c) << 1 | uint32_t(b > c) << 2 |
                       uint32_t(-b > c) << 3 | uint32_t(c <= 0) << 4;
  return top | face(b, a, c) << 5 | face(b, -a, c) << 10 | face(a, b, c) << 15 | face(a, -b, c) << 20;
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

/// The accumulator's slots: the elements, then sky, then back faces (every item id past the
/// elements but the sky's is an occluder's back); `seen` is the bit set of the slots written.
struct Slots {
  double* acc;
  uint64_t* seen;
  uint32_t n, skySlot, backSlot;

  uint32_t slot(uint32_t id) const { return id < n ? id : id == raster::kNoItem ? skySlot : backSlot; }
  void add(uint32_t id, double value) {
    const uint32_t s = slot(id);
    acc[s] += value;
    seen[s >> 6] |= uint64_t(1) << (s & 63);
  }
  /// Slot s's sum, the slot cleared.
  double take(uint32_t s) {
    const double value = acc[s];
    acc[s] = 0;
    seen[s >> 6] &= ~(uint64_t(1) << (s & 63));
    return value;
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

HemicubeGeometry HemicubeGeometry::fromMesh(const PatchMesh& mesh) {
  HemicubeGeometry g;
  for (auto v : mesh.mesh.vertices()) g.positions.push_back(PatchMesh::toGlm(mesh.mesh.point(v)));
  for (auto f : mesh.mesh.faces()) {
    for (auto v : mesh.mesh.fv_range(f)) g.indices.push_back(uint32_t(v.idx()));
    g.normals.push_back(mesh.normal(f.idx()));
  }
  return g;
}

int HemicubeGeometry::addTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  uint32_t base = uint32_t(positions.size());
  positions.insert(positions.end(), {a, b, c});
  indices.insert(indices.end(), {base, base + 1, base + 2});
  normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
  return int(normals.size()) - 1;
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
  slot = std::move(d);
  return *slot;
}

Hemicube::Hemicube(const HemicubeGeometry& geometry, int resolution, double sceneSize)
    : geometry_(geometry), resolution_(resolution), near_(kNearPlane * sceneSize),
      eyeOffset_(kEyeOffset * sceneSize), delta_(DeltaFormFactors::forResolution(resolution)) {
  RAD_CHECK(sceneSize > 0);
  faces_[0] = std::make_unique<raster::Target>(resolution, resolution, true, false);
  for (int f = 1; f < 5; ++f)
    faces_[f] = std::make_unique<raster::Target>(resolution, resolution / 2, true, false);
  ids_.resize(geometry.elementCount());
  local_.resize(geometry.positions.size());
  outside_.resize(geometry.positions.size());
  needed_.assign(geometry.positions.size(), 0);
  faces_of_.resize(geometry.elementCount());
  slot_.resize(5 * geometry.positions.size());
  accumulator_.assign(geometry.elementCount() + 2, 0.0);
  seen_.assign((geometry.elementCount() + 2 + 63) / 64, 0);
}

Hemicube::~Hemicube() = default;

void Hemicube::compute(const glm::dvec3& x, const glm::dvec3& n, double rotation,
                       FormFactors& out, const std::vector<int>& excluded) {
  prepare(x, n, rotation, excluded);
  renderFaces();
  accumulate(out);
}

void Hemicube::prepare(const glm::dvec3& x, const glm::dvec3& n, double rotation,
                       const std::vector<int>& excluded) {
  // A frame turned about n by 2π·rotation, from a tangent least aligned with n.
  glm::dvec3 t = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  glm::dvec3 u0 = glm::normalize(glm::cross(n, t)), v0 = glm::cross(n, u0);
  double angle = 2 * M_PI * rotation;
  glm::dvec3 u = std::cos(angle) * u0 + std::sin(angle) * v0;
  glm::dvec3 v = glm::cross(n, u);
  glm::dvec3 eye = x + eyeOffset_ * n;

  // Elements seen from behind occlude but receive nothing; so do the excluded ones.
  const auto& P = geometry_.positions;
  const auto& I = geometry_.indices;
  for (size_t e = 0; e < ids_.size(); ++e)
    ids_[e] = glm::dot(geometry_.normals[e], eye - P[I[3 * e]]) > 0 ? uint32_t(e) : kOccluder;
  for (int e : excluded) ids_[e] = kOccluder;

  // Local coordinates in double, relative to the eye, then float for the raster.
  for (size_t i = 0; i < P.size(); ++i) {
    glm::dvec3 d = P[i] - eye;
    local_[i] = {float(glm::dot(d, u)), float(glm::dot(d, v)), float(glm::dot(d, n))};
    outside_[i] = outsidePlanes(local_[i]);
  }
  sortToFaces();
}

void Hemicube::sortToFaces() {
  // Only triangles reaching above the base plane can show on any face (often half the scene
  // is behind the point), and most of those on one face only. Each face gets its own
  // triangles, in element order, and the clip-space vertices they use: first the faces of
  // each triangle (and so of its corners), then each face's vertices, then its indices.
  const auto& I = geometry_.indices;
  const size_t elements = ids_.size(), vertices = local_.size();
  std::array<size_t, 5> triangles{};
  for (size_t e = 0; e < elements; ++e) {
    const uint32_t a = I[3 * e], b = I[3 * e + 1], c = I[3 * e + 2];
    const uint32_t shared = outside_[a] & outside_[b] & outside_[c];
    // Bit 4 of the top face: no corner above the base plane.
    uint32_t faces = 0;
    if (!(shared & 16u))
      for (int f = 0; f < 5; ++f) {
        const uint32_t shows = ((shared >> (5 * f)) & 31u) == 0;
        faces |= shows << f;
        triangles[size_t(f)] += shows;
      }
    faces_of_[e] = uint8_t(faces);
    needed_[a] |= uint8_t(faces), needed_[b] |= uint8_t(faces), needed_[c] |= uint8_t(faces);
  }
  const float near = float(near_);
  for (auto& draw : draws_) draw.clip.clear();
  for (size_t v = 0; v < vertices; ++v) {
    if (!needed_[v]) continue;
    for (uint32_t faces = needed_[v]; faces; faces &= faces - 1) {
      const int f = __builtin_ctz(faces);
      FaceDraw& draw = draws_[size_t(f)];
      slot_[size_t(f) * vertices + v] = uint32_t(draw.clip.size());
      draw.clip.push_back(rad::faceClip(f, local_[v], near));
    }
    needed_[v] = 0;
  }
  std::array<uint32_t*, 5> index;
  std::array<uint32_t*, 5> id;
  for (size_t f = 0; f < 5; ++f) {
    draws_[f].indices.resize(3 * triangles[f]);
    draws_[f].ids.resize(triangles[f]);
    index[f] = draws_[f].indices.data();
    id[f] = draws_[f].ids.data();
  }
  for (size_t e = 0; e < elements; ++e)
    for (uint32_t faces = faces_of_[e]; faces; faces &= faces - 1) {
      const size_t f = size_t(__builtin_ctz(faces));
      const uint32_t* slot = slot_.data() + f * vertices;
      *index[f]++ = slot[I[3 * e]];
      *index[f]++ = slot[I[3 * e + 1]];
      *index[f]++ = slot[I[3 * e + 2]];
      *id[f]++ = ids_[e];
    }
}

void Hemicube::renderFaces() {
  raster::State state;
  state.depthFunc = raster::DepthFunc::Greater;
  state.clipDepth = raster::ClipDepth::ZeroToOne;
  for (int f = 0; f < 5; ++f) {
    const FaceDraw& draw = draws_[size_t(f)];
    raster::Target& target = *faces_[f];
    target.clearDepth(0.0f);
    target.clearItem();
    if (draw.ids.empty()) continue;
    raster::drawTriangles(target, state, draw.clip.data(), draw.clip.size(), draw.indices.data(),
                          draw.ids.size(), draw.ids.data());
  }
}

void Hemicube::accumulate(FormFactors& out) {
  out.elements.clear();
  out.factors.clear();
  const uint32_t n = uint32_t(geometry_.elementCount());
  Slots slots{accumulator_.data(), seen_.data(), n, n, n + 1};
  for (int f = 0; f < 5; ++f)
    accumulateFace(faces_[f]->item.data(), (f == 0 ? delta_.top : delta_.side).data(),
                   faces_[f]->item.size(), slots);
  out.sky = slots.take(slots.skySlot);
  out.backFaces = slots.take(slots.backSlot);
  // Ascending element order, from the bit set of the slots seen.
  for (size_t w = 0; w < seen_.size(); ++w) {
    for (uint64_t bits = seen_[w]; bits; bits &= bits - 1) {
      const uint32_t e = uint32_t(w * 64 + size_t(__builtin_ctzll(bits)));
      if (accumulator_[e] != 0) {
        out.elements.push_back(int(e));
        out.factors.push_back(accumulator_[e]);
      }
      accumulator_[e] = 0;
    }
    seen_[w] = 0;
  }
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
