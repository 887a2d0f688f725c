#pragma once
// Adaptive subdivision: elements are bisected where the direct light, computed at their
// vertices by rays, changes visibly across them: their vertices see different parts of an
// emitter (a penumbra) or show values more than a contrast threshold apart.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/light/direct_light.h"
#include "radiosity/settings.h"

namespace rad {


/// A vertex is in a gap when this share of its short rays meet a surface: all of them (a floor
/// point 6 mm under a sofa). At the foot of a wall about a half do, in a room's corner three
/// quarters, and those are no gaps; asking for 7 of 8 instead, a corner's jittered rays made it
/// one by chance where the room is turned to the axes (about 1 in 7 at 45°). An element with a
/// corner in a gap and another not spans the gap's mouth.
constexpr double kInGap = 1.0;
/// The rays that look for a gap keep within this angle of the normal, so that every one of them
/// meets the far side of a gap narrower than half the reach: past it they graze that side and
/// leave the reach before meeting it, by chance.
constexpr double kGapConeDeg = 60;

/// Under the floor (AdaptiveOptions::minElementEdge), an element whose light changes across it
/// by kSharpContrast times the contrast (a shadow's sharp edge, a crease lit on one side) is
/// still bisected, down to elements kSharpRefinement times shorter: a thin strip of light
/// beside an overhang stays as narrow as it is instead of smeared over a floor-sized element.
constexpr double kSharpContrast = 8;
constexpr double kSharpRefinement = 4;

struct AdaptiveOptions {
  double minElementEdge = 0;      ///< elements whose longest edge is this or less stay whole, but for sharp changes
  double contrast = kDefaultContrast;
  double exposure = 0;            ///< 0: estimated from the direct light (estimateExposure)
  int maxRounds = 64;
  long maxElements = 0;           ///< refinement stops once the mesh has this many (0: no cap)
  /// Gaps narrower than this are looked for (0: none): an element across the mouth of one (the
  /// floor where a sofa standing 6 mm above it ends, a ceiling round a fixture 9 mm under it)
  /// is bisected too, the indirect light falling off there within centimetres.
  double gapReach = 0;
};

struct AdaptiveStats {
  int rounds = 0;                 ///< rounds that bisected something
  int elementsBefore = 0, elementsAfter = 0;
  int marked = 0;                 ///< elements marked over all rounds
  double exposure = 0;            ///< the exposure the contrast was judged at
  double seconds = 0;
};

/// How the result will most likely be shown, before it is solved: the ambient light the
/// direct light will become, Σ A·D / ΣA / (1 − ρ̄) (Cohen et al. 1988), each element showing
/// D + ρ·ambient; and the exposure result.h's rule gives that.
struct DisplayEstimate {
  double exposure = 1;
  glm::dvec3 ambient{0.0};
};
DisplayEstimate estimateDisplay(const PatchMesh& mesh, const DirectLight& light);

/// The direct light at edge midpoints already computed, by edge (its end vertices): when an
/// edge is split, its new vertex takes it over.
using MidpointLight = std::unordered_map<uint64_t, VertexLight>;

/// The elements that need refining: longest edge above options.minElementEdge (above a
/// kSharpRefinement-th of it, for a change of kSharpContrast times the contrast only), and either
/// - at the midpoint of one of their edges, the direct light differs from what Gouraud
///   shading shows there (the mean of the edge's ends) by more than options.contrast on
///   display (display units, with the ambient estimate added): a smooth falloff, which
///   linear interpolation follows, is left alone; or
/// - two of their vertices see different samples on an emitter, and the light through the
///   samples one sees and the other does not is more than options.contrast on display
///   (a shadow boundary crossing the element); or
/// - with options.gapReach, one of its corners is in a gap and another not (kInGap, of the
///   rays DirectLight::surfacesWithin casts that far): the element spans a gap's mouth.
/// Midpoints are computed by rays once and kept in `midpoints`. With `among`, only those
/// elements are looked at (the others are as they were when last looked at).
/// `enclosure`: per vertex, with options.gapReach, the share of its rays that met a surface.
std::vector<int> elementsToRefine(const PatchMesh& mesh, DirectLight& light,
                                  const DisplayEstimate& shown, const AdaptiveOptions& options,
                                  MidpointLight& midpoints, const std::vector<double>& enclosure,
                                  const std::vector<int>* among = nullptr);

/// Refines the mesh until no element needs it (or maxRounds): each round bisects the marked
/// elements (conforming, mesh/refine.h) and casts rays from the new vertices only.
AdaptiveStats refineAdaptively(PatchMesh& mesh, DirectLight& light, const AdaptiveOptions& options);

}  // namespace rad
