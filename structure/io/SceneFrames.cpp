#include "structure/io/SceneFrames.hpp"

#include "structure/elements/ElementKind.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

SceneFrames::SceneFrames(const Model& model, const Constraints& constraints,
                         const std::set<std::string>& fields, const std::filesystem::path& file,
                         std::optional<double> keepUntil)
    : model_(model), constraints_(constraints), fields_(fields) {
  const Model& m = model_;
  // Every element kind's cells, in registry order.
  std::vector<CellSet> cells;
  for (const ElementKind* kind : elementKinds())
    if (std::optional<CellSet> s = kind->outputCells(m)) cells.push_back(std::move(*s));
  writer_ = keepUntil ? std::make_unique<ResultsWriter>(
                            ResultsWriter::append(file, m.nodes.count, std::move(cells), *keepUntil))
                      : std::make_unique<ResultsWriter>(file, m.nodes.count, std::move(cells));
}

void SceneFrames::write(double time, long step) {
  const Model& m = model_;
  const Nodes& N = m.nodes;
  const auto& f = fields_;
  std::vector<FieldView> views;
  u_.resize(3 * N.count);
  for (int i = 0; i < 3 * N.count; ++i) u_[i] = N.x[i] - N.X[i];
  if (f.count("displacement")) views.push_back({"displacement", FieldView::Center::Node, 3, u_.data()});
  if (f.count("velocity")) views.push_back({"velocity", FieldView::Center::Node, 3, N.v.data()});
  if (f.count("residual")) {
    // Out-of-balance force f_ext − f_int on free dofs (forces as last evaluated by the solver; on a tied node
    // its share of its group's, Constraints::reactions).
    constraints_.reactions(N, r_);
    for (int i = 0; i < 3 * N.count; ++i) r_[i] = N.invMassDof[i] != 0.0 ? -r_[i] : 0.0;
    views.push_back({"residual", FieldView::Center::Node, 3, r_.data()});
  }
  // Element fields: every element kind adds the ones it has (stress of the membranes, cable forces, ...).
  const auto& kinds = elementKinds();
  elementFields_.resize(kinds.size());
  for (std::size_t k = 0; k < kinds.size(); ++k)
    kinds[k]->addFields(m, N.x.data(), f, elementFields_[k], views);
  writer_->writeStep(time, step, N.x.data(), views);
}

}  // namespace fsi::structure
