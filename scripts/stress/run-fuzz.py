#!/usr/bin/python3
"""Meshes fuzz.py's parts in three poses and lists what went wrong.

usage: run-fuzz.py LIST.tsv RESULTS.jsonl [--bin LAYTRACKS] [--deadline EPOCH_SECONDS]

LIST.tsv is what `fuzz.py gen` prints. Each part is meshed with `laytracks mesh` at its own
size (one thread, 60 s at most) in its own pose, rotated in 3D and moved (a rotation drawn from
the part's seed), and mirrored and scaled by 1e-3 (the size too). One JSON line per part goes
to RESULTS.jsonl (status, quads and seconds per pose); a part already in RESULTS.jsonl is
skipped, so a run can be resumed. At the end: how many parts mesh in every pose, how many give
the same quad count in every pose, and each part that does not, with its first message.
Not a test: 600 parts take 15-25 minutes on one core.
"""
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
POSES = ("own", "rot", "mir")


def rotation(rnd):
    """A uniformly random rotation matrix (from a random unit quaternion)."""
    q = [rnd.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = [c / n for c in q]
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def posed(part, kind, seed):
    """The part turned and moved ("rot") or mirrored and scaled by 1e-3 ("mir")."""
    d = json.loads(json.dumps(part))
    if kind == "rot":
        rnd = random.Random(seed)
        m = rotation(rnd)
        t = [rnd.uniform(-100, 100) for _ in range(3)]
        s = 1.0
        f = lambda p: [sum(m[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]
    else:
        s = 1e-3
        f = lambda p: [-p[0] * s, p[1] * s, p[2] * s]
    d["vertices"] = [f(p) for p in d["vertices"]]
    for a in d.get("arcs", []):
        a["via"] = f(a["via"])
    d["mesh"]["size"] *= s
    return d


def quads_in(msh):
    """Quads and other elements in an MSH 4.1 file."""
    with open(msh) as fh:
        lines = fh.read().split("\n")
    i = lines.index("$Elements")
    blocks = int(lines[i + 1].split()[0])
    k, quads, other = i + 2, 0, 0
    for _ in range(blocks):
        _, _, kind, n = map(int, lines[k].split())
        k += 1 + n
        if kind == 3:
            quads += n
        else:
            other += n
    return quads, other


def mesh(binary, path, out):
    if os.path.exists(out):
        os.remove(out)
    env = dict(os.environ, LAYTRACKS_THREADS="1")
    t0 = time.time()
    try:
        p = subprocess.run([binary, "mesh", path, "-o", out, "--quiet"], capture_output=True,
                           text=True, timeout=60, env=env)
        rc, lines = p.returncode, p.stderr.strip().split("\n")
        err = lines[-1] if p.stderr.strip() else ""
    except subprocess.TimeoutExpired:
        rc, err = "timeout", ""
    r = {"rc": rc, "err": err if rc != 0 else "", "quads": None, "t": round(time.time() - t0, 3)}
    if rc == 0:
        if not os.path.exists(out):
            r["err"] = "no output file"
        else:
            quads, other = quads_in(out)
            r["quads"] = quads
            if other:
                r["err"] = "%d elements other than quads" % other
    return r


def main():
    args = sys.argv[1:]
    binary = os.path.join(ROOT, "build", "cli", "laytracks")
    deadline = float("inf")
    if "--bin" in args:
        i = args.index("--bin")
        binary = args[i + 1]
        del args[i:i + 2]
    if "--deadline" in args:
        i = args.index("--deadline")
        deadline = float(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    listing, results = args
    done = set()
    if os.path.exists(results):
        with open(results) as fh:
            done = {json.loads(line)["file"] for line in fh}
    work = tempfile.mkdtemp(prefix="laytracks-fuzz-")
    out = os.path.join(work, "out.msh")
    with open(results, "a") as res, open(listing) as fh:
        for line in fh:
            path, family, seed, name, estimate = line.rstrip("\n").split("\t")
            if path in done:
                continue
            if time.time() > deadline:
                print("run-fuzz: deadline reached", file=sys.stderr)
                break
            with open(path) as pf:
                part = json.load(pf)
            rec = {"file": path, "family": family, "seed": int(seed), "name": name,
                   "estimate": float(estimate), "own": mesh(binary, path, out)}
            for kind in POSES[1:]:
                if rec["own"]["rc"] == "timeout":
                    rec[kind] = {"rc": "skipped", "err": "", "quads": None, "t": 0}
                    continue
                pose = os.path.join(work, "pose.json")
                with open(pose, "w") as pf:
                    json.dump(posed(part, kind, int(seed)), pf)
                rec[kind] = mesh(binary, pose, out)
            res.write(json.dumps(rec) + "\n")
            res.flush()
            print(family, os.path.basename(path), name,
                  [(rec[k]["rc"], rec[k]["quads"], rec[k]["t"]) for k in POSES], flush=True)
    shutil.rmtree(work, ignore_errors=True)
    summarize(results)


def summarize(results):
    with open(results) as fh:
        recs = [json.loads(line) for line in fh]
    meshed = [r for r in recs if all(r[k]["rc"] == 0 and not r[k]["err"] for k in POSES)]
    same = [r for r in meshed if len({r[k]["quads"] for k in POSES}) == 1]
    print("%d parts: %d mesh in every pose, %d with the same quad count in every pose; slowest "
          "run %.1f s" % (len(recs), len(meshed), len(same),
                          max((r[k]["t"] for r in recs for k in POSES), default=0.0)))
    for r in recs:
        if r in same:
            continue
        first = next((r[k]["err"] for k in POSES if r[k]["err"]), "")
        print("  %s (%s): %s %s %s" % (os.path.basename(r["file"]), r["name"],
                                       [r[k]["rc"] for k in POSES], [r[k]["quads"] for k in POSES],
                                       first[:200]))


if __name__ == "__main__":
    main()
