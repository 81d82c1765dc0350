#pragma once
// What every variant of the L2 projection assembles and how (coupling/mapping/L2Projection): the set-up
// they all read (ProjectionSetup: meshes, target quadrature, where each point finds the source, the gap
// correction), the rows of M_t and C they build one target node at a time (RowAssembly, a sparse
// accumulator per matrix, CSR output) and the result (ProjectionRows). The variants differ only in their
// test functions (nodal or dual) and in how H is applied (a solve with M_t or its diagonal).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/projection/GapGradient.hpp"
#include "coupling/mapping/projection/Quadrature.hpp"
#include "coupling/mapping/projection/SourcePoints.hpp"

namespace fsi::coupling {

/// The set-up every variant's assembly reads.
struct ProjectionSetup {
  const InterfaceMesh& source;
  const InterfaceMesh& target;
  const FanTriangulation& targetFan;
  const FanTriangulation& sourceFan;
  const std::vector<QuadPoint>& points;                    ///< the target quadrature
  const std::vector<std::pair<int, double>>& perTriangle;  ///< (point, weight) per fan triangle (dual only)
  int level;                                               ///< the quadrature level
  const SourcePoints& sources;                             ///< where each point finds the source
  const GapGradient* gradient;                             ///< the gap correction's stencils (null: none)
  double sourceEdge;                                       ///< the source's mean edge length
};

/// The assembled projection: C (target nodes × source nodes), M_t (none for dual), the row sums ∫ N_i and
/// which target nodes had their whole support mapped.
struct ProjectionRows {
  L2Projection::SparseRows c, m;
  Eigen::VectorXd lumped;
  std::vector<unsigned char> nodeMapped;
};

// Sparse accumulator for one row: dense values plus the list of touched columns.
struct RowAccumulator {
  explicit RowAccumulator(int n) : value(std::size_t(n), 0.0), mark(std::size_t(n), -1) {}
  void add(int row, int col, double v) {
    if (mark[std::size_t(col)] != row) {
      mark[std::size_t(col)] = row;
      value[std::size_t(col)] = 0.0;
      touched.push_back(col);
    }
    value[std::size_t(col)] += v;
  }
  // Appends the row (sorted columns) to CSR arrays and resets.
  void emit(std::vector<int>& inner, std::vector<double>& values);
  void discard() {
    for (int col : touched) mark[std::size_t(col)] = -1;
    touched.clear();
  }
  std::vector<double> value;
  std::vector<int> mark, touched;
};

/// The rows of M_t and C, target node by target node in order: addMass/addSource into row i, then
/// finishRow(i, ...); finish() returns the matrices.
class RowAssembly {
 public:
  /// `unitDiagonal`: a row without support gets M_t's unit diagonal (consistent: keeps M_t definite).
  RowAssembly(const ProjectionSetup& setup, bool unitDiagonal, ProjectionReport& report);

  void addMass(int i, int j, double v) { accM_.add(i, j, v); }
  /// Adds w × (the source functions at quadrature point q, moved across the gap) to row i of C.
  void addSource(int i, long q, double w);
  /// Closes row i of M_t and C; rowSum = ∫ N_i.
  void finishRow(int i, double rowSum, bool unmapped);
  ProjectionRows finish();

 private:
  const ProjectionSetup& setup_;
  bool unitDiagonal_;
  ProjectionReport& report_;
  int nt_, ns_;
  RowAccumulator accM_, accC_;
  std::vector<int> mOuter_{0}, mInner_, cOuter_{0}, cInner_;
  std::vector<double> mValues_, cValues_;
  Eigen::VectorXd lumped_;
  std::vector<unsigned char> nodeMapped_;
};

/// The rows with the nodal (hat) test functions N_i: M_t and C as the consistent and lumped variants use
/// them.
ProjectionRows assembleNodalRows(const ProjectionSetup& setup, bool unitDiagonal, ProjectionReport& report);

}  // namespace fsi::coupling
