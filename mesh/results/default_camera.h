#pragma once
// The camera a scene or a result gets when it has none: one that sees what the scene is.
// Rays from the centre of the bounding box towards 9 points on each of its 6 faces (passing the
// backs of one-sided surfaces) say what the scene is, "up" being +y:
//  - a closed room (no face of the box open): stand inside at eye height (1.6 m, at most 0.8 of
//    the room's height; 0.6 of it when the units are unknown) at the free floor point nearest
//    the middle of the free floor, looking horizontally at the main light (the emitting surface
//    of most power), or, when that light is more than 45° overhead or there is none, along the
//    deepest of 8 horizontal directions; a 60° field of view;
//  - an open box (exactly one face open, where most of its rays escape): look into it from
//    outside through that face, on the axis through the box's centre, from where the face fills
//    a 45° view;
//  - anything else, an object: from the raised diagonal (1, 0.6, 1), its bounding sphere filling
//    a 45° view.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/results/result_file.h"
#include "mesh/scene/scene.h"

namespace rad {

/// What a default camera is chosen from.
struct ViewGeometry {
  std::vector<Polygon> polygons;
  std::vector<bool> twoSided;              ///< per polygon: lit on both sides
  std::optional<glm::dvec3> light;         ///< the centre of the main light, if there is one
  std::optional<double> unitsPerMetre;     ///< scene units in a metre, when known
};

/// Scene units in a metre for a scene's `units` ("mm" 1000, "cm", "m", "km", "in", "ft", "yd" and
/// their long names, any case); nothing for an empty or unknown unit.
std::optional<double> unitsPerMetre(const std::string& units);

/// The scene's polygons, their sides, its units and its main light: the emitting surface whose
/// luminance times area is largest, at its area-weighted centre.
ViewGeometry viewGeometry(const Scene& scene);

/// The result's triangles (one-sided; units unknown) and its most lit part: the area-weighted
/// centre of the faces of the brightest face's surface that are at least half as bright.
ViewGeometry viewGeometry(const ResultFile& result);

/// The camera for the geometry, as the header says; needs at least one polygon.
Camera defaultCamera(const ViewGeometry& geometry);

/// defaultCamera of the scene's viewGeometry.
Camera defaultCamera(const Scene& scene);

/// defaultCamera of the result's viewGeometry; for a result without faces, defaultCamera of its
/// bounding box (mesh/scene/camera.h).
Camera defaultCamera(const ResultFile& result);

}  // namespace rad
