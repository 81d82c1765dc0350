#include "structure/integrate/FictitiousMass.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "structure/elements/ElementKind.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace {
// The scene names of the rules, the one place they are spelled (`solver: {mass: NAME}`).
const std::vector<std::pair<FictitiousMassRule, std::string>>& ruleNames() {
  static const std::vector<std::pair<FictitiousMassRule, std::string>> names{
      {FictitiousMassRule::Gerschgorin, "gerschgorin"},
      {FictitiousMassRule::StressBound, "stress"},
      {FictitiousMassRule::RezaiePajand, "rezaiee_pajand"}};
  return names;
}
}  // namespace

const std::vector<std::string>& fictitiousMassRuleNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& entry : ruleNames()) n.push_back(entry.second);
    return n;
  }();
  return names;
}

FictitiousMassRule fictitiousMassRuleFromName(const std::string& name) {
  for (const auto& [rule, text] : ruleNames())
    if (text == name) return rule;
  std::string valid;
  for (const std::string& n : fictitiousMassRuleNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError("unknown fictitious mass rule '" + name + "'; valid: " + valid);
}

std::string toString(FictitiousMassRule rule) {
  for (const auto& [r, text] : ruleNames())
    if (r == rule) return text;
  return "?";
}

void tangentStiffnessBounds(const Model& model, const double* x, std::vector<double>& rowSum,
                            std::vector<double>& diagonal) {
  const int N = model.nodes.count;
  // Per-dof row sums and diagonal, assembled element by element by every element kind.
  std::vector<double> dofRow(3 * N, 0.0), dofDiag(3 * N, 0.0);
  for (const ElementKind* kind : elementKinds()) kind->addStiffnessBounds(model, x, dofRow, dofDiag);
  rowSum.assign(N, 0.0);
  diagonal.assign(N, 0.0);
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k) {
      rowSum[i] = std::max(rowSum[i], dofRow[3 * i + k]);
      diagonal[i] = std::max(diagonal[i], dofDiag[3 * i + k]);
    }
}

std::vector<double> fictitiousMasses(const Model& model, const double* x, FictitiousMassRule rule,
                                     double lambda) {
  const int N = model.nodes.count;
  std::vector<double> m(N, 0.0);
  if (rule == FictitiousMassRule::StressBound) {
    // Kinds that define the stress bound add it; the nodes none covers (cables: not in the proposal) keep the
    // Gerschgorin bound.
    std::vector<char> covered(N, 0);
    for (const ElementKind* kind : elementKinds()) kind->addStressBoundMass(model, x, lambda, m, covered);
    if (std::find(covered.begin(), covered.end(), 0) != covered.end()) {
      std::vector<double> row, diag;
      tangentStiffnessBounds(model, x, row, diag);
      for (int i = 0; i < N; ++i)
        if (!covered[i]) m[i] = 0.5 * lambda * row[i];
    }
    return m;
  }
  std::vector<double> row, diag;
  tangentStiffnessBounds(model, x, row, diag);
  for (int i = 0; i < N; ++i)
    m[i] = rule == FictitiousMassRule::Gerschgorin ? 0.5 * lambda * row[i]
                                                   : lambda * std::max(diag[i], 0.5 * row[i]);
  return m;
}

}  // namespace fsi::structure
