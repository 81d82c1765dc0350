#!/usr/bin/env python3
"""The fluid side of a ram-air wing case: OpenFOAM v1912 dictionaries around the canopy's closed skin (the
STL that `fsi generate` writes), from a small validated settings file; and the case's summary.json.

Usage (run by the case's Allrun; /usr/bin/python3, standard library only):
  ramair_fluid.py check SETTINGS              validate the settings file (exit 2 with FILE:LINE: message)
  ramair_fluid.py generate-args SETTINGS      the `fsi generate --set` arguments of the fluid's skin, one a line
  ramair_fluid.py write SETTINGS STL CASE     system/ and constant/ dictionaries (blockMesh, surface features,
                                              snappyHexMesh, schemes, solution, controlDict with forceCoeffs,
                                              decomposition, transport, turbulence, dynamic mesh) and
                                              constant/fluidSettings.json (settings + derived numbers)
  ramair_fluid.py structure SETTINGS SCENE OUT  the coupled run's structure scene (coupled yes): SCENE with the
                                              ram pressure and line-drag wind of the settings, the skin as
                                              the coupling interface
  ramair_fluid.py fields CASE                 0/ (U, p, pointDisplacement; k, omega, nut for kOmegaSST): after
                                              snappyHexMesh, from constant/fluidSettings.json
  ramair_fluid.py summary CASE                summary.json from the logs, postProcessing/ and constant/polyMesh
  ramair_fluid.py settings-table              the settings as a Markdown table (docs/RAMAIR.md "Settings")
  ramair_fluid.py courant-check LOG SETTINGS  exit 1 naming the step when LOG's Courant number ran away (past
                                              100 x the settings' courant, or NaN): the flow diverged
  ramair_fluid.py patch-area CASE PATCH       area of a boundary patch of constant/polyMesh (ASCII)
  ramair_fluid.py mirror-check CASE           mirror_mesh yes, before mirrorMesh: every point of the patch
                                              `mirror` lies on the plane y = 0
  ramair_fluid.py mirror-finish CASE          after mirrorMesh: the patch `mirror` has no faces left (all
                                              merged); removes it from constant/polyMesh/boundary
  ramair_fluid.py remesh-dicts CASE           a new mesh's background block over the whole box (remeshing)
  ramair_fluid.py split-exclude CASE LOG     after wall_split's splits and checkMesh LOG: exit 0 when the mesh
                                              passes; exit 3 when it has wrong-oriented faces, whose spots
                                              system/topoSetDict now leaves unsplit (split again)
  ramair_fluid.py mesh-gate CASE LOG         exit 1 when a new mesh's checkMesh LOG failed anything but the
                                              skewness check (Allrun's remesh loop, before the run goes on)
  ramair_fluid.py split-stage CASE T DT       a new mesh at time T on a controlDict with step DT: `split N`,
                                              `layers yes|no`, and at wall_after's time that stage's step,
                                              write interval and equilibrium steps (`key value` lines)

Why a generator rather than static dictionaries edited with foamDictionary/sed: the dictionaries depend on the
wing's size and position (domain, refinement boxes, locationInMesh outside the body, reference area), on
derived numbers (time step from a Courant number, k and omega from the intensity) and on the model (which
fields exist at all). Computing those in one place from numbers that were parsed and range-checked is simpler
and safer than editing text: nothing from the settings file reaches a shell, and every value written is a
number this script formatted or a word from a fixed list.

The generator's parts, one concern each, in the same folder and installed beside it (share/fsi):
ramair_settings.py (the settings file: keys, validation, the docs' table, fluidSettings.json),
ramair_geometry.py (the wing's STL and the numbers derived from it), ramair_dicts.py (system/ and constant/,
new meshes' dictionaries, the coupled structure scene), ramair_fields.py (0/), ramair_mesh.py (polyMesh and
checkMesh readers) and ramair_summary.py (summary.json and summary.md). This file is the command line and
keeps every name of those parts importable from it (`import ramair_fluid; ramair_fluid.read_settings`).
"""
import sys

from ramair_dicts import (HEADER, domain, split_exclude, split_stage, write, write_block_mesh, write_case,
                          write_remesh_dicts, write_split_set, write_structure)  # noqa: F401
from ramair_fields import write_fields  # noqa: F401
from ramair_geometry import (_cross, _norm, _sub, derived, read_stl, v3, wing_geometry)  # noqa: F401
from ramair_mesh import (_foam_list, _patch_range, check_mesh, mesh_gate, mirror_check, mirror_finish,
                         patch_area, read_patch)  # noqa: F401
from ramair_settings import (DIFFUSIVITY, InputError, NUMBER, RESOLUTIONS, SETTINGS, _distance, brake_inputs,
                             brake_travel, brake_window, load_record, read_brake_table, read_settings,
                             settings_table, wall_factor)  # noqa: F401
from ramair_summary import (brake_response, coupled_summary, courant_check, plot_brake, read_force_coeffs,
                            read_table, remeshes, summary, write_table)  # noqa: F401


def main(argv):
    cmds = {"generate-args": 1, "check": 1, "write": 3, "structure": 3, "fields": 1, "summary": 1,
            "settings-table": 0, "courant-check": 2,
            "patch-area": 2, "mirror-check": 1, "mirror-finish": 1, "remesh-dicts": 1, "split-stage": 3, "mesh-gate": 2,
            "split-exclude": 2}
    if len(argv) < 2 or argv[1] not in cmds or len(argv) != 2 + cmds[argv[1]]:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        cmd, args = argv[1], argv[2:]
        if cmd == "check":
            s = read_settings(args[0])
            # one word per key (a brake table as its file): Allrun reads these with sed
            print(" ".join(f"{k}={v['file'] if isinstance(v, dict) else v}" for k, v in s.items()))
        elif cmd == "generate-args":
            # The skin the fluid sees: the same generator, sampled finer than the structure (the coupling
            # maps between the two). Only validated whole numbers are printed.
            s = read_settings(args[0])
            for key in ("chordwise_points", "span_divisions"):
                if s["stl_" + key] > 0:
                    print("--set")
                    print(f"meshes.wing.generator.{key}={int(s['stl_' + key])}")
            if s["stl_bulge"] >= 0:
                print("--set")
                print(f"meshes.wing.generator.bulge={s['stl_bulge']:.9g}")
            if s["stl_deformed"]:
                print("--deformed")
                print(s["stl_deformed"])
        elif cmd == "write":
            write_case(*args)
        elif cmd == "structure":
            write_structure(*args)
        elif cmd == "fields":
            write_fields(*args)
        elif cmd == "summary":
            summary(*args)
        elif cmd == "settings-table":
            sys.stdout.write(settings_table())
        elif cmd in ("courant-check", "mesh-gate"):  # a check: exit 1 with its message
            msg = (courant_check if cmd == "courant-check" else mesh_gate)(*args)
            if msg:
                print(f"ramair_fluid: {msg}", file=sys.stderr)
                return 1
        elif cmd == "mirror-check":
            mirror_check(*args)
        elif cmd == "mirror-finish":
            mirror_finish(*args)
        elif cmd == "remesh-dicts":
            write_remesh_dicts(*args)
        elif cmd == "split-exclude":
            return 0 if split_exclude(*args) else 3
        elif cmd == "split-stage":
            print("\n".join(split_stage(*args)))
        else:
            area, n = patch_area(*args)
            print(f"{area:.9g} {n}")
    except InputError as e:
        print(f"ramair_fluid: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"ramair_fluid: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
