#pragma once
// Fictitious masses for dynamic relaxation (step Δt = 1). Stability of central differences needs
// Δt ≤ 2/ω_max, and Gerschgorin's theorem bounds ω_max² ≤ max_r Σ_j |K_rj| / m_r; so masses
// m_i = (λ/2)·ρ_i with ρ_i the row-sum bound are stable for λ ≥ 0.5. Every bound here is assembled element by
// element from the element tangent stiffness; no global matrix is formed.

#include <string>
#include <vector>

#include "structure/model/Model.hpp"

namespace fsi::structure {

enum class FictitiousMassRule {
  Gerschgorin,   ///< m_i = (λ/2) max over the node's 3 dofs of Σ_j |K_ij|   (thesis "proposal 2")
  StressBound,   ///< m_i = (λ/2) Σ_e (t/4)[K + G + tr S/3 + S_vm/2]           (thesis "proposal 1")
  RezaiePajand,  ///< m_i = λ max over dofs of max(K_ii, ½ Σ_j |K_ij|)         (λ = 0.5: the R-P masses)
};

/// The rules' scene names (`solver: {mass: NAME}`), in the enum's order; toString and
/// fictitiousMassRuleFromName translate with the same table.
const std::vector<std::string>& fictitiousMassRuleNames();
/// Throws fsi::InputError listing the valid names for an unknown one.
FictitiousMassRule fictitiousMassRuleFromName(const std::string& name);
std::string toString(FictitiousMassRule rule);

/// Per node: Gerschgorin row sum (max over the 3 dofs) and largest diagonal entry of the tangent stiffness
/// (material + geometric, taut material law even where wrinkled: an upper bound) at configuration x.
void tangentStiffnessBounds(const Model& model, const double* x, std::vector<double>& rowSum,
                            std::vector<double>& diagonal);

/// Fictitious nodal masses for a rule and scale λ at configuration x.
std::vector<double> fictitiousMasses(const Model& model, const double* x, FictitiousMassRule rule,
                                     double lambda);

}  // namespace fsi::structure
