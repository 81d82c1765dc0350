#include "coupling/mapping/projection/ProjectionVariant.hpp"

#include <algorithm>

namespace fsi::coupling {

ProjectionVariant::ProjectionVariant(ProjectionRows rows)
    : rows_(std::move(rows)), ns_(int(rows_.c.cols())), nt_(int(rows_.c.rows())) {
  lumpedInv_ = rows_.lumped.unaryExpr([](double d) { return d > 0.0 ? 1.0 / d : 0.0; });
}

template <int K>
void ProjectionVariant::applyDiagonalK(const double* us, double* ut) const {
  const int* outer = rows_.c.outerIndexPtr();
  const int* inner = rows_.c.innerIndexPtr();
  const double* val = rows_.c.valuePtr();
  for (int i = 0; i < nt_; ++i) {
    double s[K] = {};
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) s[k] += val[p] * us[inner[p] * K + k];
    for (int k = 0; k < K; ++k) ut[i * K + k] = s[k] * lumpedInv_[i];
  }
}

template <int K>
void ProjectionVariant::applyTransposeDiagonalK(const double* ft, double* fs) const {
  const int* outer = rows_.c.outerIndexPtr();
  const int* inner = rows_.c.innerIndexPtr();
  const double* val = rows_.c.valuePtr();
  std::fill(fs, fs + std::size_t(ns_) * K, 0.0);
  for (int i = 0; i < nt_; ++i) {
    double x[K];
    for (int k = 0; k < K; ++k) x[k] = ft[i * K + k] * lumpedInv_[i];
    for (int p = outer[i]; p < outer[i + 1]; ++p)
      for (int k = 0; k < K; ++k) fs[inner[p] * K + k] += val[p] * x[k];
  }
}

void ProjectionVariant::applyDiagonal(const double* us, double* ut, int components) const {
  if (components == 1)
    applyDiagonalK<1>(us, ut);
  else
    applyDiagonalK<3>(us, ut);
}

void ProjectionVariant::applyTransposeDiagonal(const double* ft, double* fs, int components) const {
  if (components == 1)
    applyTransposeDiagonalK<1>(ft, fs);
  else
    applyTransposeDiagonalK<3>(ft, fs);
}

ProjectionVariant::SparseRows ProjectionVariant::diagonalMatrix() const {
  SparseRows h = lumpedInv_.asDiagonal() * rows_.c;
  return h;
}

}  // namespace fsi::coupling
