#include "coupling/scheme/CouplingOptions.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <sstream>

#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MappingDefaults.hpp"
#include "coupling/scheme/Equilibrium.hpp"
#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"
#include "structure/scene/NearestName.hpp"

namespace fsi::coupling {
namespace {

std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string join(const std::vector<std::string>& words, const std::string& sep) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) out += (i ? sep : "") + words[i];
  return out;
}

// The tokens as the user wrote them, near enough: "(a b)" rather than "( a b )".
std::string display(const std::vector<std::string>& tokens) {
  std::string out;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const bool glue = i == 0 || tokens[i - 1] == "(" || tokens[i] == ")";
    out += (glue ? "" : " ") + tokens[i];
  }
  return out;
}

const std::vector<std::string>& switchWords(bool value) {
  // OpenFOAM's Switch words, so that every value OpenFOAM would read still reads.
  static const std::vector<std::string> yes{"yes", "on", "true", "y", "t", "any"};
  static const std::vector<std::string> no{"no", "off", "false", "n", "f", "none"};
  return value ? yes : no;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

[[noreturn]] void fail(const OptionSpec& spec, const std::vector<std::string>& tokens,
                       const std::string& what) {
  std::string msg = "option '" + spec.key + "' = " + (tokens.empty() ? "(nothing)" : display(tokens)) + " " +
                    what + "; valid: " + spec.rangeText();
  if (!spec.description.empty()) msg += " (" + spec.description + ")";
  throw OptionError(spec.key, msg);
}

bool inRange(const OptionSpec& s, double v) {
  if (s.lower && (s.lower->inclusive ? v < s.lower->value : v <= s.lower->value)) return false;
  if (s.upper && (s.upper->inclusive ? v > s.upper->value : v >= s.upper->value)) return false;
  return true;
}

OptionValues::Value parse(const OptionSpec& spec, const std::vector<std::string>& tokens) {
  OptionValues::Value v;
  v.type = spec.type;
  if (spec.type == OptionType::Any) {
    v.words = tokens;
    return v;
  }
  if (tokens.empty()) fail(spec, tokens, "has no value");
  if (spec.type == OptionType::WordList) {
    // A single word, or [count] ( words ).
    std::size_t i = 0;
    long count = -1;
    if (tokens.size() > 1 && std::isdigit(static_cast<unsigned char>(tokens[0][0])))
      count = std::atol(tokens[i++].c_str());
    if (tokens.size() == 1 && tokens[0] != "(" && tokens[0] != ")") {
      v.words = tokens;
      return v;
    }
    if (tokens[i] != "(" || tokens.back() != ")") fail(spec, tokens, "is not a list of words");
    for (++i; i + 1 < tokens.size(); ++i) {
      if (tokens[i] == "(" || tokens[i] == ")") fail(spec, tokens, "is not a flat list of words");
      v.words.push_back(tokens[i]);
    }
    if (v.words.empty()) fail(spec, tokens, "is an empty list");
    if (count >= 0 && count != long(v.words.size()))
      fail(spec, tokens, "has a count that does not match its list");
    return v;
  }
  if (tokens.size() != 1) fail(spec, tokens, "is not a single value");
  const std::string& t = tokens[0];
  switch (spec.type) {
    case OptionType::Switch:
      if (contains(switchWords(true), t))
        v.flag = true;
      else if (contains(switchWords(false), t))
        v.flag = false;
      else
        fail(spec, tokens, "is not a switch");
      return v;
    case OptionType::Integer:
    case OptionType::Real: {
      if (contains(spec.choices, t)) {  // a word the number may be replaced by (`auto`)
        v.words = tokens;
        return v;
      }
      const bool integer = spec.type == OptionType::Integer;
      char* end = nullptr;
      errno = 0;
      double x = 0;
      if (integer) {
        const long n = std::strtol(t.c_str(), &end, 10);
        x = double(n);
      } else {
        x = std::strtod(t.c_str(), &end);
      }
      if (end == t.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(x))
        fail(spec, tokens, integer ? "is not an integer" : "is not a number");
      if (!inRange(spec, x)) fail(spec, tokens, "is out of range");
      v.number = x;
      return v;
    }
    case OptionType::Choice:
      if (!contains(spec.choices, t)) {
        std::string what = "is not a valid choice";
        const std::string near = fsi::nearestName(t, spec.choices);
        if (!near.empty()) what += " (did you mean '" + near + "'?)";
        fail(spec, tokens, what);
      }
      v.words = tokens;
      return v;
    case OptionType::Text:
      v.words = tokens;
      return v;
    default:
      return v;
  }
}

bool holds(const OptionCondition& c, const std::string& value, bool given) {
  return c.values.empty() ? given : contains(c.values, value);
}

}  // namespace

const char* toString(OptionType t) {
  switch (t) {
    case OptionType::Switch:
      return "switch";
    case OptionType::Integer:
      return "integer";
    case OptionType::Real:
      return "real";
    case OptionType::Choice:
      return "word";
    case OptionType::Text:
      return "file name";
    case OptionType::WordList:
      return "word list";
    case OptionType::Any:
      return "any";
  }
  return "?";
}

std::string OptionSpec::rangeText() const {
  switch (type) {
    case OptionType::Switch:
      return "yes or no (on/off, true/false)";
    case OptionType::Choice:
      return "one of " + join(choices, " ");
    case OptionType::Text:
      return "one word or quoted string";
    case OptionType::WordList:
      return "a list of words, e.g. (a b)";
    case OptionType::Any:
      return "anything";
    case OptionType::Integer:
    case OptionType::Real: {
      const std::string kind = type == OptionType::Integer ? "integer" : "number";
      const std::string words = choices.empty() ? "" : join(choices, " or ") + ", or ";
      if (lower && upper)
        return words + (type == OptionType::Integer ? "integer, " : "") + number(lower->value) +
               (lower->inclusive ? " <= " : " < ") + key + (upper->inclusive ? " <= " : " < ") +
               number(upper->value);
      if (lower)
        return words + (type == OptionType::Integer ? "integer, " : "") + key +
               (lower->inclusive ? " >= " : " > ") + number(lower->value);
      if (upper)
        return words + (type == OptionType::Integer ? "integer, " : "") + key +
               (upper->inclusive ? " <= " : " < ") + number(upper->value);
      return words + "any " + kind;
    }
  }
  return {};
}

std::string OptionSpec::defaultText() const {
  if (!defaultValue.empty()) return defaultValue;
  if (!defaultNote.empty()) return "computed: " + defaultNote;
  return required ? "required" : "none";
}

// ---------------------------------------------------------------------------------------------------------

const OptionValues::Value& OptionValues::at(const std::string& key, const char* what) const {
  const auto it = values_.find(key);
  if (it == values_.end())
    throw std::logic_error("OptionValues: " + std::string(what) + " of '" + key + "', which has no value");
  return it->second;
}
bool OptionValues::given(const std::string& key) const {
  const auto it = values_.find(key);
  return it != values_.end() && it->second.given;
}
bool OptionValues::has(const std::string& key) const {
  return values_.count(key) > 0;
}
double OptionValues::real(const std::string& key) const {
  return at(key, "real").number;
}
long OptionValues::integer(const std::string& key) const {
  return long(at(key, "integer").number);
}
bool OptionValues::isWord(const std::string& key) const {
  return !at(key, "number or word").words.empty();
}
bool OptionValues::flag(const std::string& key) const {
  return at(key, "flag").flag;
}
const std::string& OptionValues::text(const std::string& key) const {
  const Value& v = at(key, "text");
  if (v.words.size() != 1) throw std::logic_error("OptionValues: '" + key + "' is not a single word");
  return v.words.front();
}
std::vector<std::string> OptionValues::words(const std::string& key) const {
  return at(key, "words").words;
}

// ---------------------------------------------------------------------------------------------------------

OptionSchema& OptionSchema::add(OptionSpec spec) {
  specs_.push_back(std::move(spec));
  return *this;
}
OptionSchema& OptionSchema::add(const std::vector<OptionSpec>& specs) {
  for (const OptionSpec& s : specs) add(s);
  return *this;
}

std::vector<std::string> OptionSchema::keys() const {
  std::vector<std::string> out;
  for (const OptionSpec& s : specs_)
    if (!contains(out, s.key)) out.push_back(s.key);
  return out;
}

std::string OptionSchema::conditionValue(const std::string& key, const OptionTokens& tokens) const {
  for (const auto& [k, t] : tokens)
    if (k == key) return t.size() == 1 ? t[0] : display(t);
  for (const OptionSpec& s : specs_)
    if (s.key == key) return s.defaultValue;
  return {};
}

const OptionSpec* OptionSchema::applicable(const std::string& key, const OptionTokens& tokens) const {
  for (const OptionSpec& s : specs_) {
    if (s.key != key) continue;
    bool ok = true;
    for (const OptionCondition& c : s.when) {
      const bool given =
          std::any_of(tokens.begin(), tokens.end(), [&](const auto& kt) { return kt.first == c.key; });
      ok = ok && holds(c, conditionValue(c.key, tokens), given);
    }
    if (ok) return &s;
  }
  return nullptr;
}

OptionValues OptionSchema::validate(const OptionTokens& tokens) const {
  const std::vector<std::string> all = keys();
  std::vector<std::string> ours, host;
  for (const OptionSpec& s : specs_)
    if (!contains(ours, s.key) && !contains(host, s.key)) (s.host ? host : ours).push_back(s.key);
  std::set<std::string> seen;
  for (const auto& [key, toks] : tokens) {
    if (!contains(all, key))
      throw OptionError(key, "unknown option '" + key + "'; did you mean '" + fsi::nearestName(key, all) +
                                 "'? Valid options: " + join(ours, " ") +
                                 (host.empty() ? "" : " (and " + hostName_ + "'s: " + join(host, " ") + ")"));
    if (!seen.insert(key).second) throw OptionError(key, "option '" + key + "' is given twice");
    for (const OptionSpec& s : specs_)
      if (s.key == key && !s.refusal.empty())
        throw OptionError(key, "option '" + key + "' cannot be used here: " + s.refusal);
  }

  OptionValues out;
  for (const auto& [key, toks] : tokens) {
    const OptionSpec* spec = applicable(key, tokens);
    if (!spec) {
      // Given but without effect: check it against the spec it is closest to applying, and say why.
      std::size_t fewest = std::numeric_limits<std::size_t>::max();
      std::vector<std::string> failing, needed;
      for (const OptionSpec& s : specs_) {
        if (s.key != key) continue;
        std::vector<std::string> f, n;
        for (const OptionCondition& c : s.when) {
          const bool given =
              std::any_of(tokens.begin(), tokens.end(), [&](const auto& kt) { return kt.first == c.key; });
          const std::string value = conditionValue(c.key, tokens);
          if (holds(c, value, given)) continue;
          f.push_back(c.values.empty() ? "without " + c.key : c.key + " " + value);
          n.push_back(c.values.empty() ? c.key : c.key + " " + join(c.values, " or "));
        }
        if (f.size() < fewest) {
          fewest = f.size();
          spec = &s;
          failing = f;
          needed = n;
        }
      }
      out.warnings_.push_back("option '" + key + "' has no effect " +
                              (failing.front().rfind("without ", 0) == 0 ? "" : "with ") +
                              join(failing, " and ") + " (it needs " + join(needed, " and ") + ")");
    }
    OptionValues::Value v = parse(*spec, toks);
    v.given = true;
    out.values_[key] = std::move(v);
  }
  for (const std::string& key : all) {
    if (out.values_.count(key)) continue;
    for (const OptionSpec& s : specs_)
      if (s.key == key && s.required)
        throw OptionError(key,
                          "option '" + key + "' is required: " + s.description + " (" + s.rangeText() + ")");
    const OptionSpec* spec = applicable(key, tokens);
    if (spec && !spec->defaultValue.empty()) out.values_[key] = parse(*spec, {spec->defaultValue});
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------------------
// The tables. Why each range:
//   omega in (0, 1]: on an added-mass problem every eigenvalue of the iteration Jacobian is -lambda <= 0, so
//     relaxation with omega > 1 contracts no mode better than omega = 1 does (docs/COUPLING.md); Aitken
//     clamps to 1 for the same reason. 0 would never move.
//   tolerance in (0, 1): a relative residual; 1 or more accepts any first iterate, 0 never converges.
//   maxIterations >= 1, reuse >= 0, extrapolation 0..2 (the predictors CouplingScheme has), subcycles >= 1.
//   rho, mapTolerance > 0: a density and a distance.
//   equilibriumSteps >= 1 (EquilibriumStructure); loadRelaxation in (0, 1]: 1 hands over the fluid's load
//     unchanged, 0 would never let it in, and beyond 1 it over-relaxes an oscillating feedback further.

OptionSpec realOption(std::string key, std::string def, std::optional<Bound> lo, std::optional<Bound> hi,
                      std::string description) {
  OptionSpec s;
  s.key = std::move(key);
  s.type = OptionType::Real;
  s.defaultValue = std::move(def);
  s.lower = lo;
  s.upper = hi;
  s.description = std::move(description);
  return s;
}

OptionSpec integerOption(std::string key, std::string def, std::optional<Bound> lo, std::optional<Bound> hi,
                         std::string description) {
  OptionSpec s = realOption(std::move(key), std::move(def), lo, hi, std::move(description));
  s.type = OptionType::Integer;
  return s;
}

OptionSpec omegaOption(const std::string& def, const std::string& description) {
  return realOption("omega", def, Bound{0, false}, Bound{1, true}, description);
}

namespace {

OptionSpec wordSpec(std::string key, OptionType type, std::string def, std::vector<std::string> choices,
                    std::string description) {
  OptionSpec s;
  s.key = std::move(key);
  s.type = type;
  s.defaultValue = std::move(def);
  s.choices = std::move(choices);
  s.description = std::move(description);
  return s;
}

const OptionCondition kWithScene{"scene", {}};
const OptionCondition kImplicit{"scheme", {"implicit"}};
const OptionCondition kTimeAccurate{"structureMode", {"timeAccurate"}};
const OptionCondition kEquilibrium{"structureMode", {"equilibrium"}};

}  // namespace

OptionSchema couplingOptionSchema() {
  OptionSchema s;
  OptionSpec patches = wordSpec("patches", OptionType::WordList, "", {},
                                "interface patches; several map onto one structure (baffle pair)");
  patches.required = true;
  s.add(patches);
  OptionSpec rho = realOption("rho", "", Bound{0, false}, std::nullopt,
                              "fluid density [kg/m3] (the incompressible solvers' p is kinematic)");
  rho.required = true;
  s.add(rho);
  s.add(realOption("pRef", "0", std::nullopt, std::nullopt,
                   "reference pressure [Pa] subtracted from the fluid's"));
  s.add(wordSpec("viscous", OptionType::Switch, "no", {}, "add the viscous traction of the solver's model"));
  s.add(
      wordSpec("scene", OptionType::Text, "", {},
               "structure scene (with coupling: {interface: ...}); without it: monitor the interface force"));

  std::vector<OptionSpec> coupled;
  coupled.push_back(wordSpec("scheme", OptionType::Choice, "staggered", {"staggered", "implicit"},
                             "staggered: one pass per window; implicit: iterate each window to convergence"));
  std::vector<std::string> names;
  for (const AccelerationEntry& a : accelerationEntries()) names.push_back(a.name);
  OptionSpec acceleration = wordSpec("acceleration", OptionType::Choice, "IQN-ILS", names,
                                     "how the implicit scheme chooses the next interface displacement");
  acceleration.when = {kImplicit};
  coupled.push_back(acceleration);
  for (const AccelerationEntry& a : accelerationEntries())
    for (OptionSpec o : a.options) {
      o.when.insert(o.when.begin(), {kImplicit, {"acceleration", {a.name}}});
      coupled.push_back(o);
    }
  OptionSpec tolerance = realOption("tolerance", "1e-5", Bound{0, false}, Bound{1, false},
                                    "relative interface-displacement residual that ends a window");
  tolerance.when = {kImplicit};
  coupled.push_back(tolerance);
  OptionSpec maxIterations =
      integerOption("maxIterations", "30", Bound{1, true}, std::nullopt, "iterations per window at most");
  maxIterations.when = {kImplicit};
  coupled.push_back(maxIterations);
  coupled.push_back(integerOption("extrapolation", "1", Bound{0, true}, Bound{2, true},
                                  "predictor order of a window's first displacement (staggered: stability)"));
  // The projection's defaults are the one set `fsi map-check` uses too (coupledRunProjection(); why these:
  // docs/PROJECTION.md, "Defaults in a coupled run").
  const ProjectionOptions run = coupledRunProjection();
  coupled.push_back(
      wordSpec("projection", OptionType::Choice, toString(run.mass), massMatrixNames(),
               "L2 projection between the non-matching interface meshes (auto: consistent up to "
               "5000 fluid points, dual above); its transpose carries the loads"));
  coupled.push_back(
      wordSpec("evaluation", OptionType::Choice, toString(run.evaluation), {"pointwise", "l2"},
               "displacement to the fluid: pointwise (each fluid point at its closest structure "
               "point: nearest projection) or l2 (the L2 projection)"));
  OptionSpec quadrature = integerOption(
      "quadratureLevel",
      run.quadratureLevel == kAutoQuadrature ? "auto" : std::to_string(run.quadratureLevel), Bound{1, true},
      Bound{double(kMaxQuadratureLevel), true},
      "sub-triangles per fluid face edge for the projection's quadrature; auto: from the meshes' edge ratio");
  quadrature.choices = {"auto"};
  coupled.push_back(quadrature);
  coupled.push_back(
      wordSpec("defectCorrection", OptionType::Choice, toString(run.defectCorrection), {"auto", "on", "off"},
               "projection: remove its averaging error where the fluid mesh is 1.5x coarser than "
               "the structure's (auto) or always/never"));
  coupled.push_back(wordSpec("gapCorrection", OptionType::Switch, run.gapCorrection ? "yes" : "no", {},
                             "projection: carry fields across the gap between curved non-matching meshes "
                             "(exact linear fields and moment; docs/PROJECTION.md)"));
  coupled.push_back(
      wordSpec("keepSide", OptionType::Switch, run.keepSide ? "yes" : "no", {},
               "projection: on a body wetted from one side, map each fluid point onto the "
               "structure's skin facing its own way (thin trailing edges; docs/PROJECTION.md)"));
  coupled.push_back(realOption(
      "smoothingLength", "0", Bound{0, true}, std::nullopt,
      "[m] the fluid skin moves with the displacement smoothed over this length, the loads go back through "
      "the transpose (conservative): the flow sees a crumpled membrane's mean surface; 0: off"));
  coupled.push_back(wordSpec("conserveMoment", OptionType::Switch, "yes", {},
                             "the transferred loads carry the fluid's moment as well as its force: a couple, "
                             "spread as the smallest traction, makes up what the surfaces' gap loses "
                             "(coupling/mapping/MomentConservation.hpp)"));
  OptionSpec mapTolerance = realOption("mapTolerance", "", Bound{0, false}, std::nullopt,
                                       "[m] fluid points farther than this from the structure stop the run");
  mapTolerance.defaultNote = "max(0.25 x mean structure edge, 2 x the chord gaps of both meshes)";
  coupled.push_back(mapTolerance);
  OptionSpec subcycles = integerOption("subcycles", "1", Bound{1, true}, std::nullopt,
                                       "at least this many structural steps per fluid step");
  subcycles.when = {kTimeAccurate};
  coupled.push_back(subcycles);
  coupled.push_back(wordSpec("structureMode", OptionType::Choice, toString(StructureMode::TimeAccurate),
                             structureModeNames(),
                             "timeAccurate: the structure's motion over each fluid step; equilibrium: its "
                             "damped relaxation under the step's load (steady states)"));
  OptionSpec equilibriumSteps =
      integerOption("equilibriumSteps", std::to_string(EquilibriumOptions{}.steps), Bound{1, true},
                    std::nullopt, "damped structural pseudo-steps per fluid step towards equilibrium");
  equilibriumSteps.when = {kEquilibrium};
  coupled.push_back(equilibriumSteps);
  OptionSpec equilibriumStart = wordSpec(
      "equilibriumStart", OptionType::Choice, equilibriumStartNames()[0], equilibriumStartNames(),
      "rest: every step's relaxation starts from rest; carry: with the pseudo-velocities of the "
      "previous step (slow modes, e.g. a canopy swinging on its lines, converge in far fewer steps)");
  equilibriumStart.when = {kEquilibrium};
  coupled.push_back(equilibriumStart);
  OptionSpec carryFrom = realOption(
      "equilibriumCarryFrom", "0", Bound{0, true}, std::nullopt,
      "carry: the steps that start before this time [s] still relax from rest (let a start-up transient die "
      "out before the motion is carried)");
  carryFrom.when = {kEquilibrium};
  coupled.push_back(carryFrom);
  coupled.push_back(realOption("loadRelaxation", "1", Bound{0, false}, Bound{1, true},
                               "the structure gets w f + (1 - w) f_previous of the fluid's load f; 1: off"));
  OptionSpec restore = wordSpec("restoreMeshPoints", OptionType::Switch, "yes", {},
                                "a repeated step starts from the first pass's mesh points (exact repeat)");
  restore.when = {kImplicit};
  coupled.push_back(restore);
  coupled.push_back(wordSpec("meshGuard", OptionType::Switch, "yes", {},
                             "stop with a diagnosis when the moving mesh inverts a cell or crushes it below "
                             "minVolumeRatio (checked after every mesh motion, before the fluid solves)"));
  // 0.01: two orders of magnitude below the shrinkage of the test cases' meshes (they stay above 0.96), and a
  // stop before a cell's Courant number can have grown a hundredfold at the fixed step (docs/COUPLING.md
  // "When the run stops"); 0 keeps only the inversion checks.
  coupled.push_back(realOption("minVolumeRatio", "0.01", Bound{0, true}, Bound{1, false},
                               "meshGuard: a cell below this fraction of its initial volume stops the run"));
  // Remeshing (docs/COUPLING.md "Remeshing during a run"): the mesh moved from one undeformed shape can
  // follow only so much of the canopy's motion; past that, a new mesh around the canopy as it is now.
  coupled.push_back(realOption(
      "remeshBelow", "0", Bound{0, true}, Bound{1, false},
      "meshGuard: a cell below this fraction of its volume in the undeformed mesh, or a wrong-oriented face, "
      "ends the run cleanly for a new mesh: the fields and the structure's state are written, the fluid's "
      "skin "
      "as it is now goes to structure/remesh/PATCH.stl; 0: off"));
  // A new mesh at a chosen time, whatever the cells: a run that starts on a mesh the moving canopy can drag
  // (coarse, thick wall cells) and goes on from its trimmed shape on one it could not (thin wall cells).
  coupled.push_back(realOption(
      "remeshAt", "0", Bound{0, true}, std::nullopt,
      "the run ends cleanly for a new mesh at the first window ending at or after this time [s] (as "
      "remeshBelow does; a run restarted at or after it does not stop again); 0: off"));
  coupled.push_back(wordSpec(
      "remeshSurface", OptionType::Text, "", {},
      "remeshBelow, remeshAt: the undeformed skin (ASCII STL, one interface patch) that is moved with the "
      "canopy and "
      "written for the new mesh; without it the patch's own faces are (each new mesh then snaps to the last "
      "one's faceted skin and loses a little of the curvature every time)"));
  coupled.push_back(wordSpec(
      "interfaceReference", OptionType::Choice, "design", {"design", "restart"},
      "the fluid mesh's undeformed skin is the structure's design shape (design) or the shape of the state "
      "the "
      "run restarts from (restart: a mesh made around the deformed canopy; later restarts keep it)"));
  coupled.push_back(wordSpec("verifyCheckpoint", OptionType::Switch, "no", {},
                             "debug: solve every pass twice from the checkpoint, report the differences"));
  OptionSpec progress = integerOption("progress", "", Bound{0, true}, std::nullopt,
                                      "a [fsi] progress line every this many windows; 0: none");
  progress.defaultNote = "ceil(windows / 40), i.e. 20 to 40 lines per run";
  coupled.push_back(progress);
  for (OptionSpec& o : coupled) {
    o.when.insert(o.when.begin(), kWithScene);
    s.add(o);
  }
  return s;
}

std::unique_ptr<Acceleration> makeAcceleration(const OptionValues& values) {
  const std::string& name = values.text("acceleration");
  if (const AccelerationEntry* a = findAcceleration(name)) return a->make(values);
  throw std::invalid_argument("makeAcceleration: unknown acceleration " + name);
}

StructureMode structureMode(const OptionValues& values) {
  return values.text("structureMode") == toString(StructureMode::Equilibrium) ? StructureMode::Equilibrium
                                                                              : StructureMode::TimeAccurate;
}

EquilibriumOptions equilibriumOptions(const OptionValues& values) {
  EquilibriumOptions o;
  o.steps = int(values.integer("equilibriumSteps"));
  o.start = values.text("equilibriumStart") == equilibriumStartNames()[1] ? EquilibriumStart::Carry
                                                                          : EquilibriumStart::Rest;
  o.carryFrom = values.real("equilibriumCarryFrom");
  return o;
}

CouplingConfig couplingConfig(const OptionValues& values, double timeWindowSize, double endTime) {
  CouplingConfig c;
  c.kind = values.text("scheme") == "implicit" ? SchemeKind::Implicit : SchemeKind::Staggered;
  c.timeWindowSize = timeWindowSize;
  c.endTime = endTime;
  c.extrapolationOrder = int(values.integer("extrapolation"));
  c.loadRelaxation = values.real("loadRelaxation");
  if (c.kind == SchemeKind::Implicit) {
    c.relativeTolerance = values.real("tolerance");
    c.maxIterations = int(values.integer("maxIterations"));
  }
  return c;
}

std::string optionTable(const OptionSchema& schema) {
  std::string out = "| key | type | default | valid | used with | description |\n|---|---|---|---|---|---|\n";
  for (const OptionSpec& s : schema.specs()) {
    std::vector<std::string> when;
    for (const OptionCondition& c : s.when)
      when.push_back(c.values.empty() ? c.key : c.key + " " + join(c.values, "/"));
    out += "| `" + s.key + "` | " + toString(s.type) + " | " + s.defaultText() + " | " + s.rangeText() +
           " | " + (when.empty() ? "always" : join(when, ", ")) + " | " +
           (s.refusal.empty() ? s.description : s.refusal) + " |\n";
  }
  return out;
}

}  // namespace fsi::coupling
