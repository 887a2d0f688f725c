// The hemicube's visit of the element hierarchy (HemicubeCulling::Hidden): whole
// subtrees below the base plane or hidden behind the batches drawn so far are skipped; the
// elements of the others are placed leaf by leaf and sorted to the faces batch by batch.
#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "radiosity/formfactors/hemicube.h"
#include "radiosity/formfactors/hemicube_culling.h"

namespace rad {
namespace {

/// Subtrees of fewer elements are drawn without testing whether they are hidden.
constexpr uint32_t kFewestTested = 16;
/// The fewest pending elements drawn early for the tests, as a share of a face's pixels
/// (and at least kFewestBatch): each early draw rebuilds the faces' depth pyramids.
constexpr double kBatchPerPixel = 1.0 / 8;
constexpr size_t kFewestBatch = 64;

}  // namespace

void Hemicube::traverse() {
  // Depth first, the nearer child first: the first batches hold what lies around the eye,
  // which hides most of an interior from the subtrees tested after them.
  const auto& nodes = hierarchy_->nodes();
  stack_.assign(1, 0u);
  while (!stack_.empty()) {
    const uint32_t k = stack_.back();
    stack_.pop_back();
    if (culled(k)) continue;
    if (nodes[k].leaf())
      collect(nodes[k]);
    else
      pushChildren(k);
  }
  sortBatch();
}

bool Hemicube::culled(uint32_t k) {
  const ElementHierarchy::Node& node = hierarchy_->nodes()[k];
  if (boxBelowBase(frame_, node.lo, node.hi)) {
    counts_.belowBase += node.count;
    return true;
  }
  if (node.count < kFewestTested) return false;
  if (worthDrawingFirst(node.count)) {
    sortBatch();
    drawBatches(true);
  }
  if (sortedCount_ == 0) return false;  // nothing drawn to hide it
  ++counts_.tested;
  if (!boxHidden(frame_, node.lo, node.hi, {pyramids_, resolution_, near_})) return false;
  counts_.hidden += node.count;
  return true;
}

bool Hemicube::worthDrawingFirst(uint32_t count) const {
  // Drawing early costs a rebuild of the depth pyramids (about the pixels of the cube); it
  // pays when the subtree to test is as large as what waits, or what waits doubles what is
  // drawn (so that the rebuilds stay few).
  const double pixels = double(resolution_) * double(resolution_);
  const size_t fewest = std::max(kFewestBatch, size_t(pixels * kBatchPerPixel));
  return pending_.size() >= fewest && (pending_.size() >= sortedCount_ || count >= pending_.size());
}

void Hemicube::pushChildren(uint32_t k) {
  const auto& nodes = hierarchy_->nodes();
  const uint32_t first = k + 1, second = nodes[k].second;
  auto distance2 = [&](const ElementHierarchy::Node& c) {
    const glm::dvec3 d = glm::max(c.lo - frame_.eye, 0.0) + glm::max(frame_.eye - c.hi, 0.0);
    return glm::dot(d, d);
  };
  const bool firstNearer = distance2(nodes[first]) <= distance2(nodes[second]);
  stack_.push_back(firstNearer ? second : first);
  stack_.push_back(firstNearer ? first : second);
}

void Hemicube::collect(const ElementHierarchy::Node& leaf) {
  // Local coordinates in double, relative to the eye, then float for the raster; the
  // frustum planes of the faces each vertex is outside of.
  const glm::dvec3* positions = hierarchy_->leafPositions().data() + leaf.vertexFirst;
  std::array<std::array<float, 3>, 3 * ElementHierarchy::kLeafSize> local;
  std::array<uint32_t, 3 * ElementHierarchy::kLeafSize> outside;
  for (size_t v = 0; v < leaf.vertexCount; ++v) {
    const glm::dvec3 p = frame_.local(positions[v]);
    local[v] = {float(p.x), float(p.y), float(p.z)};
    outside[v] = outsidePlanes(local[v][0], local[v][1], local[v][2]);
  }
  for (uint32_t i = leaf.first; i < leaf.first + leaf.count; ++i) {
    const std::array<uint8_t, 3>& c = hierarchy_->corners()[i];
    const uint32_t faces = facesShowing(outside[c[0]] & outside[c[1]] & outside[c[2]]);
    if (!faces) continue;
    const uint32_t e = hierarchy_->order()[i];
    if (twinShows(e, hierarchy_->normals()[i], positions[c[0]])) continue;
    pendingAt_[e] = uint32_t(pending_.size());
    Pending& p = pending_.emplace_back();
    for (size_t k = 0; k < 3; ++k) p.corners[k] = local[c[k]];
    p.id = itemId(e, hierarchy_->normals()[i], positions[c[0]]);
    p.faces = faces;
    pendingSet_.insert(e);
  }
}

void Hemicube::sortBatch() {
  // Each face gets the batch's triangles that may show on it, in element order, three
  // vertices each.
  if (pending_.empty()) return;
  for (FaceDraw& draw : draws_)
    draw.batches.push_back({uint32_t(draw.clip.size()), uint32_t(draw.ids.size())});
  const float near = float(near_);
  pendingSet_.drain([&](uint32_t e) {
    const Pending& p = pending_[pendingAt_[e]];
    for (uint32_t faces = p.faces; faces; faces &= faces - 1) {
      const int f = __builtin_ctz(faces);
      FaceDraw& draw = draws_[size_t(f)];
      for (const auto& c : p.corners) draw.clip.push_back(faceClip(f, c[0], c[1], c[2], near));
      draw.ids.push_back(p.id);
    }
  });
  sortedCount_ += pending_.size();
  pending_.clear();
}

}  // namespace rad
