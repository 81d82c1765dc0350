#include <cstdio>
#include <cstdlib>

#include "IOstreams.H"
#include "OStringStream.H"
#include "fsiCouplingOptions.H"
#include "token.H"

namespace Foam {

namespace {

// Shortest decimal form that reads back to the same double (OpenFOAM parsed `1e-5` into a double; %.17g
// would show it as 1.0000000000000001e-05 in messages).
std::string shortest(double v) {
  char buf[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string tokenText(const token& t) {
  if (t.isWord()) return t.wordToken();
  if (t.isString()) return t.stringToken();
  if (t.isLabel()) return std::to_string(t.labelToken());
  if (t.isScalar()) return shortest(t.number());
  if (t.isPunctuation()) return std::string(1, char(t.pToken()));
  if (t.isBool()) return t.boolToken() ? "true" : "false";
  OStringStream os;
  os << t;
  return os.str();
}

}  // namespace

fsi::coupling::OptionTokens optionTokens(const dictionary& dict) {
  fsi::coupling::OptionTokens out;
  for (const entry& e : dict) {
    std::vector<std::string> tokens;
    if (e.isDict()) {
      tokens.push_back("{dictionary}");
    } else {
      const ITstream& is = e.stream();
      forAll(is, i) tokens.push_back(tokenText(is[i]));
    }
    out.emplace_back(std::string(e.keyword()), std::move(tokens));
  }
  return out;
}

fsi::coupling::OptionSchema fsiCouplingSchema() {
  using fsi::coupling::OptionSpec;
  using fsi::coupling::OptionType;
  fsi::coupling::OptionSchema s = fsi::coupling::couplingOptionSchema();
  s.setHostName("OpenFOAM");
  const char* const openfoam = "read by OpenFOAM for every function object";
  for (const char* key : {"type", "libs", "functionObjectLibs", "enabled", "log", "region", "subRegion"}) {
    OptionSpec o;
    o.key = key;
    o.description = openfoam;
    o.host = true;
    s.add(o);
  }
  // OpenFOAM runs an object with any of these under a timeControl wrapper (v1912 functionObjectList,
  // timeControlFunctionObject), which skips execute() between intervals or outside [timeStart, timeEnd] (the
  // structure would fall behind the fluid) and, in write(), calls execute() again when the time index
  // changed since the last execute() -- which it has after a repeated implicit step restored the time: the
  // coupling would advance a second time at the restored time. The coupling must run exactly once per
  // fluid step, so none of them may be given.
  const char* const everyStep =
      "OpenFOAM would run the coupling under a time control, which skips fluid steps or repeats a coupling "
      "step; it must run exactly once per fluid step";
  for (const char* key : {"executeControl", "executeInterval", "writeControl", "writeInterval",
                          "outputControl", "outputInterval", "timeStart", "timeEnd", "triggerStart",
                          "triggerEnd", "controlMode", "deltaTCoeff", "nStepsToStartTimeChange"}) {
    OptionSpec o;
    o.key = key;
    o.refusal = everyStep;
    o.host = true;
    s.add(o);
  }
  return s;
}

fsi::coupling::OptionValues readCouplingOptions(const dictionary& dict) {
  try {
    return fsiCouplingSchema().validate(optionTokens(dict));
  } catch (const fsi::coupling::OptionError& e) {
    const entry* ep = dict.findEntry(e.key(), keyType::LITERAL);
    FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what();
    if (ep) FatalIOError << nl << "    (line " << ep->startLineNumber() << " of " << dict.name() << ")";
    FatalIOError << exit(FatalIOError);
  }
  return {};
}

}  // namespace Foam
