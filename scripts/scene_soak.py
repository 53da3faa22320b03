#!/usr/bin/env python3
"""Scene soak: runs `aloha profile` on random *valid* scenes and reports every run that does not end cleanly.

The fuzzers (scripts/fuzz.sh) feed the loaders broken bytes; this feeds the whole pipeline (loading, the LOD,
motion and geometry systems, the renderer) scenes that load, with values anywhere in their documented ranges
(docs/SCENES.md, data/schemas/scene.schema.json): coincident path points, cameras inside the crowd or under the
ground, time steps from 1e-5 to 1 s, crowds of one, heights and builds at their limits, every request type with
extreme parameters, overlays. Built for a sanitizer build of the tool (build/asan-ubsan), where a memory error or
undefined behaviour ends the run with a report (leak checking off: see main()); any build finds crashes, hangs
and validation messages.

Usage: scripts/scene_soak.py ALOHA [--runs N] [--seed S] [--keep DIR] [--timeout SECONDS] [--no-render] [--frames F]
                             [--assets DIR]
  Writes each scene to a temporary folder (DIR with --keep: failing scenes are kept there), runs
  `ALOHA profile SCENE --frames F --warmup W --quiet --force --out OUT` with validation layers on
  (ALOHA_VALIDATION=1), and prints one line per failing run: the scene, the exit status and the first lines of
  what the run printed. Exit status 1 when any run failed.
A run fails when it exits non-zero, prints a sanitizer report ("runtime error", "AddressSanitizer",
"LeakSanitizer"), prints a Vulkan validation message, or runs past the timeout. A scene the tool refuses with a
named error is also a failure here: every generated scene is meant to be valid.
"""
import argparse
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile

REQUESTS = ["play", "walk", "reach", "look_at", "rest"]
EFFECTORS = ["RightWrist", "LeftWrist", "Head", "RightAnkle", "LeftAnkle", "Hips"]
CLIPS = ["walk_0.50", "walk_1.10", "run_3.00", "idle", "turn", "wave"]
# Types made from the shared test assets (--assets), with the clips and effectors each has: CesiumMan's joint names
# match no convention, so it is a non-humanoid (file joint names, its own clip and the in-place copy); the CMU take
# is a mapped humanoid with the generated library; the built-in humanoid may also play the take retargeted.
FILE_TYPES = {
    "cm": ({"gltf": "CesiumMan.glb"}, ["clip0", "cm.inplace"], ["Skeleton_arm_joint_R__3_", "Skeleton_neck_joint_2"]),
    "cmu": ({"bvh": "131_01.bvh"}, ["cmu." + c for c in ["mocap", "inplace"] + CLIPS], EFFECTORS),
}


def vec3(r, lo=-60.0, hi=60.0, y=None):
    return [r.uniform(lo, hi), r.uniform(-1.0, 30.0) if y is None else y, r.uniform(lo, hi)]


def request(r, kind_of, paths):
    """A random request for a character of the type described by `kind_of` (a dict: clips, effectors)."""
    kind = r.choice(REQUESTS)
    q = {"type": kind}
    if r.random() < 0.7:
        q["duration"] = r.choice([-1, 0, r.uniform(0.0, 3.0), 1e6])
    if r.random() < 0.5:
        q["crossfade"] = r.choice([0.0, r.uniform(0.0, 2.0), 10.0])
    if kind == "play":
        q["clip"] = r.choice(kind_of["clips"])
        if r.random() < 0.5:
            q["loop"] = r.random() < 0.5
        if r.random() < 0.5:
            q["speed"] = r.choice([-10.0, -1.0, 0.0, r.uniform(-3.0, 3.0), 10.0])
        if r.random() < 0.3:
            q["start"] = r.choice([0.0, r.uniform(0.0, 20.0), 1e6])
        if r.random() < 0.3:
            q["root_motion"] = r.random() < 0.5
    elif kind == "walk":
        q["speed"] = r.choice([0.0, r.uniform(0.0, 4.0), 10.0])
        if paths and r.random() < 0.5:
            q["path"] = r.choice(paths)["name"]
        else:
            d = [r.uniform(-1, 1), 0.0, r.uniform(-1, 1)]
            if math.hypot(d[0], d[2]) < 1e-3:
                d = [1.0, 0.0, 0.0]
            q["direction"] = d
    elif kind in ("reach", "look_at"):
        q["effector"] = r.choice(kind_of["effectors"])
        q["target"] = vec3(r, -5, 5) if r.random() < 0.8 else [0.0, 0.0, 0.0]
        if kind == "reach" and r.random() < 0.3:
            a = [r.gauss(0, 1) for _ in range(4)]
            n = math.sqrt(sum(x * x for x in a)) or 1.0
            q["orientation"] = [x / n for x in a]
    return q


def scene(r, index, assets):
    types = []
    kinds = {}
    for t in range(r.randint(1, 3)):
        ct = {"name": f"h{t}", "humanoid": "builtin:humanoid"}
        if r.random() < 0.7:
            ct["height"] = r.choice([0.5, 2.5, r.uniform(0.5, 2.5)])
        if r.random() < 0.7:
            ct["build"] = r.choice([0.0, 1.0, r.random()])
        if assets and r.random() < 0.3:
            ct["motions"] = [{"bvh": "131_01.bvh", "name": "take"}]
        types.append(ct)
        kinds[ct["name"]] = {"clips": [f"h{t}." + c for c in CLIPS] + ([f"h{t}.take"] if "motions" in ct else []), "effectors": EFFECTORS}
    if assets:
        for name, (source, clips, effectors) in FILE_TYPES.items():
            if r.random() < 0.5:
                ct = dict(source, name=name)
                if r.random() < 0.3:
                    ct["scale"] = r.choice([0.01, 1.0, 100.0]) if name == "cm" else r.choice([0.01, 0.056444])
                types.append(ct)
                kinds[name] = {"clips": clips, "effectors": effectors}
    names = [t["name"] for t in types]
    paths = []
    for p in range(r.randint(0, 3)):
        pts = [vec3(r, -20, 20, 0.0) for _ in range(r.randint(2, 6))]
        if r.random() < 0.3:
            pts[1] = list(pts[0])  # coincident points
        paths.append({"name": f"p{p}", "loop": r.random() < 0.6, "points": pts})
    chars = []
    for _ in range(r.randint(0, 6)):
        c = {"type": r.choice(names), "position": vec3(r, -15, 15, 0.0)}
        if r.random() < 0.5:
            c["heading_deg"] = r.uniform(-3600, 3600)
        if r.random() < 0.5:
            c["importance"] = r.random()
        if r.random() < 0.2:
            c["always_full"] = True
        c["requests"] = [request(r, kinds[c["type"]], paths) for _ in range(r.randint(0, 4))]
        if r.random() < 0.25:
            o = request(r, kinds[c["type"]], paths)
            o["type"] = r.choice(["reach", "look_at"])
            o.setdefault("target", [1.0, 1.5, 1.0])
            o["effector"] = r.choice(kinds[c["type"]]["effectors"])
            for k in ("clip", "loop", "speed", "start", "root_motion", "path", "direction", "duration"):
                o.pop(k, None)
            o["weight"] = r.random()
            c["overlay"] = o
        chars.append(c)
    crowds = []
    for _ in range(r.randint(0 if chars else 1, 2)):
        cr = {"type": r.choice(names), "count": r.choice([1, 2, r.randint(0, 400)]), "seed": r.randint(0, 1 << 30)}
        if r.random() < 0.5:
            cr["layout"] = "disc"
            cr["radius"] = r.choice([0.1, r.uniform(0.1, 60.0)])
        else:
            cr["layout"] = "grid"
            cr["spacing"] = r.choice([0.1, r.uniform(0.1, 5.0)])
        if r.random() < 0.5:
            cr["center"] = vec3(r, -20, 20, 0.0)
        cr["walk_route"] = r.choice(["straight", "circle"])
        # A non-humanoid crowd has no wrists to reach with (an error naming /crowds/N/mix/reach): walk and idle only.
        mix = {k: r.random() for k in ("walk", "idle", "reach") if r.random() < 0.8 and not (k == "reach" and cr["type"] == "cm")}
        if cr["type"] == "cm":
            mix["reach"] = 0.0
        if sum(mix.values()) > 0:
            cr["mix"] = mix
        if r.random() < 0.5:
            a, b = sorted([r.random(), r.random()])
            cr["importance"] = [a, b]
        if r.random() < 0.5:
            a, b = sorted([r.uniform(0, 10), r.uniform(0, 10)])
            cr["speed"] = [a, b]
        if r.random() < 0.5 and cr["type"] != "cm":  # height variants need a mapped humanoid
            a, b = sorted([r.uniform(0.5, 2.5), r.uniform(0.5, 2.5)])
            cr["height"] = [a, b]
            if cr["type"] not in FILE_TYPES:  # a file type takes a height range only
                cr["build"] = sorted([r.random(), r.random()])
            cr["variants"] = r.choice([1, r.randint(1, 64), 64])
        crowds.append(cr)
    near = r.choice([0.0001, 0.01, 0.1, 1.0])
    camera = {"fov_deg": r.choice([1.0, 170.0, r.uniform(20, 100)]), "near": near, "far": near * r.choice([10.0, 1e3, 1e7])}
    if chars and r.random() < 0.35:
        # Close to a placed character: the top levels (layered bodies, subdivision) and their switches.
        at = r.choice(chars)["position"]
        a = r.uniform(0, 2 * math.pi)
        d = r.uniform(1.0, 6.0)
        camera["position"] = [at[0] + d * math.sin(a), r.uniform(0.3, 2.5), at[2] + d * math.cos(a)]
        camera["target"] = [at[0], r.uniform(0.5, 1.5), at[2]]
    elif r.random() < 0.6:
        camera["position"] = vec3(r)
        camera["target"] = vec3(r, -10, 10, r.uniform(0, 2))
        if camera["target"] == camera["position"]:
            camera["target"][0] += 1.0
    else:
        t = 0.0
        keys = []
        for _ in range(r.randint(1, 4)):
            keys.append({"time": t, "position": vec3(r), "target": vec3(r, -10, 10, 1.0)})
            t += r.uniform(0.0, 2.0)
        camera["keys"] = keys
    dt = r.choice([1e-5, 1.0, 1.0 / 60.0, 1.0 / 30.0, 1.0 / 60.0, 10 ** r.uniform(-5, 0)])
    return {"name": f"soak_{index}", "frames": 20, "dt": dt, "seed": r.randint(0, 1 << 30),
            "viewport": {"width": r.choice([16, 64, r.randint(16, 480)]), "height": r.choice([16, 48, r.randint(16, 320)])},
            "camera": camera, "character_types": types, "paths": paths, "characters": chars, "crowds": crowds}


BAD_WORDS = ("runtime error", "AddressSanitizer", "LeakSanitizer", "Validation Error", "VUID-")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("aloha")
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", default="")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--no-render", action="store_true")
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--assets", default=os.environ.get("ALOHA_TEST_ASSETS", os.path.join(os.path.dirname(__file__), "..", "..", "shared", "assets")),
                    help="folder of CesiumMan.glb and 131_01.bvh (default $ALOHA_TEST_ASSETS, else ../shared/assets); "
                         "without them only built-in humanoids are made")
    args = ap.parse_args()
    r = random.Random(args.seed)
    work = args.keep or tempfile.mkdtemp(prefix="aloha_soak_")
    os.makedirs(work, exist_ok=True)
    env = dict(os.environ, ALOHA_VALIDATION="1")
    # The Vulkan loader and lavapipe are dlopen'ed and unloaded: what they keep at exit reads as leaks in an
    # "<unknown module>" that LeakSanitizer cannot name or suppress. The project's own leaks are the sanitizer
    # unit tests' business (ctest --preset asan-ubsan); here leak checking is off unless ASAN_OPTIONS says otherwise.
    env.setdefault("ASAN_OPTIONS", "detect_leaks=0")
    assets = all(os.path.isfile(os.path.join(args.assets, f)) for f in ("CesiumMan.glb", "131_01.bvh"))
    if assets:
        for f in ("CesiumMan.glb", "131_01.bvh"):
            shutil.copyfile(os.path.join(args.assets, f), os.path.join(work, f))
    else:
        print(f"no CesiumMan.glb and 131_01.bvh in {args.assets}: built-in humanoids only", flush=True)
    failed = 0
    for i in range(args.runs):
        doc = scene(r, i, assets)
        path = os.path.join(work, f"soak_{args.seed}_{i}.json")
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
        out = os.path.join(work, f"out_{args.seed}_{i}")
        cmd = [args.aloha, "profile", path, "--frames", str(args.frames), "--warmup", "2", "--quiet", "--force", "--out", out]
        if args.no_render:
            cmd.append("--no-render")
        try:
            p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=args.timeout)
            text, rc = p.stdout + p.stderr, p.returncode
        except subprocess.TimeoutExpired:
            text, rc = "timed out", "timeout"
        bad = [line for line in text.splitlines() if any(w in line for w in BAD_WORDS)]
        ok = rc == 0 and not bad
        shutil.rmtree(out, ignore_errors=True)
        if ok:
            if not args.keep:
                os.remove(path)
            print(f"ok   {path}", flush=True)
            continue
        failed += 1
        head = "\n    ".join((bad or text.splitlines())[:12])
        print(f"FAIL {path}: exit {rc}\n    {head}", flush=True)
    print(f"{args.runs - failed} of {args.runs} scenes ran cleanly; scenes in {work}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
