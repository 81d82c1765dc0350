#pragma once
// Material records as the scene defines them. Units: SI (Pa, m, kg/m³).

#include <map>
#include <string>
#include <vector>

namespace fsi::structure {

/// Isotropic linear membrane (St Venant–Kirchhoff in Green–Lagrange strain), optional wrinkling.
struct MembraneMaterial {
  std::string name;
  double young = 0;       ///< Young's modulus [Pa]
  double poisson = 0;     ///< Poisson's ratio [-]
  double thickness = 0;   ///< reference thickness [m]
  double density = 0;     ///< mass density [kg/m³]
  bool wrinkling = true;  ///< false: the membrane also carries compression (plain plane stress)
};

/// Tension-only cable.
struct CableMaterial {
  std::string name;
  double young = 0;    ///< Young's modulus [Pa]
  double area = 0;     ///< cross-section [m²]
  double density = 0;  ///< mass density [kg/m³]
};

/// A lumped point mass (a payload), carried by the nodes of a mesh's node group (`point_masses:`).
struct PointMassMaterial {
  std::string name;
  double mass = 0;  ///< mass per node [kg]
};

/// A material of an element kind without a list of its own in the table: its named numbers as the scene gave
/// them (e.g. a bar's young, area, density); the kind's build reads and checks them.
struct KindMaterial {
  std::string name;
  std::map<std::string, double> values;
};

/// The materials of a scene, by element kind (what the material types' readers fill, material/MaterialTypes).
struct MaterialTable {
  std::vector<MembraneMaterial> membrane;
  std::vector<CableMaterial> cable;
  std::vector<PointMassMaterial> pointMass;
  /// The materials of every other element kind, by kind name (a new kind needs no list here).
  std::map<std::string, std::vector<KindMaterial>> other;
  /// element kind → material name → index in that kind's list
  std::map<std::string, std::map<std::string, int>> index;
};

}  // namespace fsi::structure
