#include "structure/scene/Scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "structure/effects/ExternalLoads.hpp"
#include "structure/integrate/FictitiousMass.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/MeshSources.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

std::vector<const Effect*> Scene::effectList() const {
  std::vector<const Effect*> list;
  for (const auto& e : effects) list.push_back(e.get());
  return list;
}

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// ---------------------------------------------------------------- time functions
TimeFunction readTimeFunction(const YamlMap& parent, const std::string& key) {
  if (!parent.has(key)) return TimeFunction::constant(1.0);
  const YAML::Node raw = parent.raw(key);
  if (raw.IsScalar()) return TimeFunction::constant(asNumber(raw, parent.file(), parent.childPath(key)));
  YamlMap m(raw, parent.file(), parent.childPath(key));
  const std::string type = m.choice("type", {"constant", "ramp", "smooth_step", "table", "sine"});
  try {
    if (type == "constant") {
      const double v = m.number("value", 1.0);
      m.finish({"type", "value"});
      return TimeFunction::constant(v);
    }
    if (type == "ramp" || type == "smooth_step") {
      const double d = m.number("duration"), s = m.number("start", 0.0);
      m.finish({"type", "duration", "start"});
      if (!(d > 0)) m.failAt("duration", "must be > 0");
      return type == "ramp" ? TimeFunction::ramp(d, s) : TimeFunction::smoothStep(d, s);
    }
    if (type == "sine") {
      const double a = m.number("amplitude"), f = m.number("frequency"), ph = m.number("phase", 0.0),
                   off = m.number("offset", 0.0);
      m.finish({"type", "amplitude", "frequency", "phase", "offset"});
      return TimeFunction::sine(a, f, ph, off);
    }
    const YAML::Node pts = m.raw("points");
    if (!pts || !pts.IsSequence() || pts.size() == 0)
      m.fail("a table needs 'points: [[t0, v0], [t1, v1], ...]'");
    std::vector<std::pair<double, double>> p;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string pp = fmt::format("{}.points[{}]", m.path(), i);
      if (!pts[i].IsSequence() || pts[i].size() != 2)
        throw InputError(locate(m.file(), pts[i], pp) + ": expected [time, value]");
      p.emplace_back(asNumber(pts[i][0], m.file(), pp), asNumber(pts[i][1], m.file(), pp));
    }
    m.finish({"type", "points"});
    for (std::size_t i = 1; i < p.size(); ++i)
      if (!(p[i].first > p[i - 1].first)) m.failAt("points", "times must strictly increase");
    return TimeFunction::table(std::move(p));
  } catch (const std::invalid_argument& e) {
    m.fail(e.what());
  }
}

// ---------------------------------------------------------------- sets
class SetResolver {
 public:
  SetResolver(const Model& model, const std::string& file) : model_(model), file_(file) {}

  void define(const std::string& name, YAML::Node sel, const std::string& path) {
    named_[name] = {std::move(sel), path};
  }

  std::vector<int> nodes(const YAML::Node& sel, const std::string& path) const {
    std::vector<int> out = nodesRaw(sel, path);
    sortUnique(out);
    if (out.empty()) throw InputError(locate(file_, sel, path) + ": selects no nodes");
    return out;
  }

  /// Resolves the set `name` as a node selection (through the memo and the cycle check).
  void resolveNamed(const std::string& name) const {
    const Named& set = named_.at(name);
    if (nodesByName(name, set.sel, set.path).empty())
      throw InputError(locate(file_, set.sel, set.path) + ": selects no nodes");
  }

  std::vector<int> triangles(const YAML::Node& sel, const std::string& path) const {
    std::vector<int> out = trianglesRaw(sel, path);
    sortUnique(out);
    if (out.empty()) throw InputError(locate(file_, sel, path) + ": selects no triangles");
    return out;
  }

 private:
  struct Named {
    YAML::Node sel;
    std::string path;
  };
  using Memo = std::map<std::string, std::vector<int>>;

  static void sortUnique(std::vector<int>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }

  // Appends a part of a union. Long unions (a list of sets that overlap, or one set listed many times) are
  // deduplicated on the way so that the list never grows much beyond the number of entities.
  static void append(std::vector<int>& out, const std::vector<int>& part, std::size_t entities) {
    out.insert(out.end(), part.begin(), part.end());
    if (out.size() > 2 * entities + 1024) sortUnique(out);
  }

  // A named set is resolved once per kind and remembered: sets built from one another in a chain cost one
  // resolution each, however deep the chain or often a set is used. `resolving_` holds the sets whose
  // resolution is under way, so a set met again there closes a cycle, which is reported with its members.
  template <class Resolve>
  std::vector<int> namedSet(const std::string& name, const Named& set, const YAML::Node& at,
                            const std::string& path, Memo& memo, Resolve resolve) const {
    if (const auto m = memo.find(name); m != memo.end()) return m->second;
    const auto open = std::find(resolving_.begin(), resolving_.end(), name);
    if (open != resolving_.end()) {
      std::string cycle;
      for (auto it = open; it != resolving_.end(); ++it) cycle += *it + " -> ";
      throw InputError(locate(file_, at, path) +
                       fmt::format(": sets refer to each other in a cycle: {}{}", cycle, name));
    }
    resolving_.push_back(name);
    std::vector<int> out;
    try {
      out = resolve(set.sel, set.path);
    } catch (...) {
      resolving_.pop_back();
      throw;
    }
    resolving_.pop_back();
    sortUnique(out);
    return memo.emplace(name, std::move(out)).first->second;
  }

  int meshIndex(const std::string& name, const YAML::Node& at, const std::string& path) const {
    for (std::size_t m = 0; m < model_.meshes.size(); ++m)
      if (model_.meshes[m].name == name) return int(m);
    std::vector<std::string> names;
    for (const auto& m : model_.meshes) names.push_back(m.name);
    for (const auto& kv : named_) names.push_back(kv.first);
    const std::string near = closestMatch(name, names);
    throw InputError(locate(file_, at, path) +
                     fmt::format(": no set or mesh named '{}'{}; known: {}", name,
                                 near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                 join(names)));
  }

  template <class Groups>
  static std::vector<std::string> groupNames(const Groups& g) {
    std::vector<std::string> n;
    for (const auto& kv : g) n.push_back(kv.first);
    return n;
  }

  std::vector<int> nodesOfTriangles(const std::vector<int>& tris) const {
    std::vector<int> out;
    for (int e : tris)
      for (int k = 0; k < 3; ++k) out.push_back(model_.membranes.conn[3 * e + k]);
    return out;
  }

  std::vector<int> nodesByName(const std::string& s, const YAML::Node& at, const std::string& path) const {
    if (auto it = named_.find(s); it != named_.end())
      return namedSet(s, it->second, at, path, nodeMemo_,
                      [this](const YAML::Node& sel, const std::string& p) { return nodesRaw(sel, p); });
    const auto slash = s.find('/');
    const int m = meshIndex(s.substr(0, slash), at, path);
    const MeshMap& mm = model_.meshes[m];
    if (slash == std::string::npos) return mm.node;
    const std::string g = s.substr(slash + 1);
    std::vector<int> out;
    if (auto it = mm.source.nodeGroups.find(g); it != mm.source.nodeGroups.end()) {
      for (int i : it->second) out.push_back(mm.node[i]);
    } else if (auto t = mm.source.triangleGroups.find(g); t != mm.source.triangleGroups.end()) {
      for (int i : t->second)
        for (int k = 0; k < 3; ++k) out.push_back(mm.node[mm.source.triangles[i][k]]);
    } else if (auto l = mm.source.lineGroups.find(g); l != mm.source.lineGroups.end()) {
      for (int i : l->second)
        for (int k = 0; k < 2; ++k) out.push_back(mm.node[mm.source.lines[i][k]]);
    } else {
      auto names = groupNames(mm.source.nodeGroups);
      for (auto& n : groupNames(mm.source.triangleGroups)) names.push_back(n);
      for (auto& n : groupNames(mm.source.lineGroups)) names.push_back(n);
      std::sort(names.begin(), names.end());
      names.erase(std::unique(names.begin(), names.end()), names.end());
      const std::string near = closestMatch(g, names);
      throw InputError(locate(file_, at, path) +
                       fmt::format(": mesh '{}' has no group '{}'{}; its groups: {}", mm.name, g,
                                   near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                   join(names)));
    }
    return out;
  }

  std::vector<int> trianglesByName(const std::string& s, const YAML::Node& at,
                                   const std::string& path) const {
    if (auto it = named_.find(s); it != named_.end())
      return namedSet(s, it->second, at, path, triangleMemo_,
                      [this](const YAML::Node& sel, const std::string& p) { return trianglesRaw(sel, p); });
    const auto slash = s.find('/');
    const int m = meshIndex(s.substr(0, slash), at, path);
    const MeshMap& mm = model_.meshes[m];
    std::vector<int> out;
    if (slash == std::string::npos) {
      for (int e : mm.triangle)
        if (e >= 0) out.push_back(e);
      return out;
    }
    const std::string g = s.substr(slash + 1);
    const auto it = mm.source.triangleGroups.find(g);
    if (it == mm.source.triangleGroups.end()) {
      const auto names = groupNames(mm.source.triangleGroups);
      const std::string near = closestMatch(g, names);
      throw InputError(locate(file_, at, path) +
                       fmt::format(": mesh '{}' has no triangle group '{}'{}; its triangle groups: {}",
                                   mm.name, g, near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                   join(names)));
    }
    for (int i : it->second) out.push_back(mm.triangle[i]);
    return out;
  }

  std::vector<int> nodesRaw(const YAML::Node& sel, const std::string& path) const {
    if (sel.IsScalar()) return nodesByName(sel.Scalar(), sel, path);
    if (sel.IsSequence()) {
      std::vector<int> out;
      for (std::size_t i = 0; i < sel.size(); ++i)
        append(out, nodesRaw(sel[i], fmt::format("{}[{}]", path, i)), std::size_t(model_.nodes.count));
      return out;
    }
    YamlMap m(sel, file_, path);
    const Nodes& N = model_.nodes;
    std::vector<int> out;
    if (m.has("plane")) {
      YamlMap p = m.map("plane");
      const auto pt = p.vec3("point");
      auto n = p.vec3("normal");
      p.finish({"point", "normal"});
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0)) p.failAt("normal", "must not be zero");
      const double tol = m.number("tolerance", 1e-9);
      std::vector<int> pool =
          m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
      if (!m.has("among")) {
        pool.resize(N.count);
        for (int i = 0; i < N.count; ++i) pool[i] = i;
      }
      for (int i : pool) {
        double d = 0;
        for (int k = 0; k < 3; ++k) d += (N.X[3 * i + k] - pt[k]) * n[k] / len;
        if (std::abs(d) <= tol) out.push_back(i);
      }
      m.finish({"plane", "tolerance", "among"});
    } else if (m.has("box")) {
      YamlMap b = m.map("box");
      const auto lo = b.vec3("min"), hi = b.vec3("max");
      b.finish({"min", "max"});
      std::vector<int> pool =
          m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
      if (!m.has("among")) {
        pool.resize(N.count);
        for (int i = 0; i < N.count; ++i) pool[i] = i;
      }
      for (int i : pool) {
        bool in = true;
        for (int k = 0; k < 3; ++k) in = in && N.X[3 * i + k] >= lo[k] && N.X[3 * i + k] <= hi[k];
        if (in) out.push_back(i);
      }
      m.finish({"box", "among"});
    } else if (m.has("nearest")) {
      const auto p = m.vec3("nearest");
      std::vector<int> pool =
          m.has("among") ? nodesRaw(m.raw("among"), m.childPath("among")) : std::vector<int>();
      if (!m.has("among")) {
        pool.resize(N.count);
        for (int i = 0; i < N.count; ++i) pool[i] = i;
      }
      int best = -1;
      double bd = std::numeric_limits<double>::infinity();
      for (int i : pool) {
        double d = 0;
        for (int k = 0; k < 3; ++k) d += (N.X[3 * i + k] - p[k]) * (N.X[3 * i + k] - p[k]);
        if (d < bd) bd = d, best = i;
      }
      if (best >= 0) out.push_back(best);
      m.finish({"nearest", "among"});
    } else if (m.has("ids")) {
      const std::string mesh = m.string("mesh");
      const int mi = meshIndex(mesh, m.node(), m.path());
      const MeshMap& mm = model_.meshes[mi];
      std::map<long, int> byTag;
      for (std::size_t i = 0; i < mm.node.size(); ++i)
        byTag[i < mm.source.pointTags.size() ? mm.source.pointTags[i] : long(i + 1)] = mm.node[i];
      for (long id :
           m.integers("ids", {std::numeric_limits<long>::min(), std::numeric_limits<long>::max()})) {
        auto it = byTag.find(id);
        if (it == byTag.end()) m.failAt("ids", fmt::format("mesh '{}' has no node {}", mesh, id));
        out.push_back(it->second);
      }
      m.finish({"ids", "mesh"});
    } else {
      m.fail(
          "a node selector is a set or mesh name ('mesh/group'), a list of them, or a mapping with one of: "
          "plane, box, nearest, ids");
    }
    return out;
  }

  std::vector<int> trianglesRaw(const YAML::Node& sel, const std::string& path) const {
    if (sel.IsScalar()) return trianglesByName(sel.Scalar(), sel, path);
    if (sel.IsSequence()) {
      std::vector<int> out;
      for (std::size_t i = 0; i < sel.size(); ++i)
        append(out, trianglesRaw(sel[i], fmt::format("{}[{}]", path, i)),
               std::size_t(model_.membranes.count));
      return out;
    }
    throw InputError(
        locate(file_, sel, path) +
        ": a triangle selector is a set or mesh name ('mesh' or 'mesh/group') or a list of them");
  }

  const Model& model_;
  std::string file_;
  std::map<std::string, Named> named_;
  mutable Memo nodeMemo_, triangleMemo_;
  mutable std::vector<std::string> resolving_;  // outermost first
};

int componentIndex(const YamlMap& m, const std::string& key, const std::vector<std::string>& allowed) {
  const std::string c = m.choice(key, allowed);
  static const std::vector<std::string> order{"x", "y", "z", "magnitude", "radial"};
  return int(std::find(order.begin(), order.end(), c) - order.begin());
}

// ---------------------------------------------------------------- the loader
Scene loadRoot(YAML::Node root, const std::string& fileName, const std::filesystem::path& dir) {
  Scene scene;
  scene.file = fileName;
  YamlMap top(root, fileName, "");
  scene.title = top.string("title", "");

  // Materials.
  std::map<std::string, int> membraneIdx, cableIdx;
  std::vector<MembraneMaterial> membraneMats;
  std::vector<CableMaterial> cableMats;
  {
    YamlMap mats = top.map("materials");
    for (const auto& name : mats.keys()) {
      YamlMap m = mats.map(name);
      const std::string type = m.choice("type", {"membrane", "cable"});
      if (type == "membrane") {
        MembraneMaterial mm;
        mm.name = name;
        mm.young = m.number("young");
        mm.poisson = m.number("poisson");
        mm.thickness = m.number("thickness");
        mm.density = m.number("density");
        mm.wrinkling = m.boolean("wrinkling", true);
        m.finish({"type", "young", "poisson", "thickness", "density", "wrinkling"});
        if (!(mm.young > 0)) m.failAt("young", "must be > 0");
        if (!(mm.poisson >= 0 && mm.poisson < 0.5)) m.failAt("poisson", "must be in [0, 0.5)");
        if (!(mm.thickness > 0)) m.failAt("thickness", "must be > 0");
        if (!(mm.density > 0) || !std::isnormal(mm.density))
          m.failAt("density",
                   "must be > 0 and at least 2.2e-308 (a smaller, subnormal density makes the lumped masses "
                   "underflow to 0)");
        membraneIdx[name] = int(membraneMats.size());
        membraneMats.push_back(mm);
      } else {
        CableMaterial cm;
        cm.name = name;
        cm.young = m.number("young");
        cm.area = m.number("area");
        cm.density = m.number("density");
        m.finish({"type", "young", "area", "density"});
        if (!(cm.young > 0)) m.failAt("young", "must be > 0");
        if (!(cm.area > 0)) m.failAt("area", "must be > 0");
        if (!(cm.density > 0) || !std::isnormal(cm.density))
          m.failAt("density",
                   "must be > 0 and at least 2.2e-308 (a smaller, subnormal density makes the lumped masses "
                   "underflow to 0)");
        cableIdx[name] = int(cableMats.size());
        cableMats.push_back(cm);
      }
    }
  }
  auto materialRef = [&](const YamlMap& m, const std::string& key, const std::map<std::string, int>& idx,
                         const std::string& kind) {
    const std::string n = m.string(key);
    const auto it = idx.find(n);
    if (it == idx.end()) {
      std::vector<std::string> names;
      for (const auto& kv : idx) names.push_back(kv.first);
      const std::string near = closestMatch(n, names);
      m.failAt(key, fmt::format("no {} material named '{}'{}; {} materials: {}", kind, n,
                                near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), kind,
                                names.empty() ? "(none defined)" : join(names)));
    }
    return it->second;
  };

  // Meshes.
  std::vector<MeshInput> inputs;
  // Where each mesh came from, for the model builder's messages (a degenerate triangle of mesh 'canopy' is
  // in canopy.msh, or in the scene's generator entry).
  std::vector<std::pair<std::string, std::string>> meshOrigins;
  {
    YamlMap meshes = top.map("meshes");
    if (meshes.keys().empty()) meshes.fail("at least one mesh is needed");
    for (const auto& name : meshes.keys()) {
      YamlMap m = meshes.map(name);
      MeshInput in;
      in.mesh = meshFromScene(m, name, dir);
      in.mesh.name = name;
      meshOrigins.emplace_back(name, m.has("file") ? (dir / m.string("file")).string() + " (" +
                                                         locate(m.file(), m.node(), "meshes." + name) + ")"
                                                   : locate(m.file(), m.node(), "meshes." + name));
      if (m.has("material")) in.membraneMaterial = materialRef(m, "material", membraneIdx, "membrane");
      if (m.has("cable_material")) in.cableMaterial = materialRef(m, "cable_material", cableIdx, "cable");
      m.finish({"file", "generator", "material", "cable_material"});
      if (!in.mesh.triangles.empty() && in.membraneMaterial < 0)
        m.fail("this mesh has triangles: give it a membrane 'material'");
      if (!in.mesh.lines.empty() && in.cableMaterial < 0)
        m.fail("this mesh has lines: give it a 'cable_material'");
      inputs.push_back(std::move(in));
    }
  }
  try {
    scene.model = std::make_unique<Model>(buildModel(std::move(inputs), membraneMats, cableMats));
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::string where = scene.file.string();
    for (const auto& [name, origin] : meshOrigins)
      if (what.find("mesh '" + name + "'") != std::string::npos) where = origin;
    throw InputError(where + ": " + what);
  }
  Model& model = *scene.model;

  // Solver: explicit dynamics (default) or dynamic relaxation.
  if (top.has("solver")) {
    YamlMap sv = top.map("solver");
    const std::string type = sv.choice("type", {"explicit_dynamics", "dynamic_relaxation"});
    if (type == "dynamic_relaxation") {
      SolverControl& sc = scene.solver;
      RelaxationSettings& rs = sc.relaxation;
      sc.type = SolverControl::Type::DynamicRelaxation;
      const std::string damping = sv.choice("damping", {"kinetic", "viscous"}, "kinetic");
      rs.damping =
          damping == "kinetic" ? RelaxationSettings::Damping::Kinetic : RelaxationSettings::Damping::Viscous;
      const std::string mass = sv.choice("mass", {"gerschgorin", "stress", "rezaiee_pajand"}, "gerschgorin");
      rs.mass = fictitiousMassRuleFromName(mass);
      const std::string coef = sv.choice("coefficient", {"underwood", "rezaiee_pajand"}, "underwood");
      rs.coefficient = coef == "underwood" ? RelaxationSettings::Coefficient::Underwood
                                           : RelaxationSettings::Coefficient::RezaiePajand;
      rs.lambda = sv.number("lambda", 0.0);
      if (rs.lambda < 0) sv.failAt("lambda", "must be > 0 (or absent for the default)");
      rs.backstep = sv.boolean("backstep", true);
      rs.tolerance = sv.number("tolerance", 1e-3);
      if (!(rs.tolerance > 0)) sv.failAt("tolerance", "must be > 0");
      rs.maxIterations = sv.integer("max_iterations", 200000, {1, std::numeric_limits<long>::max()});
      if (rs.maxIterations < 1) sv.failAt("max_iterations", "must be >= 1");
      rs.increments = int(sv.integer("increments", 1, {1, std::numeric_limits<int>::max()}));
      if (rs.increments < 1) sv.failAt("increments", "must be >= 1");
      rs.loadTime = sv.number("load_time", 0.0);
      rs.autoMass = sv.boolean("auto_mass", true);
      rs.updateMasses = sv.boolean("update_masses", false);
      sv.finish({"type", "damping", "mass", "coefficient", "lambda", "backstep", "tolerance",
                 "max_iterations", "increments", "load_time", "auto_mass", "update_masses"});
      if (rs.damping == RelaxationSettings::Damping::Kinetic)
        sc.method = rs.mass == FictitiousMassRule::StressBound   ? "KDR1"
                    : rs.mass == FictitiousMassRule::Gerschgorin ? "KDR"
                                                                 : "KDR-RP";
      else
        sc.method = std::string(rs.mass == FictitiousMassRule::RezaiePajand ? "m" : "o") +
                    (rs.coefficient == RelaxationSettings::Coefficient::RezaiePajand ? "dDR" : "DR");
    } else {
      sv.finish({"type"});
    }
  }
  const bool relaxation = scene.solver.type == SolverControl::Type::DynamicRelaxation;

  // Time control (mass scaling must precede the effects, which cache wave speeds).
  if (relaxation) {
    if (top.has("time")) top.failAt("time", "a dynamic-relaxation scene has no time control (see 'solver')");
  } else if (!top.has("time") && top.has("coupling")) {
    // The structural side of a coupled run: the flow solver sets the end; the step is automatic.
    scene.time.endTime = std::numeric_limits<double>::infinity();
  } else {
    YamlMap t = top.map("time");
    TimeControl& tc = scene.time;
    if (t.has("until_static")) {
      YamlMap s = t.map("until_static");
      tc.untilStatic = true;
      tc.staticTolerance = s.number("tolerance", 1e-8);
      tc.endTime = s.number("max_time");
      s.finish({"tolerance", "max_time"});
      if (!(tc.staticTolerance > 0)) s.failAt("tolerance", "must be > 0");
      if (t.has("end")) t.failAt("end", "give either 'end' or 'until_static', not both");
    } else if (top.has("coupling") && !t.has("end")) {
      tc.endTime = std::numeric_limits<double>::infinity();  // set by the flow solver
    } else {
      tc.endTime = t.number("end");
    }
    if (!(tc.endTime > 0)) t.fail("the end time (or until_static.max_time) must be > 0");
    tc.integrator.safety = t.number("safety", 0.9);
    if (!(tc.integrator.safety > 0 && tc.integrator.safety <= 1.0)) t.failAt("safety", "must be in (0, 1]");
    tc.integrator.fixedDt = t.number("fixed_dt", 0.0);
    if (tc.integrator.fixedDt < 0) t.failAt("fixed_dt", "must be > 0 (or absent for the automatic step)");
    tc.integrator.maxDt = t.number("max_dt", 1e300);
    if (!(tc.integrator.maxDt > 0)) t.failAt("max_dt", "must be > 0");
    tc.monitorEvery = t.integer("monitor_every", 100, {1, std::numeric_limits<long>::max()});
    if (tc.monitorEvery < 1) t.failAt("monitor_every", "must be >= 1");
    tc.energyTolerance = t.number("energy_tolerance", 0.05);
    if (!(tc.energyTolerance > 0)) t.failAt("energy_tolerance", "must be > 0");
    tc.massScalingMinDt = t.number("mass_scaling_min_dt", 0.0);
    if (tc.massScalingMinDt < 0) t.failAt("mass_scaling_min_dt", "must be >= 0");
    t.finish({"end", "until_static", "safety", "fixed_dt", "max_dt", "monitor_every", "energy_tolerance",
              "mass_scaling_min_dt"});
    if (tc.massScalingMinDt > 0)
      scene.massScaling = applyMassScaling(model, tc.massScalingMinDt, tc.integrator.safety);
  }

  // Named sets.
  SetResolver sets(model, fileName);
  if (top.has("sets")) {
    YamlMap s = top.map("sets");
    for (const auto& name : s.keys()) {
      for (const auto& m : model.meshes)
        if (m.name == name) s.failAt(name, "a set may not have the name of a mesh");
      sets.define(name, s.raw(name), s.childPath(name));
    }
    // Resolve every set once, used or not, so that a typo in an unused set is still reported.
    for (const auto& name : s.keys()) {
      const YAML::Node sel = s.node()[name];
      if (sel.IsScalar() || sel.IsSequence() || sel.IsMap()) sets.resolveNamed(name);
    }
  }

  // Constraints.
  if (top.has("constraints")) {
    const YAML::Node list = top.raw("constraints");
    if (!list.IsSequence()) top.failAt("constraints", "expected a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      YamlMap c(list[i], fileName, fmt::format("constraints[{}]", i));
      if (c.has("fix")) {
        const auto nodes = sets.nodes(c.required("nodes"), c.childPath("nodes"));
        for (const auto& comp : c.strings("fix")) {
          static const std::vector<std::string> valid{"x", "y", "z", "all"};
          if (std::find(valid.begin(), valid.end(), comp) == valid.end())
            c.failAt("fix", fmt::format("'{}' is not a component; valid: x, y, z, all", comp));
          for (int n : nodes)
            for (int k = 0; k < 3; ++k)
              if (comp == "all" || comp == valid[k]) scene.constraints.fixedDofs.push_back(3 * n + k);
        }
        c.finish({"nodes", "fix"});
      } else if (c.has("symmetry")) {
        YamlMap s = c.map("symmetry");
        const auto pt = s.vec3("point", {0, 0, 0});
        auto n = s.vec3("normal");
        const double tol = s.number("tolerance", 1e-9);
        s.finish({"point", "normal", "tolerance"});
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0)) s.failAt("normal", "must not be zero");
        for (auto& v : n) v /= len;
        int axis = -1;
        for (int k = 0; k < 3; ++k)
          if (std::abs(std::abs(n[k]) - 1.0) < 1e-14) axis = k;
        int count = 0;
        const Nodes& N = model.nodes;
        for (int j = 0; j < N.count; ++j) {
          double d = 0;
          for (int k = 0; k < 3; ++k) d += (N.X[3 * j + k] - pt[k]) * n[k];
          if (std::abs(d) > tol) continue;
          ++count;
          if (axis >= 0)
            scene.constraints.fixedDofs.push_back(3 * j + axis);
          else
            scene.constraints.sliders.push_back({j, n});
        }
        if (count == 0) c.failAt("symmetry", "no node lies on this plane (check point, normal, tolerance)");
        c.finish({"symmetry"});
      } else if (c.has("prescribe")) {
        const auto nodes = sets.nodes(c.required("nodes"), c.childPath("nodes"));
        YamlMap p = c.map("prescribe");
        const int comp = componentIndex(p, "component", {"x", "y", "z"});
        const double amp = p.number("amplitude");
        const TimeFunction fn = readTimeFunction(p, "function");
        p.finish({"component", "amplitude", "function"});
        for (int n : nodes) scene.constraints.prescribed.push_back({n, comp, amp, fn});
        c.finish({"nodes", "prescribe"});
      } else {
        c.fail("a constraint needs one of: fix (with nodes), symmetry, prescribe (with nodes)");
      }
    }
    auto& f = scene.constraints.fixedDofs;
    std::sort(f.begin(), f.end());
    f.erase(std::unique(f.begin(), f.end()), f.end());
  }

  // Effects: only what is listed here is ever computed.
  MembraneViscosity mv;
  CableViscosity cv;
  std::vector<std::unique_ptr<Effect>> loads;
  if (top.has("effects")) {
    YamlMap fx = top.map("effects");
    if (fx.has("mass_damping") && relaxation)
      fx.failAt("mass_damping",
                "dynamic relaxation brings its own damping (solver.damping); remove this effect");
    if (fx.has("mass_damping")) {
      YamlMap d = fx.map("mass_damping");
      scene.time.integrator.massDamping = d.number("alpha");
      d.finish({"alpha"});
      if (!(scene.time.integrator.massDamping >= 0)) d.failAt("alpha", "must be >= 0");
      scene.enabledEffects.push_back("mass_damping");
    }
    if (fx.has("stiffness_damping")) {
      YamlMap d = fx.map("stiffness_damping");
      mv.beta = cv.beta = d.number("beta");
      d.finish({"beta"});
      if (!(mv.beta >= 0)) d.failAt("beta", "must be >= 0");
      scene.enabledEffects.push_back("stiffness_damping");
    }
    if (fx.has("bulk_viscosity")) {
      YamlMap d = fx.map("bulk_viscosity");
      mv.bulkB1 = cv.bulkB1 = d.number("b1", 0.06);
      d.finish({"b1"});
      if (!(mv.bulkB1 >= 0)) d.failAt("b1", "must be >= 0");
      scene.enabledEffects.push_back("bulk_viscosity");
    }
    if (fx.has("gravity")) {
      YamlMap g = fx.map("gravity");
      const auto acc = g.vec3("acceleration");
      const TimeFunction fn = readTimeFunction(g, "function");
      g.finish({"acceleration", "function"});
      loads.push_back(std::make_unique<Gravity>(model.nodes.physicalMass, acc, fn));
      scene.enabledEffects.push_back("gravity");
    }
    auto listOf = [&](const std::string& key) {
      const YAML::Node n = fx.raw(key);
      std::vector<YamlMap> out;
      if (n.IsSequence()) {
        for (std::size_t i = 0; i < n.size(); ++i)
          out.emplace_back(n[i], fileName, fmt::format("{}[{}]", fx.childPath(key), i));
      } else {
        out.emplace_back(n, fileName, fx.childPath(key));
      }
      return out;
    };
    if (fx.has("pressure")) {
      for (const YamlMap& p : listOf("pressure")) {
        const auto tris = sets.triangles(p.required("triangles"), p.childPath("triangles"));
        const double value = p.number("value");
        const TimeFunction fn = readTimeFunction(p, "function");
        p.finish({"triangles", "value", "function"});
        std::vector<int> conn;
        for (int e : tris)
          for (int k = 0; k < 3; ++k) conn.push_back(model.membranes.conn[3 * e + k]);
        const std::string label =
            p.node()["triangles"].IsScalar() ? p.node()["triangles"].Scalar() : p.path();
        loads.push_back(std::make_unique<FollowerPressure>(label, std::move(conn), value, fn));
      }
      scene.enabledEffects.push_back("pressure");
    }
    if (fx.has("nodal_forces")) {
      for (const YamlMap& p : listOf("nodal_forces")) {
        const auto nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
        const auto f = p.vec3("force");
        const TimeFunction fn = readTimeFunction(p, "function");
        p.finish({"nodes", "force", "function"});
        loads.push_back(std::make_unique<NodalForces>(p.path(), nodes, f, fn));
      }
      scene.enabledEffects.push_back("nodal_forces");
    }
    fx.finish({"mass_damping", "stiffness_damping", "bulk_viscosity", "gravity", "pressure", "nodal_forces"});
  }
  if (model.membranes.count > 0) {
    auto m = std::make_unique<MembraneForces>(model.membranes, mv);
    scene.membrane = m.get();
    scene.effects.push_back(std::move(m));
    scene.enabledEffects.insert(scene.enabledEffects.begin(), "membrane");
  }
  if (model.cables.count > 0) {
    auto c = std::make_unique<CableForces>(model.cables, cv);
    scene.cable = c.get();
    scene.effects.push_back(std::move(c));
    scene.enabledEffects.insert(scene.enabledEffects.begin(), "cable");
  }
  for (auto& l : loads) scene.effects.push_back(std::move(l));

  // Coupling: the triangles that receive the flow's load (the coupling participant adds their effect).
  if (top.has("coupling")) {
    YamlMap c = top.map("coupling");
    const auto tris = sets.triangles(c.required("interface"), c.childPath("interface"));
    const std::string rule = c.choice("load_in_window", {"mean", "end", "linear"}, "mean");
    c.finish({"interface", "load_in_window"});
    Scene::CouplingInterface ci;
    ci.loadInWindow = rule == "mean"  ? LoadInterpolation::ConstantMean
                      : rule == "end" ? LoadInterpolation::ConstantEnd
                                      : LoadInterpolation::Linear;
    for (int e : tris)
      for (int k = 0; k < 3; ++k) ci.triangles.push_back(model.membranes.conn[3 * e + k]);
    ci.nodes = ci.triangles;
    std::sort(ci.nodes.begin(), ci.nodes.end());
    ci.nodes.erase(std::unique(ci.nodes.begin(), ci.nodes.end()), ci.nodes.end());
    scene.couplingInterface = std::move(ci);
  }

  // Output.
  if (top.has("output")) {
    YamlMap o = top.map("output");
    scene.output.interval = o.number("interval", 0.0);
    if (scene.output.interval < 0) o.failAt("interval", "must be >= 0");
    if (scene.output.interval > 0 && !std::isnormal(scene.output.interval))
      o.failAt("interval", "must be 0 (every step) or at least 2.2e-308 (a subnormal interval is no time)");
    if (o.has("fields")) {
      for (const auto& f : o.strings("fields")) {
        const auto& all = allOutputFields();
        if (std::find(all.begin(), all.end(), f) == all.end()) {
          const std::string near = closestMatch(f, all);
          o.failAt("fields",
                   fmt::format("unknown field '{}'{}; valid: {}", f,
                               near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), join(all)));
        }
        scene.output.fields.insert(f);
      }
    } else {
      scene.output.fields.insert(allOutputFields().begin(), allOutputFields().end());
    }
    o.finish({"interval", "fields"});
  }

  if (scene.output.fields.empty() && !top.has("output"))
    scene.output.fields.insert(allOutputFields().begin(), allOutputFields().end());

  // Probes.
  if (top.has("probes")) {
    YamlMap ps = top.map("probes");
    for (const auto& name : ps.keys()) {
      // The name becomes a column of /tables/probes in results.h5 (next to 'time') and a key of summary.json.
      if (name.empty() || name == "." || name == "time" || name.find('/') != std::string::npos ||
          std::any_of(name.begin(), name.end(), [](char ch) { return (ch >= 0 && ch < 0x20) || ch == 0x7F; }))
        ps.failAt(name, fmt::format("'{}' cannot name a probe: it must be non-empty, not 'time' or '.', and "
                                    "without '/' or control characters",
                                    name));
      YamlMap p = ps.map(name);
      ProbeSpec spec;
      spec.name = name;
      const std::string type = p.choice("type", {"displacement", "position", "reaction", "volume", "stress"});
      const std::map<std::string, ProbeSpec::Reduce> reduces{{"value", ProbeSpec::Reduce::Value},
                                                             {"mean", ProbeSpec::Reduce::Mean},
                                                             {"max", ProbeSpec::Reduce::Max},
                                                             {"min", ProbeSpec::Reduce::Min},
                                                             {"sum", ProbeSpec::Reduce::Sum}};
      if (type == "displacement" || type == "position") {
        spec.type = type == "position" ? ProbeSpec::Type::Position : ProbeSpec::Type::Displacement;
        spec.nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
        spec.component = componentIndex(p, "component", {"x", "y", "z", "magnitude", "radial"});
        spec.center = p.vec3("center", {0, 0, 0});
        spec.reduce = reduces.at(p.choice("reduce", {"value", "mean", "max", "min"}, "value"));
        if (spec.reduce == ProbeSpec::Reduce::Value && spec.nodes.size() != 1)
          p.failAt("nodes",
                   fmt::format("selects {} nodes; 'reduce: value' needs exactly one (use nearest, or "
                               "reduce: mean | max | min)",
                               spec.nodes.size()));
        p.finish({"type", "nodes", "component", "center", "reduce"});
      } else if (type == "reaction") {
        spec.type = ProbeSpec::Type::Reaction;
        spec.reduce = ProbeSpec::Reduce::Sum;
        spec.nodes = sets.nodes(p.required("nodes"), p.childPath("nodes"));
        spec.component = componentIndex(p, "component", {"x", "y", "z", "magnitude"});
        p.finish({"type", "nodes", "component"});
      } else if (type == "volume") {
        spec.type = ProbeSpec::Type::Volume;
        spec.triangles = sets.triangles(p.required("triangles"), p.childPath("triangles"));
        spec.center = p.vec3("center", {0, 0, 0});
        p.finish({"type", "triangles", "center"});
      } else {
        spec.type = ProbeSpec::Type::Stress;
        spec.triangles = sets.triangles(p.required("triangles"), p.childPath("triangles"));
        spec.quantity = p.choice("quantity", {"max_principal", "min_principal"}, "max_principal");
        spec.reduce = reduces.at(p.choice("reduce", {"max", "min", "mean"}, "max"));
        p.finish({"type", "triangles", "quantity", "reduce"});
      }
      scene.probes.push_back(std::move(spec));
    }
  }

  top.finish({"title", "materials", "meshes", "sets", "constraints", "effects", "solver", "time", "output",
              "probes"});
  return scene;
}

}  // namespace

Scene loadSceneFromString(const std::string& yaml, const std::string& name,
                          const std::vector<std::string>& overrides) {
  requireUtf8Text(yaml, name);
  YAML::Node root = parseDocument(yaml, name);
  for (const auto& o : overrides) applyOverride(root, o);
  checkDocument(root, name);  // after the overrides, so that their values are checked too
  return loadRoot(root, name, std::filesystem::path(name).parent_path());
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(fmt::format("{}: is a directory, not a scene file", file.string()));
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open scene file", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read scene file", file.string()));
  return loadSceneFromString(ss.str(), file.string(), overrides);
}

}  // namespace fsi::structure
