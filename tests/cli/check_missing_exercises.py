#!/usr/bin/env python3
"""`./springlab test`'s summary in a student tree (tools/missing_exercises.py): a lab whose
exercise files still hold the skeleton's stubs lists them; a written exercise is not listed;
a finished lab says so.

    check_missing_exercises.py ROOT
"""
import pathlib
import shutil
import subprocess
import sys
import tempfile

root = pathlib.Path(sys.argv[1])
failures = []
with tempfile.TemporaryDirectory() as tmp:
    tree = pathlib.Path(tmp)
    # A student who wrote exercise 1.1 of Lab 1 and nothing else; Lab 2 finished.
    shutil.copytree(root / "labs" / "01_rope", tree / "labs" / "01_rope")
    shutil.copytree(root / "labs" / "02_net", tree / "labs" / "02_net")
    for lab in ("01_rope", "02_net"):
        (tree / "tests" / lab).mkdir(parents=True)
        shutil.copy(root / "tests" / lab / "exercises.json", tree / "tests" / lab / "exercises.json")
    written = (tree / "labs" / "01_rope" / "spring_force.cpp")
    written.write_text(written.read_text().replace(
        'throw springlab::NotImplemented("1.1"', 'return Vec3::Zero(); // was: throw NotImplemented("1.1"'))
    for cpp in (tree / "labs" / "02_net").glob("*.cpp"):
        cpp.write_text("// written\n")
    p = subprocess.run([sys.executable, str(root / "tools" / "missing_exercises.py"), str(tree)],
                       capture_output=True, text=True, timeout=60)
    out = p.stdout
    if p.returncode != 0:
        failures.append(f"exit {p.returncode}\n{p.stderr}")
    for needle in ("Lab 1: the rope: 7 missing", "1.2 gravity and air friction (labs/01_rope/gravity_air.cpp)",
                   "1.8 fixed end", "Lab 2: the elastic net: none, every exercise is written"):
        if needle not in out:
            failures.append(f"summary lacks {needle!r}")
    if "1.1 spring-damper force" in out:
        failures.append("the written exercise 1.1 is listed as missing")
for f in failures:
    print("FAIL:", f)
print(out if failures else "missing exercises summary: ok")
sys.exit(1 if failures else 0)
