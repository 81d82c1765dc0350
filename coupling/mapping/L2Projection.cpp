#include "coupling/mapping/L2Projection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "coupling/mapping/projection/GapGradient.hpp"
#include "coupling/mapping/projection/PointwiseEvaluation.hpp"
#include "coupling/mapping/projection/ProjectionRegistry.hpp"
#include "coupling/mapping/projection/Quadrature.hpp"
#include "coupling/mapping/projection/SourcePoints.hpp"

namespace fsi::coupling {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void checkComponents(int components) {
  if (components != 1 && components != 3)
    throw std::invalid_argument(fmt::format("L2Projection: {} components (1 or 3 supported)", components));
}

}  // namespace

L2Projection::L2Projection(const InterfaceMesh& source, const InterfaceMesh& target,
                           const ProjectionOptions& options)
    : ns_(source.numPoints()), nt_(target.numPoints()), mass_(resolveMass(options.mass, target.numPoints())) {
  const auto tSetup = Clock::now();
  report_.source = source.name;
  report_.target = target.name;
  report_.sourceNodes = ns_;
  report_.targetNodes = nt_;
  const ProjectionVariantEntry& variant = projectionVariant(mass_);

  auto t0 = Clock::now();
  const SurfaceSearch search(source, options.tolerance);
  const FanTriangulation tf(target);
  report_.targetTriangles = tf.numTriangles();
  const int level = options.quadratureLevel == kAutoQuadrature ? autoQuadratureLevel(source, target)
                                                               : std::max(1, options.quadratureLevel);
  report_.quadratureLevel = level;
  std::vector<std::pair<int, double>> perTriangle;
  const std::vector<QuadPoint> qp =
      quadraturePoints(tf, level, variant.perTriangleQuadrature ? &perTriangle : nullptr);
  report_.quadraturePoints = long(qp.size());
  const SourcePoints sources =
      findSourcePoints(search, tf, qp, options.gapCorrection, options.keepSide, report_);
  report_.searchSeconds = secondsSince(t0);

  t0 = Clock::now();
  const FanTriangulation& sf = search.fan();
  // The patch reaches 2 × the larger mean edge: the fitted normal derivative is then well determined
  // against the gaps (which grow as the coarser mesh's h²), see GapGradient.
  const double sourceEdge = source.meanEdgeLength();
  std::optional<GapGradient> gradient;
  report_.gapCorrection = options.gapCorrection;
  if (options.gapCorrection) {
    gradient.emplace(source, sf, 2.0 * std::max(sourceEdge, target.meanEdgeLength()));
    // Stencils only where a point has a gap (none on coinciding flat surfaces: no cost there).
    std::vector<unsigned char> used(std::size_t(sf.numTriangles()), 0);
    for (std::size_t q = 0; q < qp.size(); ++q)
      if (sources.triangle[q] >= 0 && !negligibleGap(sources.gap[q], sourceEdge))
        used[std::size_t(sources.triangle[q])] = 1;
    gradient->build(used);
    report_.flatGradientTriangles = gradient->flatTriangles;
    report_.gapStencilEntries = gradient->entries();
  }
  const ProjectionSetup setup{
      source, target, tf, sf, qp, perTriangle, level, sources, gradient ? &*gradient : nullptr, sourceEdge};
  variant_ = variant.make(setup, report_);  // assembles (and for the consistent variant factors) H
  report_.assemblySeconds = secondsSince(t0) - report_.factorSeconds;
  nodeMapped_ = variant_->rows().nodeMapped;
  if (options.evaluation == ProjectionOptions::Evaluation::Pointwise) setUpPointwise(search, target);

  const bool coarserTarget = target.meanEdgeLength() >= kDefectRatio * source.meanEdgeLength();
  if (options.defectCorrection == ProjectionOptions::Defect::On ||
      (options.defectCorrection == ProjectionOptions::Defect::Auto && coarserTarget)) {
    // P back onto the source: dual (sparse, exact for linear fields like H), never corrected itself.
    ProjectionOptions back = options;
    back.mass = MassMatrix::Dual;
    back.quadratureLevel = kAutoQuadrature;
    back.defectCorrection = ProjectionOptions::Defect::Off;
    back.evaluation = ProjectionOptions::Evaluation::L2;
    back_ = std::make_unique<L2Projection>(target, source, back);
    // A source node P cannot reach would feed H a value pulled towards 0: only correct with P complete.
    if (back_->report().allMapped() || options.defectCorrection == ProjectionOptions::Defect::On) {
      report_.defectCorrection = true;
      defectSource_.assign(std::size_t(3 * ns_), 0.0);
      defectTarget_.assign(std::size_t(3 * nt_), 0.0);
    } else {
      back_.reset();
    }
  }
  report_.setupSeconds = secondsSince(tSetup);
}

L2Projection::~L2Projection() = default;
L2Projection::L2Projection(L2Projection&&) noexcept = default;
L2Projection& L2Projection::operator=(L2Projection&&) noexcept = default;

const L2Projection::SparseRows& L2Projection::coupling() const {
  return variant_->rows().c;
}
const L2Projection::SparseRows& L2Projection::targetMass() const {
  return variant_->rows().m;
}
const std::vector<unsigned char>& L2Projection::targetNodeMapped() const {
  return nodeMapped_;
}

// Evaluation::Pointwise: the target nodes themselves are searched; a node farther than the tolerance is
// unmapped like a node whose support has an unmapped quadrature point.
void L2Projection::setUpPointwise(const SurfaceSearch& search, const InterfaceMesh& target) {
  pointwise_ = std::make_unique<PointwiseEvaluation>(search, target);
  report_.pointwise = true;
  report_.maxNodeGap = pointwise_->maxGap();
  for (int i = 0; i < nt_; ++i) {
    if (pointwise_->nodeMapped()[std::size_t(i)] || !nodeMapped_[std::size_t(i)]) continue;
    nodeMapped_[std::size_t(i)] = 0;
    ++report_.unmappedTargetNodes;
    if (report_.firstUnmappedNodes.size() < ProjectionReport::kListed)
      report_.firstUnmappedNodes.push_back(i);
  }
}
const Eigen::VectorXd& L2Projection::lumpedMass() const {
  return variant_->rows().lumped;
}

int autoQuadratureLevel(const InterfaceMesh& source, const InterfaceMesh& target) {
  const double hs = source.meanEdgeLength(), ht = target.meanEdgeLength();
  if (!(hs > 0.0) || !(ht > 0.0) || !std::isfinite(ht / hs)) return 1;
  return int(std::clamp(std::ceil(2.0 * ht / hs - 1e-9), 1.0, double(kMaxQuadratureLevel)));
}

// The defect correction (ProjectionOptions::defectCorrection): H u carries the projection's averaging error
// e = H u − u_t (~c h_t² ∇²u); P maps the target field back to the source nearly exactly (the source is
// finer), so H P H u carries it twice, and 2 H u − H P H u = u_t + O(h_t⁴) + the source's own error. Both
// H and P reproduce constants and linear fields, so H' does, and Hᵀ' = 2Hᵀ − Hᵀ Pᵀ Hᵀ conserves force
// and moment exactly as Hᵀ does.
void L2Projection::apply(const double* us, double* ut, int components) const {
  checkComponents(components);
  if (pointwise_) {
    pointwise_->apply(us, ut, components);
    return;
  }
  variant_->apply(us, ut, components);
  if (!back_) return;
  back_->apply(ut, defectSource_.data(), components);
  variant_->apply(defectSource_.data(), defectTarget_.data(), components);
  const std::size_t n = std::size_t(nt_) * std::size_t(components);
  for (std::size_t i = 0; i < n; ++i) ut[i] = 2.0 * ut[i] - defectTarget_[i];
}

void L2Projection::applyTranspose(const double* ft, double* fs, int components) const {
  checkComponents(components);
  variant_->applyTranspose(ft, fs, components);
  if (!back_) return;
  back_->applyTranspose(fs, defectTarget_.data(), components);
  variant_->applyTranspose(defectTarget_.data(), defectSource_.data(), components);
  const std::size_t n = std::size_t(ns_) * std::size_t(components);
  for (std::size_t i = 0; i < n; ++i) fs[i] = 2.0 * fs[i] - defectSource_[i];
}

void L2Projection::apply(const Eigen::VectorXd& us, Eigen::VectorXd& ut, int components) const {
  checkComponents(components);
  if (us.size() != long(ns_) * components)
    throw std::invalid_argument(
        fmt::format("L2Projection::apply: {} source values, expected {}", us.size(), long(ns_) * components));
  ut.resize(long(nt_) * components);
  apply(us.data(), ut.data(), components);
}

void L2Projection::applyTranspose(const Eigen::VectorXd& ft, Eigen::VectorXd& fs, int components) const {
  checkComponents(components);
  if (ft.size() != long(nt_) * components)
    throw std::invalid_argument(fmt::format("L2Projection::applyTranspose: {} target values, expected {}",
                                            ft.size(), long(nt_) * components));
  fs.resize(long(ns_) * components);
  applyTranspose(ft.data(), fs.data(), components);
}

L2Projection::SparseRows L2Projection::operatorMatrix(double dropTolerance) const {
  if (pointwise_) return pointwise_->matrix();
  if (!back_) return variant_->matrix(dropTolerance);
  // The corrected operator, column by column.
  std::vector<Eigen::Triplet<double, int>> entries;
  std::vector<double> e(std::size_t(ns_), 0.0);
  std::vector<double> col(std::size_t(nt_), 0.0);
  std::vector<double> rowMax(std::size_t(nt_), 0.0);
  for (int j = 0; j < ns_; ++j) {
    e[std::size_t(j)] = 1.0;
    apply(e.data(), col.data());
    e[std::size_t(j)] = 0.0;
    for (int i = 0; i < nt_; ++i)
      if (col[std::size_t(i)] != 0.0) {
        entries.emplace_back(i, j, col[std::size_t(i)]);
        rowMax[std::size_t(i)] = std::max(rowMax[std::size_t(i)], std::abs(col[std::size_t(i)]));
      }
  }
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [&](const auto& t) {
                                 return std::abs(t.value()) < dropTolerance * rowMax[std::size_t(t.row())];
                               }),
                entries.end());
  SparseRows h(nt_, ns_);
  h.setFromTriplets(entries.begin(), entries.end());
  return h;
}

}  // namespace fsi::coupling
