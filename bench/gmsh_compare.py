#!/usr/bin/env python3
"""Meshes a part with `gmsh -2` at the quad count of each row of a bench_mesh JSON report, and
rates every Gmsh mesh with our checker (`laytracks quality`).

    python3 bench/gmsh_compare.py OURS.json --laytracks BIN --work DIR -o OUT.json
                                  [--timeout S] [--tolerance F]

OURS.json is what `bench_mesh PART.json ... --json OURS.json` wrote (or a stub with "part" and
"rows" whose status is "timeout"). For each row the quad count to match is ours when the row
was meshed; otherwise the row's --target-quads, or area / size^2 for a size we refused.

Gmsh runs on the .geo of bench/brep_to_geo.py (Mesh.Algorithm 6 Frontal-Delaunay,
RecombineAll, Blossom recombination, arcs as true circles) with `-nt 1` (one thread, as our
mesher runs), and its characteristic length lc is searched so that its element count is
within --tolerance of the count N to match (5% by default, 10% above 200,000 quads, where a
Gmsh run takes minutes):
- the first mesh has lc0 = sqrt(area / min(N, 2000)) (cheap); while a mesh has fewer than
  N / 16 elements, lc is scaled by sqrt(count / goal), goal = min(16 count, N / 8); then lc is
  scaled by sqrt(count / N) and meshed again, until the count is within the tolerance
  (elements go as 1 / lc^2) or 5 candidates (meshes of at least N / 2 elements) were made.
  The candidate closest to N is kept (counts come in steps: the closed cube's edges get 9
  or 10 segments, 473 or 717 quads, nothing between); if it is still beyond the tolerance it
  is marked "nearest";
- after the ladder, lc never exceeds 1.5 x our element size h (3 h with subdivision): past
  that the count hardly falls (every boundary vertex is a node and every curve gets at least
  one edge) and Gmsh starts to make elements across narrow features (cgal_Detmier: valid at
  2 h with subdivision, inverted quads at its 0.0125-wide steps from 3 h);
- Mesh.SubdivisionAlgorithm = 0 for that search. If the mesh it ends on still has triangles,
  the search is done again with Mesh.SubdivisionAlgorithm = 1 (every quad split into 4 quads
  and every triangle into 3, so all-quad), from twice the lc; the unsubdivided mesh's counts
  are kept as "without_subdivision".
For a row that our mesher refused, Gmsh meshes once at lc = our element size (and, if
triangles remain, once more at 2 lc with subdivision): there is no count to match. For a row
that timed out, the count asked for (--target-quads) is matched. A Gmsh run that exceeds
--timeout (default 3600 s) makes the row "timeout" unless a candidate within the
tolerance came before it.
The last mesh is rated by `laytracks quality PART MSH --json`, and its times are Gmsh's own
"Done meshing 1D / 2D" and "Done refining mesh" wall and CPU seconds from its log (reading the
.geo and writing the .msh excluded, as bench_mesh excludes them) besides the wall time of the
whole command. Then both whole commands are timed, best of 3 (1 above 200,000 quads): ours,
`laytracks mesh PART -o OUT.msh --size h` (reading, meshing, the self-check, writing), and
Gmsh's `gmsh -2` of the matched mesh (reading the .geo, meshing, writing): "commands".
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def part_size(path):
    """Twice the largest distance of a used vertex from their centroid (Part::size)."""
    with open(path) as f:
        part = json.load(f)
    used = sorted({v for p in part["patches"] for loop in p["loops"] for v in loop})
    pts = [part["vertices"][i] for i in used]
    c = [sum(p[k] for p in pts) / len(pts) for k in range(3)]
    return 2.0 * max(math.dist(p, c) for p in pts)


def count_elements(msh):
    """(quads, triangles, nodes) of the surface elements of an MSH 4.1 ASCII file."""
    quads = tris = nodes = 0
    with open(msh) as f:
        for line in f:
            if line.startswith("$Nodes"):
                nodes = int(f.readline().split()[1])
            elif line.startswith("$Elements"):
                blocks = int(f.readline().split()[0])
                for _ in range(blocks):
                    dim, _tag, etype, n = (int(x) for x in f.readline().split())
                    for _ in range(n):
                        f.readline()
                    if dim == 2 and etype == 3:
                        quads += n
                    elif dim == 2 and etype == 2:
                        tris += n
                break
    return quads, tris, nodes


LOG_STAGE = re.compile(r"Done (meshing [0-9]D|refining mesh|optimizing mesh)"
                       r" \(Wall ([0-9.eE+-]+)s, CPU ([0-9.eE+-]+)s\)")


def run_gmsh(geo, msh, lc, subdivide, timeout, log):
    """Runs gmsh -2 once; returns a dict with the counts and times, or status timeout/failed."""
    cmd = ["gmsh", geo, "-2", "-nt", "1", "-setnumber", "lc", repr(lc),
           "-setnumber", "subdivide", str(subdivide), "-format", "msh41", "-o", msh]
    if os.path.exists(msh):
        os.remove(msh)
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"lc": lc, "subdivide": subdivide, "status": "timeout", "wall": timeout}
    wall = time.monotonic() - t0
    with open(log, "w") as f:
        f.write(p.stdout)
    r = {"lc": lc, "subdivide": subdivide, "wall": wall}
    if p.returncode != 0 or not os.path.exists(msh):
        errors = [l for l in p.stdout.splitlines() if l.startswith("Error")]
        r.update(status="failed", message=(errors[0] if errors else "exit %d" % p.returncode))
        return r
    mesh_wall = mesh_cpu = 0.0
    for m in LOG_STAGE.finditer(p.stdout):
        mesh_wall += float(m.group(2))
        mesh_cpu += float(m.group(3))
    q, t, n = count_elements(msh)
    r.update(status="ok", quads=q, triangles=t, nodes=n, mesh_wall=mesh_wall, mesh_cpu=mesh_cpu,
             warnings=sum(1 for l in p.stdout.splitlines() if l.startswith("Warning")))
    return r


def rate(laytracks, part, msh, out_json):
    """laytracks quality: the summary JSON, validity and the rules that failed."""
    p = subprocess.run([laytracks, "quality", part, msh, "--json", out_json, "--quiet"],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    rules = {}
    for line in p.stderr.splitlines():
        m = re.match(r"rule ([0-9]):", line)
        if m:
            rules[m.group(1)] = rules.get(m.group(1), 0) + 1
    if p.returncode not in (0, 5):
        return {"valid": False, "error": p.stderr.strip()[:500]}
    with open(out_json) as f:
        summary = json.load(f)
    first = [l for l in p.stderr.splitlines() if l.startswith("rule")][:3]
    return {"valid": p.returncode == 0, "failed_rules": sorted(rules), "first_failures": first,
            "quality": summary}


def best_wall(cmd, repeats):
    """The shortest wall time of `repeats` runs of cmd (output discarded)."""
    best = None
    for _ in range(repeats):
        t0 = time.monotonic()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        t = time.monotonic() - t0
        best = t if best is None else min(best, t)
    return best


def time_commands(laytracks, part, row, geo, base, r):
    """What a user waits for: the whole `laytracks mesh PART -o OUT.msh` (reading the part,
    writing the file, the self-check) and the whole `gmsh -2` of the matched mesh, best of 3
    (1 above 200,000 quads)."""
    repeats = 3 if r["quads"] <= 200000 else 1
    ours = best_wall([laytracks, "mesh", part, "-o", base + "-ours.msh", "--quiet",
                      "--size", repr(row["size"])], repeats)
    gmsh = best_wall(["gmsh", geo, "-2", "-nt", "1", "-setnumber", "lc", repr(r["lc"]),
                      "-setnumber", "subdivide", str(r["subdivide"]), "-format", "msh41",
                      "-o", base + "-timed.msh"], repeats)
    return {"ours": ours, "gmsh": gmsh, "repeats": repeats}


def record(runs, r):
    runs.append({k: v for k, v in r.items() if k in
                 ("lc", "subdivide", "status", "quads", "triangles", "wall")})


def search(geo, msh, log, target, lc, lc_max, subdivide, timeout, tolerance, runs):
    """Meshes at lc, then rescales lc (never above lc_max) until the element count is within
    the tolerance of target, by the ladder of the module comment. Returns the candidate run
    (count >= target / 2) closest to target, its mesh and log left at msh and log, with
    "nearest": True when it is still beyond the tolerance; or the failed run (timeout, gmsh
    error) when no candidate came before it."""
    tried = []  # lc of every candidate run
    best = None  # (run, count)
    while True:
        r = run_gmsh(geo, msh, lc, subdivide, timeout, log)
        record(runs, r)
        if r["status"] != "ok":
            if best is None or abs(best[1] - target) > tolerance * target:
                for f in (msh + ".best", log + ".best"):
                    if os.path.exists(f):
                        os.remove(f)
                return r
            break
        q = max(r["quads"] + r["triangles"], 1)
        if q < target / 16.0 and not tried:
            # The ladder: coarser than the final mesh, so lc_max does not apply.
            lc *= math.sqrt(q / min(16.0 * q, target / 8.0))
            continue
        if q >= target / 2.0:
            tried.append(lc)
            if best is None or abs(q - target) < abs(best[1] - target):
                best = (r, q)
                shutil.copyfile(msh, msh + ".best")
                shutil.copyfile(log, log + ".best")
            if abs(q - target) <= tolerance * target or len(tried) >= 5:
                break
        # Counts come in steps (edges get whole numbers of segments): never retry an lc.
        lc = min(lc * math.sqrt(q / target), lc_max)
        if any(abs(lc - l) <= 1e-9 * lc for l in tried):
            break
    if best is None:
        return r
    os.replace(msh + ".best", msh)
    os.replace(log + ".best", log)
    r = best[0]
    if abs(best[1] - target) > tolerance * target:
        r["nearest"] = True  # no lc tried gave a count within the tolerance
    return r


def match(geo, msh, log, target, lc, h, timeout, tolerance, runs):
    """The mesh of about `target` quads (or, with target None, the one mesh at lc): without
    subdivision, then, if triangles remain, with Mesh.SubdivisionAlgorithm = 1. `h` is our
    element size (None if unknown): lc stays at most 1.5 h, 3 h with subdivision."""
    if target is None:
        r = run_gmsh(geo, msh, lc, 0, timeout, log)
        record(runs, r)
        if r["status"] == "ok" and r["triangles"] > 0:
            first = {k: r[k] for k in ("lc", "quads", "triangles")}
            r = run_gmsh(geo, msh, 2.0 * lc, 1, timeout, log)
            record(runs, r)
            r["without_subdivision"] = first
        return r
    cap = math.inf if h is None else 1.5 * h
    r = search(geo, msh, log, target, lc, cap, 0, timeout, tolerance, runs)
    if r["status"] == "ok" and r["triangles"] > 0:
        first = {k: r[k] for k in ("lc", "quads", "triangles")}
        # Subdivision makes 4 quads of a quad and 3 of a triangle: twice the lc for as many.
        q, t = r["quads"], r["triangles"]
        lc = r["lc"] * 2.0 * math.sqrt((q + 0.75 * t) / max(q + t, 1))
        r = search(geo, msh, log, target, min(lc, 2.0 * cap), 2.0 * cap, 1, timeout, tolerance,
                   runs)
        r["without_subdivision"] = first
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ours")
    ap.add_argument("--laytracks", required=True)
    ap.add_argument("--work", required=True, help="folder for the .geo, .msh and logs")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--timeout", type=float, default=3600.0, help="seconds per gmsh run")
    ap.add_argument("--tolerance", type=float, default=0.05,
                    help="relative count difference accepted (doubled above 200,000 quads)")
    args = ap.parse_args()

    with open(args.ours) as f:
        ours = json.load(f)
    part = ours["part"]
    stem = os.path.splitext(os.path.basename(part))[0]
    os.makedirs(args.work, exist_ok=True)
    with open(part) as f:
        has_arcs = bool(json.load(f).get("arcs"))
    geo = os.path.join(args.work, stem + ".geo")
    subprocess.run([sys.executable, os.path.join(HERE, "brep_to_geo.py"), part, "-o", geo],
                   check=True)

    ours_stem = os.path.splitext(os.path.basename(args.ours))[0]
    rows = []
    for i, row in enumerate(ours["rows"]):
        req = row.get("request")
        if row.get("status") == "ok":
            target, lc = row["quads"], math.sqrt(ours["area"] / min(row["quads"], 2000))
        elif "size" in row:
            target, lc = None, row["size"]  # refused: Gmsh at the same element size
        else:
            target = req["target_quads"]  # timed out: the count asked for
            lc = math.sqrt(ours["area"] / min(target, 2000)) if ours.get("area") else \
                part_size(part) / math.sqrt(min(target, 2000))
        # Named after OURS.json, so runs of one part at several sizes keep their own files.
        base = os.path.join(args.work, "%s-%d" % (ours_stem, i))
        runs = []
        tolerance = args.tolerance if target is None or target <= 200000 else 2 * args.tolerance
        r = match(geo, base + ".msh", base + ".log", target, lc, row.get("size"), args.timeout,
                  tolerance, runs)
        g = {"target_quads": target, "runs": runs}
        g.update(r)
        if r["status"] == "ok":
            g.update(rate(args.laytracks, part, base + ".msh", base + "-quality.json"))
        if r["status"] == "ok" and row.get("status") == "ok":
            g["commands"] = time_commands(args.laytracks, part, row, geo, base, r)
        rows.append({"ours": row, "gmsh": g})
        print("%s row %d: ours %s, gmsh %s quads (target %s), valid %s" %
              (stem, i, row.get("quads", row.get("status")), r.get("quads", r["status"]),
               target, g.get("valid")), file=sys.stderr)

    with open(args.output, "w") as f:
        json.dump({"part": part, "patches": ours.get("patches"), "area": ours.get("area"),
                   "has_arcs": has_arcs, "rows": rows}, f, indent=1)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
