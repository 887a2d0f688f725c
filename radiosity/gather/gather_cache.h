#pragma once
// Which vertices of the mesh the final gather draws render hemicubes: not every one. What a
// vertex gathers is the light reflected to it (its direct light is its own rays'), and that
// changes from place to place over distances like that of what the point sees (Ward,
// Rubinstein & Clear 1988, "A ray tracing solution for diffuse interreflection", with the
// harmonic mean distance; here, as Tabellion & Lamorlette 2004, the nearest surface's: a
// vertex beside a gathering one that sees far may have a surface near it that the gathering
// one sees only at the horizon; R from the hemicube's depths, Hemicube::nearest). A vertex
// lying within accuracy·R of gathering vertices of its own surface, facing their way, takes
// their light interpolated, weighted by Ward's 1/ε; the others gather themselves.
//
// The gathering vertices are chosen level by level on grids halving in size, one per cell
// among the vertices no earlier one covers, until each is covered or gathers itself: where
// another surface is near (corners, contacts, the floor under a sofa, small objects close to
// others) R is small and every vertex gathers; an open floor gathers at a few. The choice
// depends on the mesh alone, not on the light or the number of threads.
#include <functional>
#include <utility>
#include <vector>

#include "mesh/patch_mesh.h"

namespace rad {

/// The default accuracy (Ward's a): a vertex within this share of a gathering vertex's R
/// interpolates it. 0 gathers at every vertex.
constexpr double kDefaultGatherAccuracy = 0.2;
/// The default GatherOptions::agreement.
constexpr double kDefaultGatherAgreement = 0.05;
/// A gathering vertex's R is held within these shares of the scene size: an open view (sky,
/// far walls) still covers no farther than a room's part.
constexpr double kMaxGatherReach = 1.0 / 8;
/// A gathering vertex covers about this share of its circle of radius accuracy·R by itself
/// (the circles overlap): for estimating how many gather (estimateGather).
constexpr double kGatherCoverShare = 0.5;
/// No vertex interpolates gathering vertices farther away than this share of the element edge
/// (GatherOptions::elementEdge): where the mesh is as fine as the scene is meshed, every vertex
/// gathers (interpolated there, the Cornell box's and the doorway's true errors rose by 0.2–0.4 %
/// at accuracy 0.2–0.4); where a model's own faces are much finer (furniture, mouldings), they share.
constexpr double kGatherFarthestShare = 0.5;
/// The first level's grid cell, as a share of the scene size.
constexpr double kFirstGatherCell = 1.0 / 16;

struct GatherCache {
  /// Per vertex of the mesh: the gathering vertices its gathered light is interpolated from,
  /// weights summing to 1 (a gathering vertex: itself alone; one not asked for: none).
  std::vector<std::vector<std::pair<int, double>>> from;
  /// Per vertex: R where it gathers (0 elsewhere).
  std::vector<double> reach;
  int gathering = 0;  ///< vertices that gather
  int levels = 0;     ///< levels of the choice
  bool complete = true;  ///< false: `render` gave up (deadline, cancelled): `from` is empty
};

/// Renders the hemicubes of vertices `which` and gives each one's Hemicube::nearest in
/// `nearest` (per vertex of the mesh), or returns false to give up.
using GatherRender = std::function<bool(const std::vector<int>& which, std::vector<double>& nearest)>;

/// Chooses which of `candidates` (vertices of `mesh`) gather, rendering their hemicubes by
/// `render` as it goes, and how the others interpolate them. accuracy ≤ 0: every candidate.
/// No vertex interpolates gathering vertices farther than `farthest` away (0: R alone decides).
GatherCache chooseGathering(const PatchMesh& mesh, const std::vector<int>& candidates, double accuracy,
                            double sceneSize, double farthest, const GatherRender& render);

/// The candidates `cache` interpolates from gathering vertices whose `light` (luminance of
/// what each gathers over the progressive start) differs by more than `agreement` of their
/// weighted mean, or from a single one: the light may change between them faster than the
/// cache assumed, so they gather themselves. agreement ≤ 0: none.
std::vector<int> disagreeing(const GatherCache& cache, const std::function<double(int)>& light, double agreement);

/// The largest R a gathering vertex is given: kMaxGatherReach of the scene, and no more than
/// lets it cover `farthest` (if positive).
double maxGatherReach(double sceneSize, double accuracy, double farthest);

/// Ward's weight of a gathering vertex at (p, n) with reach R at a point (q, m) of the same
/// surface: 1/ε − 1/accuracy with ε = |q − p|/R + √(1 − n·m), or 0 where that is not positive
/// or the point lies in front of the gathering one (on a curved surface's far side).
double gatherWeight(const glm::dvec3& p, const glm::dvec3& n, double R, const glm::dvec3& q, const glm::dvec3& m,
                    double accuracy);

}  // namespace rad
