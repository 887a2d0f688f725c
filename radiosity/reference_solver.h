#pragma once
// The full radiosity system from the same shooter samples and hemicubes as the progressive
// solver, solved directly (LU) or by Jacobi and Gauss–Seidel gathering: the reference the
// progressive solution is compared with. Dense: for scenes up to a few thousand elements.
#include <functional>
#include <vector>

#include <Eigen/Dense>
#include <glm/vec3.hpp>

#include "radiosity/shooting/progressive_solver.h"

namespace rad {

class PatchMesh;

/// Largest element count the dense reference accepts (8 000² doubles are 512 MB).
constexpr int kMaxReferenceElements = 8000;

/// G[j][i] = Fᵢⱼ·Aᵢ/Aⱼ: the radiosity element j receives per unit radiosity of element i,
/// before reflection, with Fᵢⱼ from exactly the samples and hemicubes the progressive solver
/// shoots through. The system is (I − diag(ρ)·G)·B = E per channel.
class TransportMatrix {
 public:
  /// Throws InputError when the mesh has more than kMaxReferenceElements elements.
  TransportMatrix(const PatchMesh& mesh, FactorSource& factors, const SolverOptions& options);

  const Eigen::MatrixXd& G() const { return G_; }
  int size() const { return int(G_.rows()); }

  /// The system's own solution by LU decomposition, per channel ("direct" in the numerical
  /// sense, as `solve --fixed-point direct` names it; everywhere else "direct" is the light
  /// straight from the emitters).
  std::vector<glm::dvec3> solveByLU() const;

  /// Called after every sweep with (sweep, B); return false to stop.
  using SweepCallback = std::function<bool(int, const std::vector<glm::dvec3>&)>;
  /// Jacobi gathering from B = E: B ← E + diag(ρ)·G·B, all elements at once.
  void solveJacobi(int maxSweeps, const SweepCallback& callback) const;
  /// Gauss–Seidel gathering: each element gathers with its neighbours' newest values.
  void solveGaussSeidel(int maxSweeps, const SweepCallback& callback) const;

 private:
  Eigen::MatrixXd G_;
  std::vector<glm::dvec3> rho_, E_;
  bool grey_ = false;  ///< one channel solved, copied to the others
};

/// Relative L2 error of element radiosity over non-emitting elements, area weighted:
/// √(Σ Aᵢ‖Bᵢ − Bᵢʳᵉᶠ‖²) / √(Σ Aᵢ‖Bᵢʳᵉᶠ‖²).
double relativeError(const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                     const std::vector<glm::dvec3>& reference);

}  // namespace rad
