#include "coupling/mapping/projection/ConsistentProjection.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

ConsistentProjection::ConsistentProjection(const ProjectionSetup& setup, ProjectionReport& report)
    : ProjectionVariant(assembleNodalRows(setup, /*unitDiagonal=*/true, report)) {
  const auto t0 = std::chrono::steady_clock::now();
  factor(setup.target);
  report.factorSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  scratch_.assign(std::size_t(3 * nt_), 0.0);
}

void ConsistentProjection::factor(const InterfaceMesh& target) {
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> mc = rows_.m;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Lower,
                        Eigen::AMDOrdering<int>>
      ldlt(mc);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0))
    throw InputError(fmt::format(
        "interface mesh '{}': its mass matrix is not positive definite (degenerate faces?)", target.name));
  perm_.resize(std::size_t(nt_));
  const auto& idx = ldlt.permutationP().indices();
  for (int i = 0; i < nt_; ++i) perm_[std::size_t(i)] = idx(i);
  const auto& l = ldlt.matrixL().nestedExpression();
  lp_.assign(1, 0);
  lp_.reserve(std::size_t(nt_) + 1);
  for (int j = 0; j < nt_; ++j) {
    for (Eigen::SparseMatrix<double, Eigen::ColMajor, int>::InnerIterator it(l, j); it; ++it)
      if (it.row() > j) {
        li_.push_back(int(it.row()));
        lx_.push_back(it.value());
      }
    lp_.push_back(int(li_.size()));
  }
  dinv_.resize(std::size_t(nt_));
  for (int i = 0; i < nt_; ++i) dinv_[std::size_t(i)] = 1.0 / ldlt.vectorD()(i);
}

template <int K>
void ConsistentProjection::solveInPlace(double* z) const {
  const int n = nt_;
  const int* lp = lp_.data();
  const int* li = li_.data();
  const double* lx = lx_.data();
  for (int j = 0; j < n; ++j) {  // L y = b, column by column
    double x[K];
    for (int k = 0; k < K; ++k) x[k] = z[j * K + k];
    for (int p = lp[j]; p < lp[j + 1]; ++p)
      for (int k = 0; k < K; ++k) z[li[p] * K + k] -= lx[p] * x[k];
  }
  for (int j = n - 1; j >= 0; --j) {  // Lᵀ x = D⁻¹ y, with the diagonal scaling fused in
    double s[K];
    for (int k = 0; k < K; ++k) s[k] = z[j * K + k] * dinv_[std::size_t(j)];
    for (int p = lp[j]; p < lp[j + 1]; ++p)
      for (int k = 0; k < K; ++k) s[k] -= lx[p] * z[li[p] * K + k];
    for (int k = 0; k < K; ++k) z[j * K + k] = s[k];
  }
}

template <int K>
void ConsistentProjection::applyK(const double* us, double* ut) const {
  const int* outer = rows_.c.outerIndexPtr();
  const int* inner = rows_.c.innerIndexPtr();
  const double* val = rows_.c.valuePtr();
  double* z = scratch_.data();
  for (int i = 0; i < nt_; ++i) {  // z = P C u_s
    double s[K] = {};
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) s[k] += val[p] * us[inner[p] * K + k];
    for (int k = 0; k < K; ++k) z[perm_[std::size_t(i)] * K + k] = s[k];
  }
  solveInPlace<K>(z);
  for (int i = 0; i < nt_; ++i)
    for (int k = 0; k < K; ++k) ut[i * K + k] = z[perm_[std::size_t(i)] * K + k];
}

template <int K>
void ConsistentProjection::applyTransposeK(const double* ft, double* fs) const {
  const int* outer = rows_.c.outerIndexPtr();
  const int* inner = rows_.c.innerIndexPtr();
  const double* val = rows_.c.valuePtr();
  std::fill(fs, fs + std::size_t(ns_) * K, 0.0);
  // Hᵀ f = Cᵀ M⁻¹ f (M symmetric).
  double* z = scratch_.data();
  for (int i = 0; i < nt_; ++i)
    for (int k = 0; k < K; ++k) z[perm_[std::size_t(i)] * K + k] = ft[i * K + k];
  solveInPlace<K>(z);
  for (int i = 0; i < nt_; ++i) {
    double x[K];
    for (int k = 0; k < K; ++k) x[k] = z[perm_[std::size_t(i)] * K + k];
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) fs[inner[p] * K + k] += val[p] * x[k];
  }
}

void ConsistentProjection::apply(const double* us, double* ut, int components) const {
  if (components == 1)
    applyK<1>(us, ut);
  else
    applyK<3>(us, ut);
}

void ConsistentProjection::applyTranspose(const double* ft, double* fs, int components) const {
  if (components == 1)
    applyTransposeK<1>(ft, fs);
  else
    applyTransposeK<3>(ft, fs);
}

ConsistentProjection::SparseRows ConsistentProjection::matrix(double dropTolerance) const {
  // Column j of H = M⁻¹ (column j of C).
  const Eigen::SparseMatrix<double, Eigen::ColMajor, int> cc = rows_.c;
  std::vector<Eigen::Triplet<double, int>> entries;
  std::vector<double> z(static_cast<std::size_t>(nt_));
  for (int j = 0; j < ns_; ++j) {
    std::fill(z.begin(), z.end(), 0.0);
    for (Eigen::SparseMatrix<double, Eigen::ColMajor, int>::InnerIterator it(cc, j); it; ++it)
      z[std::size_t(perm_[std::size_t(it.row())])] = it.value();
    solveInPlace<1>(z.data());
    for (int i = 0; i < nt_; ++i) {
      const double v = z[std::size_t(perm_[std::size_t(i)])];
      if (v != 0.0) entries.emplace_back(i, j, v);
    }
  }
  std::vector<double> rowMax(std::size_t(nt_), 0.0);
  for (const auto& e : entries)
    rowMax[std::size_t(e.row())] = std::max(rowMax[std::size_t(e.row())], std::abs(e.value()));
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [&](const auto& e) {
                                 return std::abs(e.value()) < dropTolerance * rowMax[std::size_t(e.row())];
                               }),
                entries.end());
  SparseRows h(nt_, ns_);
  h.setFromTriplets(entries.begin(), entries.end());
  return h;
}

std::unique_ptr<ProjectionVariant> makeConsistentProjection(const ProjectionSetup& setup,
                                                            ProjectionReport& report) {
  return std::make_unique<ConsistentProjection>(setup, report);
}

}  // namespace fsi::coupling
