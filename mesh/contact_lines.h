#pragma once
// Internal to buildPatchMesh: cutting the planar pieces along the lines where other pieces
// touch or pierce them, and leaving out what those enclose.
#include <set>
#include <utility>
#include <vector>

#include "mesh/base/stage_times.h"
#include "mesh/patch_mesh.h"
#include "mesh/planar_pieces.h"

namespace rad::meshing {

/// What cutting at contacts did.
struct ContactCuts {
  /// The edges (point ids, lower first) of contact lines that run across a piece.
  std::set<std::pair<int, int>> across;
  std::vector<CutAway> cutAway;  ///< what was left out
  int lines = 0;                 ///< contact lines found
};

/// Cuts every piece along the lines where other pieces touch or pierce it (a block standing
/// on a floor, a wall meeting a floor, a box pushed into a wall) and leaves out what they
/// enclose (cutAlongContacts); pieces left out entirely are dropped. New points within the
/// contact tolerance of an existing one are merged with it, so that both pieces at a contact
/// share their points. Adds the time spent finding the lines ("contact lines") and cutting
/// along them ("contact cuts") to `stages`.
ContactCuts cutAtContacts(const Scene& scene, PointTable& table, std::vector<Piece>& pieces,
                          StageTimes& stages);

}  // namespace rad::meshing
