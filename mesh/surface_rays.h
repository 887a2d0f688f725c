#pragma once
// Rays against a list of polygons, for choices made once per scene (the default camera): the
// nearest polygon a ray meets and which side of it, through a hierarchy of the polygons' boxes.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/scene/geometry.h"
#include "mesh/scene/scene.h"

namespace rad {

/// What a ray met.
struct RayHit {
  double t = 0;        ///< distance along the ray (scene units for a unit direction)
  int polygon = -1;    ///< index into the polygons given
  bool front = false;  ///< met from its lit side, or a two-sided polygon
};

/// The first polygon along a ray, among polygons kept by reference (they must outlive it).
class SurfaceRays {
 public:
  /// Indexes `polygons` (a non-planar one as its best-fit plane); twoSided[i] says whether
  /// polygon i is lit on both sides. Zero-area polygons are never met.
  SurfaceRays(const std::vector<Polygon>& polygons, const std::vector<bool>& twoSided);

  /// The nearest polygon the ray from `origin` along `dir` meets at t > after (>= 0); with
  /// `throughBacks` the backs of one-sided polygons are passed, as a renderer culling back faces
  /// would.
  std::optional<RayHit> firstHit(const glm::dvec3& origin, const glm::dvec3& dir, bool throughBacks,
                                 double after = 0) const;

 private:
  struct Target {
    PlaneFrame frame;   ///< a zero normal for a zero-area polygon
    glm::dvec3 lo, hi;  ///< the polygon's box, widened by round-off
    bool twoSided = false;
  };
  /// A box over the targets order_[begin, end): a leaf, or the parent of two nodes.
  struct Node {
    glm::dvec3 lo, hi;
    int begin = 0, end = 0;
    int children[2] = {-1, -1};
  };
  /// A ray as the search carries it.
  struct Ray {
    glm::dvec3 origin, dir, inverse;
    bool throughBacks = false;
    double after = 0;
  };

  int addNode(int begin, int end);
  void search(int node, const Ray& ray, std::optional<RayHit>& best) const;
  bool meets(int i, const Ray& ray, double& t) const;
  RayHit hit(int i, const Ray& ray, double t) const;

  const std::vector<Polygon>& polygons_;
  std::vector<Target> targets_;
  std::vector<int> order_;  ///< target indices, grouped by node
  std::vector<Node> nodes_;  ///< nodes_[0] is the root
};

}  // namespace rad
