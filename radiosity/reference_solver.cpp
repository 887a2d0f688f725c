#include "radiosity/reference_solver.h"
#include "radiosity/settings.h"

#include <algorithm>
#include <cmath>

#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/base/parallel.h"
#include "mesh/patch_mesh.h"

namespace rad {
namespace {

/// Adds the columns of `patch`'s elements to G: the factors of its `samples` shooter samples,
/// computed by `worker` into `ff`.
void addPatchColumns(Eigen::MatrixXd& G, const PatchMesh& mesh, FactorSource& factors, int patch,
                     int samples, FormFactors& ff, int worker) {
  const auto shooters = patchSamples(mesh, patch, samples);
  for (int index = 0; index < int(shooters.size()); ++index) {
    const ShooterSample& s = shooters[index];
    factors.factors(Shooter{patch}, index, s, ff, worker);
    for (size_t k = 0; k < ff.elements.size(); ++k) {
      int j = ff.elements[k];
      for (size_t m = 0; m < s.elements.size(); ++m) {
        int i = s.elements[m];
        G(j, i) += s.weights[m] * ff.factors[k] * mesh.area(i) / mesh.area(j);
      }
    }
  }
}

}  // namespace

TransportMatrix::TransportMatrix(const PatchMesh& mesh, FactorSource& factors,
                                 const SolverOptions& options) {
  const int n = mesh.elementCount();
  if (n > kMaxReferenceElements)
    throw SettingError(inputError("fixed point 'direct'", "a mesh of at most " + std::to_string(kMaxReferenceElements) +
                                                          " elements for the dense full-matrix solution",
                                  std::to_string(n) + " elements (raise solver.max_element_edge, or compare "
                                                      "with an earlier result file)").what());
  G_ = Eigen::MatrixXd::Zero(n, n);
  grey_ = isGrey(mesh);
  rho_.resize(n);
  E_.resize(n);
  for (int e = 0; e < n; ++e) {
    rho_[e] = mesh.reflectance(e);
    E_[e] = mesh.emission(e);
  }
  const SampleCounter count(mesh, options);
  // Workers take whole patches; a patch writes only its own elements' columns.
  std::vector<FormFactors> scratch(size_t(std::max(1, factors.workers())));
  parallelFor(mesh.patches.size(), int(scratch.size()), [&](size_t p, int worker) {
    addPatchColumns(G_, mesh, factors, int(p), count(int(p)), scratch[size_t(worker)], worker);
  });
}

std::vector<glm::dvec3> TransportMatrix::solveByLU() const {
  const int n = size();
  std::vector<glm::dvec3> B(n);
  for (int c = 0; c < (grey_ ? 1 : 3); ++c) {
    Eigen::MatrixXd A = -G_;
    Eigen::VectorXd rhs(n);
    for (int j = 0; j < n; ++j) {
      A.row(j) *= rho_[j][c];
      A(j, j) += 1.0;
      rhs(j) = E_[j][c];
    }
    Eigen::VectorXd x = A.partialPivLu().solve(rhs);
    for (int j = 0; j < n; ++j) B[j][c] = x(j);
  }
  if (grey_)
    for (auto& b : B) b = glm::dvec3(b.x);
  return B;
}

void TransportMatrix::solveJacobi(int maxSweeps, const SweepCallback& callback) const {
  const int n = size();
  Eigen::MatrixXd B(n, 3), E(n, 3), rho(n, 3);
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) E(j, c) = E_[j][c], rho(j, c) = rho_[j][c];
  B = E;
  std::vector<glm::dvec3> out(n);
  for (int sweep = 1; sweep <= maxSweeps; ++sweep) {
    B = E + rho.cwiseProduct(G_ * B);
    for (int j = 0; j < n; ++j) out[j] = {B(j, 0), B(j, 1), B(j, 2)};
    if (!callback(sweep, out)) return;
  }
}

void TransportMatrix::solveGaussSeidel(int maxSweeps, const SweepCallback& callback) const {
  const int n = size();
  std::vector<glm::dvec3> B(E_);
  for (int sweep = 1; sweep <= maxSweeps; ++sweep) {
    for (int j = 0; j < n; ++j) {
      glm::dvec3 gathered(0.0);
      for (int i = 0; i < n; ++i) gathered += G_(j, i) * B[i];  // G's self terms are zero
      B[j] = E_[j] + rho_[j] * gathered;
    }
    if (!callback(sweep, B)) return;
  }
}

double relativeError(const PatchMesh& mesh, const std::vector<glm::dvec3>& B,
                     const std::vector<glm::dvec3>& reference) {
  double num = 0, den = 0;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    if (luminance(mesh.emission(e)) > 0) continue;
    glm::dvec3 d = B[e] - reference[e];
    num += mesh.area(e) * (d.x * d.x + d.y * d.y + d.z * d.z);
    const glm::dvec3& r = reference[e];
    den += mesh.area(e) * (r.x * r.x + r.y * r.y + r.z * r.z);
  }
  return den > 0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace rad
