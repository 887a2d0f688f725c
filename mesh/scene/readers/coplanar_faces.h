#pragma once
// The faces of a triangulated mesh file (glTF carries nothing but triangles) merged back into
// the planar polygons they were cut from, so that a wall exported as two triangles is meshed
// as the quad it is, not as two thin triangles.
#include <vector>

#include "mesh/scene/scene.h"

namespace rad {

/// The faces (outer rings; a face with holes passes through as it is) with every region of
/// edge-adjacent faces that lie in one plane (within kPlanarity of its extent) and face the
/// same way replaced by one polygon: its boundary as the outer ring, any inner boundaries as
/// holes. Corners are shared by exact position. A region whose boundary touches itself at a
/// corner, or meets an edge of three or more faces, keeps its faces. Order: merged polygons
/// and kept faces in the order of each region's first face.
std::vector<Polygon> mergeCoplanarFaces(const std::vector<Polygon>& faces);

}  // namespace rad
