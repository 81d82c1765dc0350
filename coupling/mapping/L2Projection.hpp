#pragma once
// L2Projection: least-squares (L2) projection of nodal fields between two non-matching interface meshes, set
// up once on the undeformed geometry (Kalro & Tezduyar 2000). With M_t the target mass matrix and
// C_ij = ∫_target N_i(x) φ_j(P(x)) dΓ (P = closest-point projection onto the source surface),
//     consistent:  H = M_t⁻¹ C            exact L2 projection; reproduces linear fields; H is dense, so
//                                        apply = sparse C, then the LDLᵀ factors of M_t (fill grows ~N log N)
//     lumped:      H = diag(M_t 1)⁻¹ C   sparse; rows sum to 1; linear fields only on symmetric meshes
//     dual:        H = D⁻¹ C_ψ           test functions ψ biorthogonal to N make the mass matrix exactly
//                                        diagonal: sparse AND reproduces linear fields (for large meshes)
// and the conservative (transpose) transfer F_s = Hᵀ F_t carries forces back the other way with the same
// virtual work. See docs/PROJECTION.md for the directions, the quadrature and the measured accuracy.
//
// This class is the set-up all variants share — the target quadrature (projection/Quadrature), the closest
// source point of every quadrature point with the side rule (projection/SourcePoints), the gap correction's
// gradients (projection/GapGradient) — and the defect correction on top; each variant is a class of its own
// in coupling/mapping/projection/ (ConsistentProjection, LumpedProjection, DualProjection on the shared row
// assembly of ProjectionRows), chosen through ProjectionRegistry.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/interface/SurfaceSearch.hpp"

namespace fsi::coupling {

class ProjectionVariant;
class PointwiseEvaluation;

/// Auto: Consistent up to kAutoConsistentMaxNodes target nodes, Dual above (same accuracy, sparse, and its
/// apply stays above 10⁷ nodes/s where the consistent solves fall below it; docs/PROJECTION.md).
enum class MassMatrix { Consistent, Lumped, Dual, Auto };
inline const char* toString(MassMatrix m) {
  switch (m) {
    case MassMatrix::Consistent:
      return "consistent";
    case MassMatrix::Lumped:
      return "lumped";
    case MassMatrix::Dual:
      return "dual";
    case MassMatrix::Auto:
      return "auto";
  }
  return "?";
}
inline constexpr int kAutoConsistentMaxNodes = 5000;
/// The variant Auto stands for on a target of `targetNodes` nodes; any other variant is itself.
inline MassMatrix resolveMass(MassMatrix m, int targetNodes) {
  if (m != MassMatrix::Auto) return m;
  return targetNodes <= kAutoConsistentMaxNodes ? MassMatrix::Consistent : MassMatrix::Dual;
}
/// The names users write for the projection's mass matrix (`projection` in the adapter's options,
/// `fsi map-check --variant`), in the order of the enum: the one list every reader of such a name uses.
inline const std::vector<std::string>& massMatrixNames() {
  static const std::vector<std::string> names{toString(MassMatrix::Consistent), toString(MassMatrix::Lumped),
                                              toString(MassMatrix::Dual), toString(MassMatrix::Auto)};
  return names;
}
/// The mass matrix a name stands for; false (and `out` untouched) for any other name.
inline bool massMatrixFromName(const std::string& name, MassMatrix& out) {
  for (MassMatrix m : {MassMatrix::Consistent, MassMatrix::Lumped, MassMatrix::Dual, MassMatrix::Auto})
    if (name == toString(m)) {
      out = m;
      return true;
    }
  return false;
}

struct ProjectionOptions {
  MassMatrix mass = MassMatrix::Consistent;
  /// Absolute distance: target quadrature points farther than this from the source surface are unmapped.
  double tolerance = std::numeric_limits<double>::infinity();
  /// Quadrature of C and M_t: each target fan triangle is split into level² triangles, each integrated by
  /// the 3-point edge-midpoint rule (exact for quadratics). kAutoQuadrature (the default) chooses it from
  /// the meshes' mean edge lengths (autoQuadratureLevel), so that a source finer than the target is sampled
  /// densely enough for Hᵀ to load every source node smoothly; a positive value is used as given.
  int quadratureLevel = 0;
  /// Transport the source field across the gap between the two discrete surfaces to first order (the
  /// source's 3D gradient, fitted on each source triangle's neighbourhood): H then maps every field linear
  /// in x, y, z exactly also on curved surfaces that do not coincide, so rigid rotations reach the target
  /// undistorted and Hᵀ conserves the moment exactly. See docs/PROJECTION.md ("Gap correction").
  bool gapCorrection = true;
  /// Defect correction H' = 2H − H P H, P the (dual) projection back from the target to the source: removes
  /// the projection's own averaging over the target's hat functions (~h_t²∇²f at the nodes), which a target
  /// much coarser than the source would otherwise add to the field; keeps constants and linear fields
  /// exact (so force and moment), Hᵀ' = 2Hᵀ − Hᵀ Pᵀ Hᵀ stays smooth. Auto: on when the target's mean edge is
  /// at least kDefectRatio × the source's and P maps every source node. See docs/PROJECTION.md.
  enum class Defect { Off, On, Auto } defectCorrection = Defect::Auto;
  /// Keep every target point on its own side of a thin body. Where the fluid wets the interface from one
  /// side only (a closed canopy: at least kOneSidedShare of the target's area finds its closest source
  /// triangle facing one consistent way), a point whose closest source triangle faces the other way — at a
  /// trailing-edge wedge thinner than the meshes' gap, the opposite skin — is mapped to the closest source
  /// triangle facing its own way instead. Surfaces wetted from both sides (a baffle, a sail) are left
  /// alone. See docs/PROJECTION.md ("Thin edges").
  bool keepSide = true;
  /// How u_t = H u_s (apply) evaluates the source field at the target nodes. L2 (the struct's default): the
  /// L2 projection above (with its corrections). Pointwise: each target node takes the source field at its
  /// closest source point (nearest projection, PointwiseEvaluation) — second order at the nodes at any mesh
  /// ratio, where the L2 projection's averaging over a coarse target's hat functions is not. applyTranspose
  /// stays Hᵀ of the L2 projection either way (smooth, exact total force). See docs/PROJECTION.md,
  /// "Consistent direction: pointwise or L2".
  enum class Evaluation { L2, Pointwise } evaluation = Evaluation::L2;
};

inline const char* toString(ProjectionOptions::Evaluation e) {
  return e == ProjectionOptions::Evaluation::Pointwise ? "pointwise" : "l2";
}
inline const char* toString(ProjectionOptions::Defect d) {
  return d == ProjectionOptions::Defect::On ? "on" : d == ProjectionOptions::Defect::Off ? "off" : "auto";
}

/// Share of the target's area that must see the source facing one way for the interface to count as wetted
/// from one side (ProjectionOptions::keepSide). A membrane wetted from both sides gives about one half.
inline constexpr double kOneSidedShare = 0.9;

inline constexpr double kDefectRatio = 1.5;

inline constexpr int kAutoQuadrature = 0;
/// Largest level autoQuadratureLevel chooses (and map-check/the adapter accept).
inline constexpr int kMaxQuadratureLevel = 64;
/// The level chosen for quadratureLevel = kAutoQuadrature: ceil(2 × target / source mean edge length),
/// at least 1 and at most kMaxQuadratureLevel, i.e. quadrature sub-triangles about half a source edge
/// across (measured: docs/PROJECTION.md, "Quadrature").
int autoQuadratureLevel(const InterfaceMesh& source, const InterfaceMesh& target);

/// A target quadrature point that found no source surface within the tolerance.
struct UnmappedPoint {
  long id = -1;               ///< quadrature point id (setup order)
  std::array<double, 3> x{};  ///< its position on the target surface
  double distance = 0.0;      ///< distance to the closest source point
};

struct ProjectionReport {
  std::string source, target;  ///< mesh names
  int sourceNodes = 0, targetNodes = 0, targetTriangles = 0;
  int quadratureLevel = 1;        ///< the level used (chosen when the options said kAutoQuadrature)
  bool gapCorrection = false;     ///< the source field was transported across the gap
  bool defectCorrection = false;  ///< H' = 2H − H P H is applied (ProjectionOptions::defectCorrection)
  /// Source triangles whose neighbourhood is flat (their normal derivative is unknown and taken as 0; the
  /// correction is then only tangential): exact linear reproduction needs gaps only where it is curved.
  long flatGradientTriangles = 0;
  long gapStencilEntries =
      0;  ///< (node, gradient weight) pairs of the gap correction (setup memory, 32 B each)
  long quadraturePoints = 0;
  /// Share of the mapped target area whose closest source triangle faces the majority's way (1 on a
  /// matching closed surface, about 0.5 on a membrane wetted from both sides).
  double facingShare = 1.0;
  bool oneSided = false;  ///< facingShare ≥ kOneSidedShare and keepSide: the side rule was applied
  /// Quadrature points moved from a source triangle facing the wrong way to the closest one facing theirs.
  long residedPoints = 0;
  /// Of those, the largest distance to the new source point (the old one was closer: this is the cost).
  double maxResidedGap = 0.0;
  /// Points facing the other way left where they were: their own side is farther than every correctly
  /// facing point's gap, so the target face itself is turned over (a snapped face at a sharp corner).
  long turnedPoints = 0;
  long unmappedQuadraturePoints = 0;
  std::vector<UnmappedPoint> firstUnmappedPoints;  ///< up to kListed
  /// Target nodes with an unmapped quadrature point in their support (their value lacks part of its data)
  /// or with no support at all.
  int unmappedTargetNodes = 0;
  std::vector<int> firstUnmappedNodes;  ///< up to kListed
  double maxGap = 0.0;                  ///< largest distance of a mapped quadrature point to the source
  bool pointwise = false;   ///< apply() evaluates at the target nodes (ProjectionOptions::evaluation)
  double maxNodeGap = 0.0;  ///< pointwise: largest distance of a mapped target node to the source
  double searchSeconds = 0.0, assemblySeconds = 0.0, factorSeconds = 0.0, setupSeconds = 0.0;
  static constexpr std::size_t kListed = 10;
  bool allMapped() const { return unmappedQuadraturePoints == 0 && unmappedTargetNodes == 0; }
};

class L2Projection {
 public:
  using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  /// Sets up H from `source` to `target` (search, assembly, factorisation of M_t). Unmapped points are
  /// reported, not fatal. Throws fsi::InputError for invalid meshes (bad faces, no faces).
  L2Projection(const InterfaceMesh& source, const InterfaceMesh& target,
               const ProjectionOptions& options = {});
  ~L2Projection();
  L2Projection(L2Projection&&) noexcept;
  L2Projection& operator=(L2Projection&&) noexcept;

  int sourceSize() const { return ns_; }
  int targetSize() const { return nt_; }
  MassMatrix mass() const { return mass_; }  ///< never Auto: the variant it chose
  const ProjectionReport& report() const { return report_; }

  /// u_t = H u_s (with Evaluation::Pointwise: E u_s, the source field at each target node's closest point)
  /// for `components` = 1 or 3 (vectors xyz-interleaved). us has sourceSize()·components values, ut
  /// targetSize()·components. No allocation; uses internal scratch, so one object must not apply from two
  /// threads at once.
  void apply(const double* us, double* ut, int components = 1) const;
  /// f_s = Hᵀ f_t: the conservative transfer (forces target → source), same conventions as apply().
  void applyTranspose(const double* ft, double* fs, int components = 1) const;
  void apply(const Eigen::VectorXd& us, Eigen::VectorXd& ut, int components = 1) const;
  void applyTranspose(const Eigen::VectorXd& ft, Eigen::VectorXd& fs, int components = 1) const;

  /// C (target nodes × source nodes; for Dual, C_ψ with the dual test functions) and the consistent target
  /// mass matrix M_t (not assembled for Dual: no entries).
  const SparseRows& coupling() const;
  const SparseRows& targetMass() const;
  /// Per target node: 1 when its whole support mapped (see ProjectionReport::unmappedTargetNodes).
  const std::vector<unsigned char>& targetNodeMapped() const;
  /// Row sums of M_t (the lumped mass, ∫ N_i dΓ).
  const Eigen::VectorXd& lumpedMass() const;
  /// H itself as a sparse matrix. Lumped, Dual: diag⁻¹ C, as sparse as C. Consistent: M_t⁻¹ C is dense in
  /// principle (the inverse of a mass matrix has no zero entries), so it is solved column by column and
  /// entries below dropTolerance × (largest entry in its row) are dropped: for inspection and small meshes;
  /// apply() never forms it. With the defect correction, the corrected operator, by one apply per source
  /// node (and C, targetMass() are those of the uncorrected H). With Evaluation::Pointwise: E, the matrix
  /// apply() uses (applyTranspose() is then not its transpose but Hᵀ of the L2 projection).
  SparseRows operatorMatrix(double dropTolerance = 0.0) const;

 private:
  void setUpPointwise(const SurfaceSearch& search, const InterfaceMesh& target);

  int ns_ = 0, nt_ = 0;
  MassMatrix mass_;
  ProjectionReport report_;
  std::unique_ptr<PointwiseEvaluation> pointwise_;  // u_t = E u_s (Evaluation::Pointwise), or null
  std::vector<unsigned char> nodeMapped_;           // the L2 rows' and the pointwise evaluation's, combined
  std::unique_ptr<ProjectionVariant> variant_;  // the uncorrected H and Hᵀ (coupling/mapping/projection/)
  std::unique_ptr<L2Projection> back_;          // P (target → source) of the defect correction, or null
  mutable std::vector<double> defectSource_, defectTarget_;
};

}  // namespace fsi::coupling
