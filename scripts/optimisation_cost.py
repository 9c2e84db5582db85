#!/usr/bin/python3
"""Optimisation time against the meshing time before it (issue 8's time target), per case.

Runs `tetmesher mesh IN -o OUT.vtu -q --timings --stats [--size H]` REPS times per case and
takes, separately, the least meshing time (input diagnosis through edge splitting) and the
least optimisation time: on a shared machine the least of several runs is the one least
disturbed. Prints both, their ratio, and the quality of the result (Q min, min dihedral).

With --compare OTHER, each case also runs a second binary, the two in turn (A B, B A, ...), and
the table sets their optimisation times, meshing times and quality side by side, with sums: how
a change to the optimiser (or before it) was judged. --cases data runs every Data/ surface at the
default size instead of the sized cases; all runs both.

Usage: /usr/bin/python3 scripts/optimisation_cost.py [--tetmesher build/bin/tetmesher] [--reps 5]
           [--compare OTHER_TETMESHER] [--cases sized|data|all]
"""
import glob
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The sized benchmark's good-surface cases (h = mean boundary edge, and h/2 on the fine ones);
# None: the default size (the mean boundary edge at each vertex).
CASES = [("sphere.off", 0.1497), ("cube.vtp", 0.142259), ("cube.vtp", 0.0711294),
         ("icosphere.vtp", 0.15073), ("icosphere.vtp", 0.0753649), ("torus.vtp", 0.127591),
         ("torus.vtp", 0.0637954), ("nested_spheres.vtp", None), ("knot1.off", None),
         ("fandisk.off", None), ("cube.vtp", 0.0303)]
MESHING = ["input diagnosis", "size sources", "surface input and checks",
           "Delaunay of the surface points", "boundary recovery", "regions and compaction",
           "mesh assembly", "size field and refinement setup", "lattice candidates",
           "lattice insertion", "edge splitting"]


def run_once(tetmesher, path, h, out):
    cmd = [tetmesher, "mesh", path, "-o", out, "-q", "--timings", "--stats"]
    if h:
        cmd += ["--size", repr(h)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), done.stderr))
    text = done.stdout + done.stderr
    stage = {m.group(2): float(m.group(1))
             for m in re.finditer(r"^\s+([0-9.]+)\s+(.+?)\s*$", text, re.M)}
    return (sum(stage.get(k, 0.0) for k in MESHING), stage.get("optimisation", 0.0),
            re.search(r"quality Q\s+min ([0-9.]+)", text).group(1),
            re.search(r"dihedral\s+min ([0-9.]+)", text).group(1),
            re.search(r"(\d+) tetrahedra", text).group(1))


def cases(which):
    data = [(os.path.basename(p), None)
            for p in sorted(glob.glob(os.path.join(ROOT, "Data", "*.*")))
            if p.endswith((".off", ".vtp", ".stl"))]
    return {"sized": CASES, "data": data, "all": CASES + data}[which]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tetmesher", default=os.path.join(ROOT, "build", "bin", "tetmesher"))
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--compare", help="a second tetmesher binary, run in turn with the first")
    ap.add_argument("--cases", choices=["sized", "data", "all"], default="sized")
    args = ap.parse_args()
    out = os.path.join(tempfile.mkdtemp(), "out.vtu")
    if args.compare:
        compare(args, out)
        return
    print("| case | h | meshing s | optimisation s | opt / meshing | Q min | min dihedral | tets |")
    print("|---|---|---|---|---|---|---|---|")
    worst = 0.0
    for name, h in cases(args.cases):
        runs = [run_once(args.tetmesher, os.path.join(ROOT, "Data", name), h, out)
                for _ in range(args.reps)]
        meshing = min(r[0] for r in runs)
        optimisation = min(r[1] for r in runs)
        _, _, qmin, dmin, tets = runs[0]
        worst = max(worst, optimisation / meshing)
        print("| %s | %s | %.3f | %.3f | %.2f | %s | %s | %s |" % (
            name, "default" if h is None else h, meshing, optimisation,
            optimisation / meshing, qmin, dmin, tets), flush=True)
    print("\nlargest opt / meshing: %.2f" % worst)


def compare(args, out):
    """A (--tetmesher) and B (--compare) in turn on each case; least times of the reps."""
    print("| case | h | opt A s | opt B s | B / A | meshing A s | meshing B s | Q min A | Q min B "
          "| min dihedral A | min dihedral B | tets A | tets B |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    sums = [0.0, 0.0, 0.0, 0.0]
    for name, h in cases(args.cases):
        path = os.path.join(ROOT, "Data", name)
        runs = {0: [], 1: []}
        for rep in range(args.reps):
            for which in ((0, 1) if rep % 2 == 0 else (1, 0)):
                binary = args.tetmesher if which == 0 else args.compare
                runs[which].append(run_once(binary, path, h, out))
        opt = [min(r[1] for r in runs[k]) for k in (0, 1)]
        meshing = [min(r[0] for r in runs[k]) for k in (0, 1)]
        sums[0] += opt[0]
        sums[1] += opt[1]
        sums[2] += meshing[0]
        sums[3] += meshing[1]
        a, b = runs[0][0], runs[1][0]
        print("| %s | %s | %.4f | %.4f | %.2f | %.4f | %.4f | %s | %s | %s | %s | %s | %s |" % (
            name, "default" if h is None else h, opt[0], opt[1],
            opt[1] / opt[0] if opt[0] > 0 else float("nan"), meshing[0], meshing[1],
            a[2], b[2], a[3], b[3], a[4], b[4]), flush=True)
    print("\nsums: optimisation A %.3f s, B %.3f s (B / A %.3f); meshing A %.3f s, B %.3f s" % (
        sums[0], sums[1], sums[1] / sums[0] if sums[0] > 0 else float("nan"), sums[2], sums[3]))


if __name__ == "__main__":
    main()
