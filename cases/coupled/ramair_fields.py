"""The ram-air case's 0/ fields (part of ramair_fluid.py, the case generator): U, p, pointDisplacement and,
for kOmegaSST, k, omega and nut on the snapped mesh's patches, from constant/fluidSettings.json.
"""
import os

from ramair_dicts import write
from ramair_geometry import v3
from ramair_settings import load_record


def write_fields(case):
    rec = load_record(case)
    s, d = rec["settings"], rec["derived"]
    src = os.path.basename(rec["settings_file"])
    z = os.path.join(case, "0")
    u = v3(d["u_inf"])
    # half_domain: every field's entry for the symmetry plane y = 0
    sym = "  mirror { type symmetryPlane; }\n" if s.get("half_domain") == "yes" else ""
    write(os.path.join(z, "U"), "volVectorField", "U", src, f"""\
dimensions [0 1 -1 0 0 0 0];
internalField uniform {u};   // a uniform start: potentialFoam spiked at the sharp trailing edge
boundaryField
{{
  farfield {{ type freestreamVelocity; freestreamValue uniform {u}; value uniform {u}; }}
  wing {{ type movingWallVelocity; value uniform (0 0 0); }}   // = noSlip while the wing is rigid
{sym}}}
""")
    write(os.path.join(z, "p"), "volScalarField", "p", src, """\
dimensions [0 2 -2 0 0 0 0];   // kinematic
internalField uniform 0;
boundaryField
{
  farfield { type freestreamPressure; freestreamValue uniform 0; value uniform 0; }
  wing { type zeroGradient; }
""" + sym + """}
""")
    wing = ("wing { type fsiInterfaceDisplacement; value uniform (0 0 0); }   // the structure's displacement"
            if s["coupled"] == "yes" else
            "wing { type fixedValue; value uniform (0 0 0); }   // rigid (coupled yes: fsiInterfaceDisplacement)")
    write(os.path.join(z, "pointDisplacement"), "pointVectorField", "pointDisplacement", src, """\
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
  """ + wing + """
  farfield { type fixedValue; value uniform (0 0 0); }
  "procBoundary.*" { type processor; value uniform (0 0 0); }
""" + sym + """}
""")
    if s["model"] == "kOmegaSST":
        k, om = d["k_inf"], d["omega_inf"]
        for name, val, wall in (("k", k, f"kqRWallFunction; value uniform {k:.9g}"),
                                ("omega", om, f"omegaWallFunction; value uniform {om:.9g}")):
            dims = "[0 2 -2 0 0 0 0]" if name == "k" else "[0 0 -1 0 0 0 0]"
            write(os.path.join(z, name), "volScalarField", name, src, f"""\
dimensions {dims};
internalField uniform {val:.9g};
boundaryField
{{
  farfield {{ type inletOutlet; inletValue uniform {val:.9g}; value uniform {val:.9g}; }}
  wing {{ type {wall}; }}
{sym}}}
""")
        write(os.path.join(z, "nut"), "volScalarField", "nut", src, """\
dimensions [0 2 -1 0 0 0 0];
internalField uniform 0;
boundaryField
{
  farfield { type calculated; value uniform 0; }
  wing { type nutUSpaldingWallFunction; value uniform 0; }   // no prism layers: y+ 75-3000 (docs/RAMAIR.md)
""" + sym + """}
""")
