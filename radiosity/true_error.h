#pragma once
// The true error: what a viewer shows (the Gouraud vertex radiosity interpolated at surface
// points) against an independent reference (mesh/results/reference_points.h, from the path tracer),
// never against the solver's own fixed point.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/patch_mesh.h"
#include "mesh/results/reference_points.h"
#include "mesh/scene/scene.h"

namespace rad {

/// A reference channel below this share of the brightest reference value in that channel on a
/// non-emitting surface is skipped (a relative error of near-black means little).
constexpr double kDarkShare = 0.01;
/// A reference point farther than this (share of the scene's size) from every element of its
/// surface is not in the result (cut away): it shows nothing there, a relative error of −1.
constexpr double kOnResult = 1e-3;

/// The relative error (shown − reference) / reference over the points and channels used.
struct ErrorSummary {
  double rms = 0;                          ///< over every used (point, channel)
  glm::dvec3 rmsRgb{0.0}, meanRgb{0.0};    ///< per channel
  double referenceNoise = 0;               ///< RMS of the reference's own SE / B over the same
  int used = 0, skipped = 0;               ///< (point, channel) pairs
  int worstPoint = -1;                     ///< largest |relative error| in any channel
  double worst = 0;                        ///< its relative error (signed)
  glm::dvec3 worstShown{0.0};              ///< what is shown there
  struct Surface {
    std::string name;
    int points = 0, channels = 0;  ///< channels: those used (not skipped as dark)
    double rms = 0, mean = 0;       ///< over the channels used; 0 when none was
  };
  std::vector<Surface> perSurface;  ///< in order of first appearance among the points
};

/// Reference points located on a result mesh once, then measured against any vertex values.
class TrueError {
 public:
  /// Locates each point on the elements of its surface (by name) facing its way. Throws
  /// InputError, naming `source` (the reference file), when a point names a surface the scene
  /// does not have: a reference of another scene.
  TrueError(const PatchMesh& mesh, const Scene& scene, std::vector<ReferencePoint> points,
            const std::string& source = "reference");

  /// The error of the given vertex values (what Gouraud shading interpolates).
  ErrorSummary measure(const std::vector<glm::dvec3>& vertexValue) const;
  /// The values shown at the points.
  std::vector<glm::dvec3> shown(const std::vector<glm::dvec3>& vertexValue) const;

  const std::vector<ReferencePoint>& points() const { return points_; }
  int notInResult() const { return notInResult_; }

 private:
  struct Location {
    int vertex[3] = {-1, -1, -1};
    glm::dvec3 weight{0.0};
  };
  /// Locates point i at the nearest point of the candidate elements facing its way (where_[i]);
  /// returns its distance (HUGE_VAL when none faces it).
  double locate(const PatchMesh& mesh, const std::vector<int>& candidates, size_t i);

  std::vector<ReferencePoint> points_;
  std::vector<Location> where_;
  glm::dvec3 floor_{0.0};
  int notInResult_ = 0;
};

}  // namespace rad
