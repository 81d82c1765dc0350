#include "Time.H"
#include "fsiCouplingConfig.H"
#include "fsiCouplingOptions.H"

namespace Foam {

namespace {

fsi::coupling::MassMatrix projectionKind(const std::string& kind) {
  fsi::coupling::MassMatrix m = fsi::coupling::MassMatrix::Consistent;
  fsi::coupling::massMatrixFromName(kind, m);  // the option table allows only these names
  return m;
}

fsi::coupling::ProjectionOptions projectionOptions(const fsi::coupling::OptionValues& o) {
  fsi::coupling::ProjectionOptions opt;
  opt.mass = projectionKind(o.text("projection"));
  opt.gapCorrection = o.flag("gapCorrection");
  opt.keepSide = o.flag("keepSide");
  opt.evaluation = o.text("evaluation") == "l2" ? fsi::coupling::ProjectionOptions::Evaluation::L2
                                                : fsi::coupling::ProjectionOptions::Evaluation::Pointwise;
  const std::string& d = o.text("defectCorrection");  // the option table allows only these
  opt.defectCorrection = d == "on"    ? fsi::coupling::ProjectionOptions::Defect::On
                         : d == "off" ? fsi::coupling::ProjectionOptions::Defect::Off
                                      : fsi::coupling::ProjectionOptions::Defect::Auto;
  opt.quadratureLevel =
      o.isWord("quadratureLevel") ? fsi::coupling::kAutoQuadrature : int(o.integer("quadratureLevel"));
  return opt;
}

// The options of a coupled run (`scene` given).
void readCoupledRun(fsiCouplingConfig& c, const Time& time) {
  const fsi::coupling::OptionValues& o = c.options;
  c.sceneGiven = o.text("scene");
  c.scene = fileName(c.sceneGiven).expand();
  if (!c.scene.isAbsolute()) c.scene = time.globalPath() / c.scene;
  c.implicit = o.text("scheme") == "implicit";
  c.verifyCheckpoint = o.flag("verifyCheckpoint");
  // restoreMeshPoints is an option of the implicit scheme only (the staggered one never repeats a step).
  c.restoreMeshPoints = !o.has("restoreMeshPoints") || o.flag("restoreMeshPoints");
  // The fluid's load arrives as nodal forces (the conservative transfer Hᵀ f). subcycles is an option of
  // time-accurate windows only, equilibriumSteps of equilibrium ones.
  c.participant.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
  if (o.has("subcycles")) c.participant.minSubcycles = int(o.integer("subcycles"));
  if (fsi::coupling::structureMode(o) == fsi::coupling::StructureMode::Equilibrium) {
    c.participant.mode = fsi::coupling::StructureMode::Equilibrium;
    c.participant.equilibrium = fsi::coupling::equilibriumOptions(o);
  }
  c.projection = projectionOptions(o);
  if (o.given("mapTolerance")) c.mapTolerance = o.real("mapTolerance");
  c.smoothingLength = o.real("smoothingLength");
  c.conserveMoment = o.flag("conserveMoment");
  c.interfaceReferenceRestart = o.text("interfaceReference") == "restart";
  c.meshGuard = o.flag("meshGuard");
  c.minVolumeRatio = o.real("minVolumeRatio");
  c.remeshBelow = o.real("remeshBelow");
  c.remeshAt = o.real("remeshAt");
  if (o.given("remeshSurface")) c.remeshSurface = o.text("remeshSurface");
  if (o.given("progress")) c.progress = label(o.integer("progress"));
}

}  // namespace

fsiCouplingConfig readCouplingConfig(const dictionary& dict, const fvMesh& mesh, const Time& time) {
  fsiCouplingConfig c;
  // Every key and value against the option table first: nothing below reads an unchecked entry.
  c.options = readCouplingOptions(dict);
  const fsi::coupling::OptionValues& o = c.options;
  for (const std::string& p : o.words("patches")) c.patches.append(word(p));
  c.rho = o.real("rho");
  c.pRef = o.real("pRef");
  c.viscous = o.flag("viscous");
  c.patchIDs.setSize(c.patches.size());
  forAll(c.patches, i) {
    c.patchIDs[i] = mesh.boundaryMesh().findPatchID(c.patches[i]);
    if (c.patchIDs[i] < 0)
      FatalIOErrorInFunction(dict) << "fsiCoupling: no patch named " << c.patches[i]
                                   << "; the mesh has the patches " << mesh.boundaryMesh().names()
                                   << exit(FatalIOError);
  }
  if (!o.given("scene")) return c;
  // The safety net: an option the table let through but a coupled run cannot read stops the run here.
  try {
    readCoupledRun(c, time);
  } catch (const std::exception& e) {
    FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
  }
  return c;
}

}  // namespace Foam
