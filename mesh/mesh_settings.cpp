#include "mesh/mesh_settings.h"

namespace rad {

MeshSettings resolveMeshSettings(const Scene& scene, const SolverBlock& flags) {
  const SolverBlock& file = scene.solver;
  MeshSettings m;
  m.maxElementEdge = flags.maxElementEdge.value_or(file.maxElementEdge.value_or(scene.diagonal() / kDefaultElementsPerDiagonal) *
                                                   elementScale(qualityOf(scene, flags)));
  m.maxPatchEdge = flags.maxPatchEdge.value_or(file.maxPatchEdge.value_or(m.maxElementEdge * kDefaultPatchToElement));
  m.cutContacts = flags.cutContacts.value_or(file.cutContacts.value_or(true));
  m.contactGrading = contactGrading(flags.adaptive.value_or(file.adaptive.value_or(true)),
                                    flags.finalGather.value_or(file.finalGather.value_or(true)));
  return m;
}

}  // namespace rad
