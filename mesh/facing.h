#pragma once
// Scene ▸ scene: mesh-file surfaces turned to face the space the light is in. A downloaded model
// may wind a room's walls outwards (Bitterli's Wooden Staircase: its 191 m² of wallpaper face
// out of the house, which its renderer shows because the material is two-sided); a one-sided
// solve would leave them black. Light paths from the emitters say which side of each surface
// the lit space sees.
#include <string>
#include <vector>

#include "mesh/scene/scene.h"

namespace rad {

/// How often light paths from the emitters met a surface on each side.
struct SideHits {
  long front = 0, back = 0;
};

/// What turnToLitSpace changed.
struct FacingRepair {
  std::vector<int> turned;  ///< surfaces some or all of whose faces were turned round
  long turnedFaces = 0;     ///< faces turned round, in all
  std::vector<std::string> warnings;  ///< one per surface turned, naming it
};

/// Light paths: this many from the emitters (area-weighted, cosine-spread from their lit sides),
/// each followed over up to kFacingBounces diffuse bounces off fronts and two-sided surfaces; the
/// back of a one-sided surface ends a path.
constexpr int kFacingPaths = 16384;
constexpr int kFacingBounces = 8;
constexpr long kFacingMinHits = 24;
/// A consistently wound sheet of a one-sided mesh-file surface (faces joined across edges their
/// windings agree on) is turned round when its back is met more than kFacingMinHits times and at
/// least this many times as often as its front: walls wound outwards are met almost only on
/// their backs, a correctly wound object's back only where light slips in through a seam.
/// Sheets, not surfaces: a room's box may wind one wall out and the others in (the Wooden
/// Staircase's wallpaper).
constexpr double kFacingBackRatio = 4;

/// Counts where light paths from the emitters meet each polygon (the same paths every run, so
/// that a solve and its reference turn the same faces) and turns round every sheet of a
/// one-sided mesh-file surface that the lit space sees mostly from its back (kFacingBackRatio),
/// with a warning naming the surface. JSON polygons keep the winding their author gave them.
/// Nothing changes in a scene without emitters.
FacingRepair turnToLitSpace(Scene& scene);

/// Counts only: the hits turnToLitSpace decides on, per polygon of every surface in the scene's
/// order (the surfaces' polygons one after another).
std::vector<SideHits> litSpaceHits(const Scene& scene);

}  // namespace rad
