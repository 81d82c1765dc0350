// The coupling option table (coupling/scheme/CouplingOptions): misspelt keys name their nearest match, bad
// values name the key and the valid range, options without effect give a warning, and the table's ranges
// agree with the checks of the library classes that use the values.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "TestScenes.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/mapping/MappingDefaults.hpp"
#include "coupling/scheme/CouplingOptions.hpp"
#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"
#include "coupling/scheme/acceleration/Aitken.hpp"
#include "coupling/scheme/acceleration/IqnIls.hpp"
#include "structure/scene/NearestName.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::coupling;

namespace {

// What a coupled case writes (cases/coupled/cavity-membrane-2d), plus `extra`.
OptionTokens implicitCase(const OptionTokens& extra = {}) {
  OptionTokens t{{"patches", {"(", "bottom", ")"}},
                 {"rho", {"1"}},
                 {"pRef", {"0"}},
                 {"scene", {"structure.yaml"}},
                 {"scheme", {"implicit"}},
                 {"acceleration", {"IQN-ILS"}},
                 {"omega", {"0.1"}},
                 {"reuse", {"8"}},
                 {"tolerance", {"1e-4"}},
                 {"maxIterations", {"40"}},
                 {"extrapolation", {"1"}},
                 {"viscous", {"yes"}}};
  t.insert(t.end(), extra.begin(), extra.end());
  return t;
}

OptionTokens minimal(const OptionTokens& extra = {}) {
  OptionTokens t{{"patches", {"(", "bottom", ")"}}, {"rho", {"1"}}, {"scene", {"structure.yaml"}}};
  t.insert(t.end(), extra.begin(), extra.end());
  return t;
}

// Replaces (or adds) one key of a token list.
OptionTokens with(OptionTokens t, const std::string& key, const std::string& value) {
  for (auto& [k, v] : t)
    if (k == key) {
      v = {value};
      return t;
    }
  t.push_back({key, {value}});
  return t;
}

std::string errorOf(const OptionTokens& tokens) {
  try {
    couplingOptionSchema().validate(tokens);
  } catch (const OptionError& e) {
    return e.what();
  }
  return "(accepted)";
}

bool accepted(const OptionTokens& tokens) {
  return errorOf(tokens) == "(accepted)";
}

bool throws(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument&) {
    return true;
  }
  return false;
}

// A structure that is never asked to solve: CouplingScheme's constructor only checks the configuration.
struct IdleStructure : StructureSolver {
  Eigen::VectorXd solve(double, double, const Eigen::VectorXd&, const Eigen::VectorXd& l) override {
    return l;
  }
  void saveCheckpoint() override {}
  void restoreCheckpoint() override {}
};

}  // namespace

TEST(CouplingOptions, EveryMisspeltKeyNamesItsNearestMatchAndTheValidKeys) {
  const std::vector<std::pair<std::string, std::string>> typos{{"shceme", "scheme"},
                                                               {"accleration", "acceleration"},
                                                               {"omgea", "omega"},
                                                               {"tolerence", "tolerance"},
                                                               {"maxIteration", "maxIterations"},
                                                               {"viscos", "viscous"},
                                                               {"subcycle", "subcycles"},
                                                               {"projecton", "projection"},
                                                               {"maptolerance", "mapTolerance"},
                                                               {"restoreMeshPoint", "restoreMeshPoints"},
                                                               {"extrapolaton", "extrapolation"},
                                                               {"resue", "reuse"},
                                                               {"progres", "progress"},
                                                               {"sceen", "scene"},
                                                               {"verifyCheckpoints", "verifyCheckpoint"},
                                                               {"pref", "pRef"}};
  const std::vector<std::string> keys = couplingOptionSchema().keys();
  for (const auto& [typo, key] : typos) {
    const std::string msg = errorOf(implicitCase({{typo, {"1"}}}));
    EXPECT_NE(msg.find("unknown option '" + typo + "'; did you mean '" + key + "'?"), std::string::npos)
        << msg;
    for (const std::string& k : keys)
      EXPECT_NE(msg.find(" " + k), std::string::npos) << k << " not listed: " << msg;
    try {
      couplingOptionSchema().validate(implicitCase({{typo, {"1"}}}));
    } catch (const OptionError& e) {
      EXPECT_EQ(e.key(), typo);  // the adapter looks up the line of this key
    }
  }
}

TEST(CouplingOptions, EveryBadValueNamesTheKeyAndTheValidRange) {
  struct Case {
    std::string key, value, range;
  };
  const std::vector<Case> cases{
      {"omega", "-1", "0 < omega <= 1"},
      {"omega", "0", "0 < omega <= 1"},
      {"omega", "50", "0 < omega <= 1"},
      {"omega", "fast", "0 < omega <= 1"},
      {"reuse", "-3", "integer, reuse >= 0"},
      {"reuse", "2.5", "integer, reuse >= 0"},
      {"maxIterations", "0", "integer, maxIterations >= 1"},
      {"extrapolation", "7", "integer, 0 <= extrapolation <= 2"},
      {"extrapolation", "-1", "integer, 0 <= extrapolation <= 2"},
      {"tolerance", "0", "0 < tolerance < 1"},
      {"tolerance", "1", "0 < tolerance < 1"},
      {"subcycles", "0", "integer, subcycles >= 1"},
      {"structureMode", "steady", "one of timeAccurate equilibrium"},
      {"structureMode", "equilibrum", "one of timeAccurate equilibrium"},
      {"equilibriumSteps", "0", "integer, equilibriumSteps >= 1"},
      {"equilibriumSteps", "-100", "integer, equilibriumSteps >= 1"},
      {"equilibriumSteps", "2.5", "integer, equilibriumSteps >= 1"},
      {"loadRelaxation", "0", "0 < loadRelaxation <= 1"},
      {"loadRelaxation", "-0.5", "0 < loadRelaxation <= 1"},
      {"loadRelaxation", "1.5", "0 < loadRelaxation <= 1"},
      {"loadRelaxation", "half", "0 < loadRelaxation <= 1"},
      {"minVolumeRatio", "1", "0 <= minVolumeRatio < 1"},
      {"minVolumeRatio", "-0.01", "0 <= minVolumeRatio < 1"},
      {"meshGuard", "sometimes", "yes or no"},
      {"mapTolerance", "0", "mapTolerance > 0"},
      {"rho", "0", "rho > 0"},
      {"rho", "-1.2", "rho > 0"},
      {"progress", "-1", "integer, progress >= 0"},
      {"scheme", "implict", "one of staggered implicit"},
      {"acceleration", "IQN", "one of constant aitken IQN-ILS"},
      {"projection", "lumpd", "one of consistent lumped dual"},
      {"viscous", "maybe", "yes or no"},
      {"pRef", "inf", "any number"},
  };
  for (const Case& c : cases) {
    const std::string msg = errorOf(with(implicitCase(), c.key, c.value));
    EXPECT_NE(msg.find("option '" + c.key + "' = " + c.value), std::string::npos) << msg;
    EXPECT_NE(msg.find("valid: " + c.range), std::string::npos) << msg;
  }
  EXPECT_NE(errorOf(with(implicitCase(), "scheme", "implict")).find("did you mean 'implicit'"),
            std::string::npos);
  EXPECT_NE(errorOf(with(implicitCase(), "structureMode", "equilibrum")).find("did you mean 'equilibrium'"),
            std::string::npos);
  // equilibriumSteps is checked (and keyed for the adapter's line number) even where it has no effect.
  try {
    couplingOptionSchema().validate(with(minimal(), "equilibriumSteps", "0"));
    ADD_FAILURE() << "equilibriumSteps 0 accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.key(), "equilibriumSteps");
  }
  OptionTokens empty = implicitCase();
  empty[6].second.clear();  // `omega ;`
  EXPECT_NE(errorOf(empty).find("option 'omega' = (nothing) has no value"), std::string::npos)
      << errorOf(empty);
  // Missing required keys.
  EXPECT_NE(errorOf({{"patches", {"a"}}}).find("option 'rho' is required"), std::string::npos);
  EXPECT_NE(errorOf({{"rho", {"1"}}}).find("option 'patches' is required"), std::string::npos);
  EXPECT_NE(errorOf(implicitCase({{"omega", {"0.2"}}})).find("given twice"), std::string::npos);
}

TEST(CouplingOptions, QuadratureLevelIsAutoOrAnInteger) {
  // `quadratureLevel auto;` or a level 1..64; anything else is refused naming the key and both forms.
  const OptionSchema schema = couplingOptionSchema();
  EXPECT_EQ(schema.validate(minimal({{"quadratureLevel", {"64"}}})).integer("quadratureLevel"), 64);
  for (const char* bad : {"0", "65", "2.5", "automatic", "-1", "1e400"}) {
    try {
      schema.validate(minimal({{"quadratureLevel", {bad}}}));
      ADD_FAILURE() << bad << " was accepted";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.key(), "quadratureLevel");
      EXPECT_NE(std::string(e.what()).find("auto, or integer, 1 <= quadratureLevel <= 64"), std::string::npos)
          << e.what();
    }
  }
}

TEST(CouplingOptions, ValuesDefaultsAndLists) {
  const OptionSchema schema = couplingOptionSchema();
  const OptionValues v = schema.validate(implicitCase());
  EXPECT_TRUE(v.warnings().empty());
  EXPECT_EQ(v.words("patches"), std::vector<std::string>{"bottom"});
  EXPECT_EQ(v.text("scheme"), "implicit");
  EXPECT_DOUBLE_EQ(v.real("tolerance"), 1e-4);
  EXPECT_EQ(v.integer("reuse"), 8);
  EXPECT_TRUE(v.flag("viscous"));
  EXPECT_TRUE(v.flag("restoreMeshPoints"));  // default of an implicit run
  EXPECT_FALSE(v.given("progress"));         // the host computes it
  EXPECT_FALSE(v.has("mapTolerance"));

  // Defaults: staggered; omega's default belongs to the chosen acceleration.
  const OptionValues d = schema.validate(minimal());
  EXPECT_EQ(d.text("scheme"), "staggered");
  EXPECT_EQ(d.integer("extrapolation"), 1);
  // the one set of projection defaults, fsi map-check's too (coupledRunProjection(); docs/PROJECTION.md,
  // "Defaults in a coupled run")
  EXPECT_EQ(d.text("projection"), "consistent");
  EXPECT_EQ(d.text("evaluation"), "pointwise");
  EXPECT_TRUE(d.isWord("quadratureLevel"));  // auto
  EXPECT_FALSE(d.flag("gapCorrection"));
  EXPECT_EQ(d.text("defectCorrection"), "off");
  EXPECT_FALSE(d.flag("keepSide"));
  const ProjectionOptions run = coupledRunProjection();
  EXPECT_EQ(d.text("projection"), toString(run.mass));
  EXPECT_EQ(d.text("evaluation"), toString(run.evaluation));
  EXPECT_EQ(d.flag("gapCorrection"), run.gapCorrection);
  EXPECT_EQ(d.text("defectCorrection"), toString(run.defectCorrection));
  EXPECT_EQ(d.flag("keepSide"), run.keepSide);
  EXPECT_EQ(run.quadratureLevel, kAutoQuadrature);
  EXPECT_TRUE(schema.validate(minimal({{"quadratureLevel", {"auto"}}})).isWord("quadratureLevel"));
  EXPECT_FALSE(schema.validate(minimal({{"quadratureLevel", {"3"}}})).isWord("quadratureLevel"));
  EXPECT_EQ(schema.validate(minimal({{"quadratureLevel", {"3"}}})).integer("quadratureLevel"), 3);
  EXPECT_FALSE(d.has("omega"));  // no effect without the implicit scheme
  EXPECT_DOUBLE_EQ(schema.validate(minimal({{"scheme", {"implicit"}}})).real("omega"), 0.1);
  EXPECT_DOUBLE_EQ(
      schema.validate(minimal({{"scheme", {"implicit"}}, {"acceleration", {"constant"}}})).real("omega"),
      0.5);
  EXPECT_FALSE(
      schema.validate(minimal({{"scheme", {"implicit"}}, {"acceleration", {"aitken"}}})).has("reuse"));

  // Lists as OpenFOAM tokenises them, with and without a count; switches in OpenFOAM's words.
  EXPECT_EQ(schema.validate(with(minimal(), "patches", "canopy")).words("patches"),
            std::vector<std::string>{"canopy"});
  OptionTokens two = minimal();
  two[0].second = {"2", "(", "up", "down", ")"};
  EXPECT_EQ(schema.validate(two).words("patches"), (std::vector<std::string>{"up", "down"}));
  two[0].second = {"3", "(", "up", "down", ")"};
  EXPECT_NE(errorOf(two).find("count"), std::string::npos);
  two[0].second = {"(", ")"};
  EXPECT_NE(errorOf(two).find("empty list"), std::string::npos);
  for (const char* yes : {"yes", "on", "true", "y"})
    EXPECT_TRUE(schema.validate(with(minimal(), "viscous", yes)).flag("viscous"));
  for (const char* no : {"no", "off", "false", "n"})
    EXPECT_FALSE(schema.validate(with(minimal(), "viscous", no)).flag("viscous"));
}

TEST(CouplingOptions, OptionsWithoutEffectGiveAWarningNotAnError) {
  const OptionSchema schema = couplingOptionSchema();
  // Switching an implicit case to staggered keeps its implicit settings: each is named, none stops the run.
  const OptionValues v = schema.validate(with(implicitCase(), "scheme", "staggered"));
  ASSERT_EQ(v.warnings().size(), 5u);  // acceleration omega reuse tolerance maxIterations
  EXPECT_EQ(v.warnings()[1], "option 'omega' has no effect with scheme staggered (it needs scheme implicit)");
  const OptionValues a = schema.validate(with(implicitCase(), "acceleration", "aitken"));
  ASSERT_EQ(a.warnings().size(), 1u);
  EXPECT_EQ(a.warnings()[0],
            "option 'reuse' has no effect with acceleration aitken (it needs acceleration IQN-ILS)");
  // Without a scene the object only monitors forces.
  const OptionValues m = schema.validate({{"patches", {"a"}}, {"rho", {"1"}}, {"scheme", {"implicit"}}});
  ASSERT_EQ(m.warnings().size(), 1u);
  EXPECT_EQ(m.warnings()[0], "option 'scheme' has no effect without scene (it needs scene)");
  // A value without effect is still checked.
  EXPECT_NE(errorOf(with(with(implicitCase(), "scheme", "staggered"), "omega", "50")).find("0 < omega <= 1"),
            std::string::npos);
}

TEST(CouplingOptions, StructureModeOptionsAndTheirEffect) {
  const OptionSchema schema = couplingOptionSchema();
  // Defaults: time-accurate windows, subcycles applies, equilibriumSteps does not; no load relaxation.
  const OptionValues d = schema.validate(minimal());
  EXPECT_EQ(d.text("structureMode"), "timeAccurate");
  EXPECT_EQ(structureMode(d), StructureMode::TimeAccurate);
  EXPECT_EQ(d.integer("subcycles"), 1);
  EXPECT_FALSE(d.has("equilibriumSteps"));
  EXPECT_DOUBLE_EQ(d.real("loadRelaxation"), 1.0);
  EXPECT_DOUBLE_EQ(couplingConfig(d, 0.01, 1.0).loadRelaxation, 1.0);
  // Equilibrium: equilibriumSteps defaults to 100 (Kalro & Tezduyar's count), subcycles has no effect.
  const OptionValues e =
      schema.validate(minimal({{"structureMode", {"equilibrium"}}, {"loadRelaxation", {"0.3"}}}));
  EXPECT_EQ(structureMode(e), StructureMode::Equilibrium);
  EXPECT_EQ(e.integer("equilibriumSteps"), 100);
  EXPECT_FALSE(e.has("subcycles"));
  EXPECT_TRUE(e.warnings().empty());
  EXPECT_DOUBLE_EQ(couplingConfig(e, 0.01, 1.0).loadRelaxation, 0.3);
  EXPECT_EQ(schema.validate(minimal({{"structureMode", {"equilibrium"}}, {"equilibriumSteps", {"400"}}}))
                .integer("equilibriumSteps"),
            400);
  // Each mode's option given with the other mode: a warning naming what it needs, not an error.
  const OptionValues w = schema.validate(minimal({{"equilibriumSteps", {"50"}}}));
  ASSERT_EQ(w.warnings().size(), 1u);
  EXPECT_EQ(w.warnings()[0],
            "option 'equilibriumSteps' has no effect with structureMode timeAccurate (it needs structureMode "
            "equilibrium)");
  const OptionValues s = schema.validate(minimal({{"structureMode", {"equilibrium"}}, {"subcycles", {"4"}}}));
  ASSERT_EQ(s.warnings().size(), 1u);
  EXPECT_EQ(s.warnings()[0],
            "option 'subcycles' has no effect with structureMode equilibrium (it needs structureMode "
            "timeAccurate)");
}

TEST(CouplingOptions, RangesAgreeWithTheLibraryChecks) {
  IdleStructure idle;
  // Each value: does the table accept it, does the class that uses it accept it?
  for (const char* acc : {"constant", "aitken", "IQN-ILS"})
    for (const char* omega : {"-1", "0", "1e-9", "0.5", "1", "1.000001", "50"}) {
      const OptionTokens t = with(with(implicitCase(), "acceleration", acc), "omega", omega);
      const bool table = accepted(t);
      const double w = std::stod(omega);
      bool library = false;
      for (const AccelerationEntry& e : accelerationEntries())
        if (e.name == acc) {
          OptionSchema loose;  // the entry's factory with the value unchecked
          OptionSpec any;
          any.key = "omega";
          any.type = OptionType::Real;
          loose.add(any);
          OptionSpec reuse;
          reuse.key = "reuse";
          reuse.type = OptionType::Integer;
          reuse.defaultValue = "0";
          loose.add(reuse);
          library = !throws([&] { e.make(loose.validate({{"omega", {omega}}})); });
        }
      EXPECT_EQ(table, library) << acc << " omega " << w;
    }
  for (const int reuse : {-1, 0, 8}) {
    IqnIlsOptions o;
    o.reuseSteps = reuse;
    EXPECT_EQ(accepted(with(implicitCase(), "reuse", std::to_string(reuse))), !throws([&] { IqnIls x(o); }))
        << reuse;
  }
  for (const char* tol : {"0", "1e-12", "0.5", "1", "2"}) {
    CouplingConfig c;
    c.timeWindowSize = 0.01;
    c.relativeTolerance = std::stod(tol);
    EXPECT_EQ(accepted(with(implicitCase(), "tolerance", tol)),
              !throws([&] { CouplingScheme s(c, idle, std::make_unique<Aitken>()); }))
        << tol;
  }
  for (const int n : {0, 1, 5}) {
    CouplingConfig c;
    c.timeWindowSize = 0.01;
    c.maxIterations = n;
    EXPECT_EQ(accepted(with(implicitCase(), "maxIterations", std::to_string(n))),
              !throws([&] { CouplingScheme s(c, idle, std::make_unique<Aitken>()); }))
        << n;
  }
  for (const int p : {-1, 0, 2, 3}) {
    CouplingConfig c;
    c.kind = SchemeKind::Staggered;
    c.timeWindowSize = 0.01;
    c.extrapolationOrder = p;
    EXPECT_EQ(accepted(with(minimal(), "extrapolation", std::to_string(p))),
              !throws([&] { CouplingScheme s(c, idle); }))
        << p;
  }
  const auto drum = [](const ParticipantOptions& options) {
    StructureParticipant s(
        fsi::structure::loadSceneFromString(
            fsi::test::drumScene("coupling: {interface: sheet}\ntime: {end: 1.0}\n"), "drum.yaml"),
        options);
  };
  for (const int n : {-1, 0, 1, 3}) {
    ParticipantOptions o;
    o.minSubcycles = n;
    EXPECT_EQ(accepted(with(minimal(), "subcycles", std::to_string(n))), !throws([&] { drum(o); })) << n;
  }
  for (const int n : {-1, 0, 1, 100}) {
    ParticipantOptions o;
    o.mode = StructureMode::Equilibrium;
    o.equilibrium.steps = n;
    EXPECT_EQ(
        accepted(minimal({{"structureMode", {"equilibrium"}}, {"equilibriumSteps", {std::to_string(n)}}})),
        !throws([&] { drum(o); }))
        << n;
  }
  for (const char* w : {"-1", "0", "1e-9", "0.5", "1", "1.000001", "2"}) {
    CouplingConfig c;
    c.kind = SchemeKind::Staggered;
    c.timeWindowSize = 0.01;
    c.loadRelaxation = std::stod(w);
    EXPECT_EQ(accepted(with(minimal(), "loadRelaxation", w)), !throws([&] { CouplingScheme s(c, idle); }))
        << w;
  }
}

TEST(CouplingOptions, ConfigAndAccelerationFromValues) {
  const OptionValues v = couplingOptionSchema().validate(implicitCase());
  const CouplingConfig c = couplingConfig(v, 0.01, 10.0);
  EXPECT_EQ(c.kind, SchemeKind::Implicit);
  EXPECT_DOUBLE_EQ(c.relativeTolerance, 1e-4);
  EXPECT_EQ(c.maxIterations, 40);
  EXPECT_EQ(c.extrapolationOrder, 1);
  EXPECT_EQ(makeAcceleration(v)->name(), "iqn-ils(q=8)");
  const OptionValues a = couplingOptionSchema().validate(with(implicitCase(), "acceleration", "aitken"));
  EXPECT_EQ(makeAcceleration(a)->name(), "aitken");
}

TEST(CouplingOptions, AccelerationNamesAndOptionsComeFromTheRegistry) {
  // The valid values of `acceleration` are the registry's names, in its order.
  const OptionSchema schema = couplingOptionSchema();
  std::vector<std::string> names;
  for (const AccelerationEntry& e : accelerationEntries()) names.push_back(e.name);
  ASSERT_GE(names.size(), 3u);
  for (const OptionSpec& o : schema.specs()) {
    if (o.key == "acceleration") {
      EXPECT_EQ(o.choices, names);
    }
  }
  EXPECT_EQ(findAcceleration("nonsense"), nullptr);
  for (const AccelerationEntry& e : accelerationEntries()) {
    EXPECT_EQ(findAcceleration(e.name), &e);
    // Each of its options is in the table, used with `acceleration <its name>`, and the implicit case
    // with only the name and that entry's defaults makes it.
    for (const OptionSpec& o : e.options) {
      bool listed = false;
      for (const OptionSpec& s : schema.specs())
        for (const OptionCondition& c : s.when)
          listed = listed || (s.key == o.key && c.key == "acceleration" && c.values == std::vector{e.name});
      EXPECT_TRUE(listed) << e.name << " " << o.key;
    }
    const OptionValues v = schema.validate(minimal({{"scheme", {"implicit"}}, {"acceleration", {e.name}}}));
    EXPECT_NE(makeAcceleration(v), nullptr) << e.name;
  }
  // A misspelt name gets the registry's nearest one.
  const std::string error = errorOf(with(implicitCase(), "acceleration", "aitkin"));
  EXPECT_NE(error.find("did you mean 'aitken'"), std::string::npos) << error;
}

TEST(CouplingOptions, EditDistanceAndTable) {
  EXPECT_EQ(fsi::editDistance("shceme", "scheme"), 1);  // a swap of neighbours is one edit
  EXPECT_EQ(fsi::editDistance("kitten", "sitting"), 3);
  EXPECT_EQ(fsi::editDistance("MAPTOLERANCE", "mapTolerance"), 0);
  EXPECT_EQ(fsi::nearestName("x", {}), "");
  // Every default in the table is a valid value of its own option, and the docs table lists every key.
  const OptionSchema schema = couplingOptionSchema();
  for (const OptionSpec& s : schema.specs()) {
    if (s.defaultValue.empty()) continue;
    OptionSpec plain = s;
    plain.when.clear();
    OptionSchema alone;
    alone.add(plain);
    EXPECT_NO_THROW(alone.validate({{s.key, {s.defaultValue}}})) << s.key;
  }
  const std::string table = optionTable(schema);
  for (const std::string& k : schema.keys()) EXPECT_NE(table.find("| `" + k + "` |"), std::string::npos) << k;
}

TEST(CouplingOptions, DocsListTheTable) {
  // docs/COUPLING.md holds the table between markers, exactly as the code has it.
  std::ifstream is(std::string(FSI_SOURCE_DIR) + "/docs/COUPLING.md");
  std::stringstream ss;
  ss << is.rdbuf();
  const std::string doc = ss.str(), begin = "<!-- coupling-options:begin -->\n",
                    end = "<!-- coupling-options:end -->";
  const auto a = doc.find(begin), b = doc.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  const std::string table = optionTable(couplingOptionSchema());
  EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()), table) << "docs/COUPLING.md should have:\n"
                                                                       << table;
}
