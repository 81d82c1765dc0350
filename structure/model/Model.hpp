#pragma once
// Model: the discretised structure in structure-of-arrays form, ready for the step loop.
//
// Every nodal quantity is one contiguous array with the three components of a node side by side (xyz xyz
// ...): an element gathers its nodes with three cache-line reads instead of nine. Nodes are renumbered along
// a space-filling (Morton) curve and elements sorted by material then by first node, so that neighbouring
// elements touch neighbouring memory. User-facing ids (Gmsh tags, generator ids) are kept in `tag` arrays and
// only used in messages and output.

#include <any>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "structure/model/Materials.hpp"
#include "structure/model/MeshData.hpp"

namespace fsi::structure {

struct Nodes {
  int count = 0;
  std::vector<double> X;             ///< reference coordinates, 3 per node
  std::vector<double> x;             ///< current coordinates
  std::vector<double> v;             ///< velocities (at the half step during a run)
  std::vector<double> fint;          ///< internal (resisting) forces, elastic + viscous
  std::vector<double> fext;          ///< external forces (pressure, gravity, nodal loads)
  std::vector<double> mass;          ///< lumped mass used for inertia (after mass scaling)
  std::vector<double> physicalMass;  ///< lumped mass from the material densities (gravity, reports)
  std::vector<double> invMassDof;    ///< 1/mass per dof, 0 for a fixed dof: constraints cost no branch
  std::vector<long> tag;             ///< user-facing node id
  std::vector<int> mesh;             ///< index of the mesh the node came from
};

/// Contiguous run of membrane elements with one material; the force kernel hoists the constants.
struct MembraneBlock {
  int begin = 0, end = 0;
  int material = 0;  ///< index into Model::membraneMaterials
  double young = 0, c11 = 0, poisson = 0, density = 0;
  bool wrinkling = true;
};

/// Constant-strain membrane triangles. Reference geometry is stored in each element's own edge-aligned frame
/// (node 1 at the origin, node 2 on the first axis): node 2 at (a0, 0), node 3 at (b0, c0).
struct MembraneTriangles {
  int count = 0;
  std::vector<int> conn;             ///< 3 node indices per element
  std::vector<double> geo;           ///< 4 per element: 1/a0, b0, 1/c0, thickness*A0
  std::vector<double> invWaveSpeed;  ///< 1/c_d per element (changes with mass scaling)
  std::vector<double> refStep2;      ///< (h0/c_d)²: squared reference stable step, h0 the smallest altitude
  std::vector<MembraneBlock> blocks;
  std::vector<long> tag;
  std::vector<int> mesh;
  static constexpr int kGeo = 4;
};

struct CableBlock {
  int begin = 0, end = 0;
  int material = 0;
  double axialStiffness = 0;  ///< E*A [N]
  double young = 0, area = 0, density = 0;
};

/// Tension-only two-node cables.
struct Cables {
  int count = 0;
  std::vector<int> conn;             ///< 2 node indices per element
  std::vector<double> restLength;    ///< L0
  std::vector<double> invWaveSpeed;  ///< 1/c per element (changes with mass scaling)
  std::vector<CableBlock> blocks;
  std::vector<long> tag;
  std::vector<int> mesh;
};

/// Where the entities of one input mesh went after renumbering.
struct MeshMap {
  std::string name;
  std::vector<int> node;      ///< mesh-local point index -> model node
  std::vector<int> triangle;  ///< mesh-local triangle index -> model membrane element (-1 if none)
  std::vector<int> line;      ///< mesh-local line index -> model cable element
  MeshData source;            ///< the mesh as read (groups are resolved through the maps above)
};

struct Model {
  Nodes nodes;
  MembraneTriangles membranes;
  Cables cables;
  std::vector<MembraneMaterial> membraneMaterials;
  std::vector<CableMaterial> cableMaterials;
  std::vector<MeshMap> meshes;
  /// The storage of every other element kind, owned generically: a kind creates its block in
  /// ElementKind::build (any copyable type, e.g. a structure-of-arrays struct with its materials) and finds
  /// it again by its registry name through block<T>(). Membranes and cables are built by their kinds too,
  /// into the typed blocks above, because surface effects, probes and the coupling interface read them
  /// directly.
  std::map<std::string, std::any> kindBlocks;

  /// The block of kind `kind`, or nullptr if the kind created none (or one of another type).
  template <class Block>
  const Block* block(const std::string& kind) const {
    const auto it = kindBlocks.find(kind);
    return it == kindBlocks.end() ? nullptr : std::any_cast<Block>(&it->second);
  }
  template <class Block>
  Block* block(const std::string& kind) {
    const auto it = kindBlocks.find(kind);
    return it == kindBlocks.end() ? nullptr : std::any_cast<Block>(&it->second);
  }

  /// Human-readable name of a node / element for messages: "node 17 of mesh 'canopy'".
  std::string describeNode(int node) const;
  std::string describeTriangle(int element) const;
  std::string describeCable(int element) const;
};

/// One mesh with the materials of its triangles and lines (index into the material lists, -1 = none).
struct MeshInput {
  MeshData mesh;
  int membraneMaterial = -1;
  int cableMaterial = -1;
  /// What the mesh carries for every other element kind, by kind name: the kind's scene reader
  /// (structure/scene/kinds) stores here what its mesh keys say, including the cells it claimed from the
  /// mesh, and the kind reads it back in ElementKind::build (e.g. the point masses' (node, material) pairs,
  /// the bars' lines).
  std::map<std::string, std::any> kindInputs;
};

/// Membrane dilatational wave speed c_d = sqrt(Y / (ρ (1 − ν²))).
double membraneWaveSpeed(const MembraneMaterial& m);

}  // namespace fsi::structure
