#!/usr/bin/python3
"""docs/RAMAIR.md's settings table is the validator's (ramair_fluid.py SETTINGS): the text between its
settings-table markers equals `ramair_fluid.py settings-table`, every key has a meaning, and a key the table
lacks or a default it misstates fails here. Usage: test_settings_table.py SOURCE_DIR"""
import re
import subprocess
import sys
from pathlib import Path

root = Path(sys.argv[1])
gen = subprocess.run(["/usr/bin/python3", str(root / "cases/coupled/ramair_fluid.py"), "settings-table"],
                     capture_output=True, text=True, check=True).stdout
doc = (root / "docs/RAMAIR.md").read_text()
m = re.search(r"<!-- settings-table:.*?-->\n(.*?)<!-- end settings-table -->", doc, re.S)
bad = []
if not m:
    bad.append("docs/RAMAIR.md: no settings-table markers")
elif m.group(1) != gen:
    doc_rows, gen_rows = m.group(1).splitlines(), gen.splitlines()
    first = next((i for i, (a, b) in enumerate(zip(doc_rows, gen_rows)) if a != b), min(len(doc_rows), len(gen_rows)))
    bad.append(f"docs/RAMAIR.md's settings table differs from `ramair_fluid.py settings-table` at row {first + 1}: "
               f"doc {doc_rows[first] if first < len(doc_rows) else '(none)'!r} vs "
               f"validator {gen_rows[first] if first < len(gen_rows) else '(none)'!r}; regenerate it")
sys.path.insert(0, str(root / "cases/coupled"))
import ramair_fluid  # noqa: E402
for key, spec in ramair_fluid.SETTINGS.items():
    if len(spec[4].strip()) < 8:
        bad.append(f"setting '{key}' has no meaning in the validator")
    if f"| `{key}` |" not in gen:
        bad.append(f"setting '{key}' missing from the generated table")
print(f"{len(ramair_fluid.SETTINGS)} settings in the validator and in docs/RAMAIR.md")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
