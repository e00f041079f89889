#!/usr/bin/env python3
"""Command-line behaviour users rely on: bad scene files and options get a clear error that
names the file and the key, and a non-zero exit; a good run writes its output; a run that
blows up says so and exits 4; a missing exercise exits 3 and names it.

    check_cli.py APP_STUDENT APP_REFERENCE SCENES_DIR
"""
import json
import pathlib
import re
import subprocess
import sys
import tempfile

student, reference, scenes = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3])
failures = []


def run(app, *args, cwd=None):
    return subprocess.run([app, *args], capture_output=True, text=True, timeout=120, cwd=cwd)


def expect(name, proc, code, *needles):
    text = proc.stdout + proc.stderr
    if proc.returncode != code:
        failures.append(f"{name}: exit code {proc.returncode}, expected {code}\n{text}")
    for n in needles:
        if n not in text:
            failures.append(f"{name}: output lacks {n!r}\n{text}")


good = json.loads((scenes / "rope.json").read_text())
with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)

    def scene_with(name, mutate=None, text=None):
        path = tmp / f"{name}.json"
        data = json.loads(json.dumps(good))
        if mutate:
            mutate(data)
        path.write_text(text if text is not None else json.dumps(data))
        return str(path)

    out = str(tmp / "out.json")
    bad = {
        "malformed": (scene_with("malformed", text='{"lab": "rope",'), "malformed JSON"),
        "nan": (scene_with("nan", text=json.dumps(good).replace('"mass": 0.05', '"mass": NaN')), "malformed JSON"),
        "missing": (scene_with("missing", lambda d: d["rope"].pop("spring_constant")), "rope.spring_constant: missing key"),
        "unknown": (scene_with("unknown", lambda d: d["rope"].update(colour="red")), "rope.colour: unknown key"),
        "type": (scene_with("type", lambda d: d["rope"].update(masses="many")), "rope.masses: must be an integer"),
        "zero_mass": (scene_with("zero_mass", lambda d: d["rope"].update(mass=0)), "rope.mass: must be > 0"),
        "stiffness": (scene_with("stiffness", lambda d: d["rope"].update(spring_constant=-1)), "rope.spring_constant: must be > 0"),
        "integrator": (scene_with("integrator", lambda d: d.update(integrator="magic")), "integrator: unknown integrator"),
        "top_level": (scene_with("top_level", lambda d: d.update(speed=3)), "speed: unknown key"),
    }
    for name, (path, needle) in bad.items():
        expect(f"bad scene {name}", run(reference, "sim", path, "--steps", "10", "--out", out), 2, path, needle)

    expect("unknown integrator option", run(reference, "sim", str(scenes / "rope.json"), "--steps", "10", "--out", out,
                                            "--integrator", "magic"), 2, "unknown integrator")
    # A file of every step that its disk cannot hold (80 masses x 1e10 steps: about 1e5 GB) is
    # refused before the run, naming the file and the --save-every that would fit.
    expect("output larger than its disk", run(reference, "sim", str(scenes / "rope.json"), "--steps", "10000000000",
                                              "--out", out), 2, out, "GB free", "--save-every 960001")
    expect("bad output extension", run(reference, "sim", str(scenes / "rope.json"), "--steps", "10", "--out",
                                       str(tmp / "out.txt")), 2, ".json or .csv")

    # A good run writes frames; a blow-up says why and exits 4; the skeleton names its exercise.
    expect("good run", run(reference, "sim", str(scenes / "rope.json"), "--steps", "100", "--out", out), 0, "steps/s")
    frames = json.loads(pathlib.Path(out).read_text())["frames"]
    if len(frames) != 101:
        failures.append(f"good run: {len(frames)} frames written, expected 101")
    # Without --out a run writes nothing and still prints its summary (the handouts' commands).
    before = sorted(tmp.iterdir())
    expect("run without --out", run(reference, "sim", str(scenes / "rope.json"), "--steps", "100", cwd=tmp), 0,
           "steps/s", "total energy", "nothing written")
    if sorted(tmp.iterdir()) != before:
        failures.append("run without --out: wrote a file")
    expect("blow-up without --out", run(reference, "sim", str(scenes / "rope.json"), "--steps", "1000", "--dt", "0.01"),
           4, "blew up")
    expect("blow-up", run(reference, "sim", str(scenes / "rope.json"), "--steps", "1000", "--dt", "0.01", "--out", out),
           4, "blew up", "is stable only below dt =")
    expect("skeleton", run(student, "sim", str(scenes / "rope.json"), "--steps", "10", "--out", out), 3,
           "not implemented: exercise 1.7")

# sim --profile splits a step into phases that add up to 100 %.
with tempfile.TemporaryDirectory() as tmp:
    proc = run(reference, "sim", str(scenes / "net_hanging.json"), "--steps", "20", "--out", str(pathlib.Path(tmp) / "o.json"),
               "--profile")
    expect("profile", proc, 0, "profile:", "ms/step", "forces", "integration", "collisions", "stretch limit")
    shares = [int(p) for p in re.findall(r"\((\d+) %\)", proc.stdout)]
    if not 95 <= sum(shares) <= 105:
        failures.append(f"profile: phase shares add up to {sum(shares)} %, expected 100\n{proc.stdout}")

# Lab 3: a scene whose mesh file cannot hold a gas names the scene key, the mesh file and the
# face; the skeleton names its first missing exercise.
soft = json.loads((scenes / "softbody_pillow_obj.json").read_text())
with tempfile.TemporaryDirectory() as tmp:
    tmp = pathlib.Path(tmp)
    (tmp / "open.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n")
    soft["softbody"]["mesh"]["file"] = "open.obj"
    bad_mesh = tmp / "bad_mesh.json"
    bad_mesh.write_text(json.dumps(soft))
    out = str(tmp / "out.json")
    expect("open mesh", run(reference, "sim", str(bad_mesh), "--steps", "10", "--out", out), 2,
           "softbody.mesh.file", "open.obj", "face 1 (vertices 1 3 2)", "not closed")
    expect("softbody skeleton", run(student, "sim", str(scenes / "softbody_ball.json"), "--steps", "10", "--out", out),
           3, "not implemented: exercise 3.2")

for f in failures:
    print("FAIL", f, file=sys.stderr)
print(f"{len(failures)} failure(s)" if failures else "command line behaves")
sys.exit(1 if failures else 0)
