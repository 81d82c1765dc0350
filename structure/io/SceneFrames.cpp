#include "structure/io/SceneFrames.hpp"

#include "structure/effects/CableForces.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

SceneFrames::SceneFrames(const Scene& scene, const std::filesystem::path& file,
                         std::optional<double> keepUntil)
    : scene_(scene) {
  const Model& m = *scene.model;
  std::vector<std::array<int, 3>> tris(m.membranes.count);
  for (int e = 0; e < m.membranes.count; ++e)
    tris[e] = {m.membranes.conn[3 * e], m.membranes.conn[3 * e + 1], m.membranes.conn[3 * e + 2]};
  std::vector<std::array<int, 2>> lines(m.cables.count);
  for (int e = 0; e < m.cables.count; ++e) lines[e] = {m.cables.conn[2 * e], m.cables.conn[2 * e + 1]};
  writer_ = keepUntil
                ? std::make_unique<ResultsWriter>(ResultsWriter::append(file, m.nodes.count, std::move(tris),
                                                                        std::move(lines), *keepUntil))
                : std::make_unique<ResultsWriter>(file, m.nodes.count, std::move(tris), std::move(lines));
}

void SceneFrames::write(double time, long step) {
  const Model& m = *scene_.model;
  const Nodes& N = m.nodes;
  const auto& f = scene_.output.fields;
  std::vector<FieldView> views;
  u_.resize(3 * N.count);
  for (int i = 0; i < 3 * N.count; ++i) u_[i] = N.x[i] - N.X[i];
  if (f.count("displacement")) views.push_back({"displacement", FieldView::Center::Node, 3, u_.data()});
  if (f.count("velocity")) views.push_back({"velocity", FieldView::Center::Node, 3, N.v.data()});
  if (f.count("residual")) {
    // Out-of-balance force f_ext − f_int on free dofs (forces as last evaluated by the solver).
    r_.resize(3 * N.count);
    for (int i = 0; i < 3 * N.count; ++i) r_[i] = N.invMassDof[i] != 0.0 ? N.fext[i] - N.fint[i] : 0.0;
    views.push_back({"residual", FieldView::Center::Node, 3, r_.data()});
  }
  if (scene_.membrane && (f.count("stress") || f.count("principal_stress") || f.count("wrinkle_state"))) {
    scene_.membrane->evaluate(N.x.data(), stress_);
    major_.resize(m.membranes.count);
    minor_.resize(m.membranes.count);
    for (int e = 0; e < m.membranes.count; ++e) {
      major_[e] = stress_.principal[2 * e];
      minor_[e] = stress_.principal[2 * e + 1];
    }
    if (f.count("stress")) views.push_back({"stress", FieldView::Center::Triangle, 6, stress_.cauchy.data()});
    if (f.count("principal_stress")) {
      views.push_back({"principal_stress_major", FieldView::Center::Triangle, 1, major_.data()});
      views.push_back({"principal_stress_minor", FieldView::Center::Triangle, 1, minor_.data()});
    }
    if (f.count("wrinkle_state"))
      views.push_back({"wrinkle_state", FieldView::Center::Triangle, 1, stress_.state.data()});
  }
  if (scene_.cable && f.count("cable_force")) {
    scene_.cable->evaluate(N.x.data(), tension_);
    views.push_back({"cable_force", FieldView::Center::Line, 1, tension_.data()});
  }
  writer_->writeStep(time, step, N.x.data(), views);
}

}  // namespace fsi::structure
