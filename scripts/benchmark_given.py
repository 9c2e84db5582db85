#!/usr/bin/python3
"""Side-by-side benchmark, mode "given": many given interior points (TetGen's -i switch),
TetMesher vs TetGen -pYi.

Companion of scripts/benchmark.py (mode "boundary") and scripts/benchmark_sized.py, whose
surface loading, tool inputs (.off with exact doubles), output readers, timing and exact
checks it reuses; nothing the tools print is trusted. Not part of the test suite. Run with
Debian's /usr/bin/python3, usually via `bash scripts/benchmark.sh --mode given`.

Points: per case, N points (--points, or several counts with --counts) strictly inside the
closed surface, made deterministically: numpy's default_rng(--seed) draws batches of 65536
points uniform in the surface's bounding box; a point is kept when vtkSelectEnclosedPoints
(tolerance 1e-6) says it is inside one of the outermost shells and its distance to the
surface (vtkImplicitPolyDataDistance, all shells) is above --margin times the bounding-box
diagonal, so that none is on or numerically at the surface; the first N kept are given.
The batch size does not depend on N: the points of a smaller count are the first ones of a
larger count. Each outermost shell is tested alone because vtkSelectEnclosedPoints counts
ray crossings, and on the whole of nested_spheres it calls the inner ball (two crossings)
outside; enclosed shells are regions of their own (no --holes), so a point in the inner ball
and one between the shells are both inside the meshed domain. Written as a TetGen .node
file (numbered from 1, coordinates as repr(float): the doubles round-trip exactly), given to
TetMesher with --points and to TetGen as in.a.node next to its in.off.

Tools:
  tetmesher        tetmesher mesh IN -o OUT.vtu -q --boundary-only --points P.node
  tetmesher-full   tetmesher mesh IN -o OUT.vtu -q --points P.node (the full pipeline:
                   refinement and optimisation around the given points, which stay put)
  tetgen-pYi       tetgen -pYi -Q in.off (reads in.a.node; boundary not split)

Checks per output (ours, on the output files): the boundary as in benchmark.py (analyse:
input triangles = output boundary faces, Steiner points on the boundary, volume, Q), and
  * given_found: given points whose nearest output point is within 1e-12 of the bounding-box
    diagonal and is a vertex of a tet (TetGen writes its .node with 17 digits and keeps unused
    points in it);
  * given_exact (TetMesher): output points N_in .. N_in+N-1 are the given points bit for bit,
    in the given order (N_in = input points), as the README promises.

Usage:
  /usr/bin/python3 scripts/benchmark_given.py [--cases a,b] [--points 10000 | --counts 2000,10000]
      [--tools ...] [--seed 1] [--repeat 3] [--timeout 120] [--out Testing/Benchmarks/results]
"""

import argparse
import datetime
import os
import shlex
import shutil
import statistics
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchmark as B  # noqa: E402

ROOT = B.ROOT
CASES = ["knot1", "torus", "fandisk", "nested_spheres"]
TOOLS = ["tetmesher", "tetmesher-full", "tetgen-pYi"]
BATCH = 65536  # candidates per draw; fixed so that the point sequence does not depend on N
MATCH_TOL = 1e-12  # given point found: nearest output point within this x bbox diagonal


# ----------------------------------------------------------------------------- points
def enclosed(surface, q):
    """vtkSelectEnclosedPoints' verdict for each row of q (inside the closed surface)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkFiltersModeling import vtkSelectEnclosedPoints
    vp = vtkPoints()
    vp.SetData(numpy_to_vtk(np.ascontiguousarray(q), deep=True))
    pd = vtkPolyData()
    pd.SetPoints(vp)
    sel = vtkSelectEnclosedPoints()
    sel.SetInputData(pd)
    sel.SetSurfaceData(surface)
    sel.SetTolerance(1e-6)
    sel.Update()
    return vtk_to_numpy(sel.GetOutput().GetPointData().GetArray("SelectedPoints")).astype(bool)


def given_points(case, n, seed, margin):
    """The first n points drawn uniformly in the bounding box that are inside the surface and
    farther than margin x diagonal from it; also returns how many candidates were drawn."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance
    pts, tris, sid = case["pts"], case["tris"], case["sid"]
    lo, hi = pts.min(0), pts.max(0)
    dmin = margin * float(np.linalg.norm(hi - lo))
    # inside = inside an outermost shell (see the docstring: parity on nested shells)
    tops = [B.polydata(pts, tris[sid == s]) for s, p in enumerate(case["parent"]) if p < 0]
    dist = vtkImplicitPolyDataDistance()
    dist.SetInput(B.polydata(pts, tris))
    rng = np.random.default_rng(seed)
    kept, total, drawn = [], 0, 0
    while total < n:
        q = rng.uniform(lo, hi, (BATCH, 3))
        drawn += BATCH
        inside = np.zeros(len(q), dtype=bool)
        for s in tops:
            inside |= enclosed(s, q)
        q = q[inside]
        d = vtkDoubleArray()
        dist.FunctionValue(numpy_to_vtk(np.ascontiguousarray(q), deep=True), d)
        q = q[np.abs(vtk_to_numpy(d)) > dmin]
        kept.append(q)
        total += len(q)
    return np.concatenate(kept)[:n], drawn


def write_node(path, P):
    with open(path, "w") as f:
        f.write("%d 3 0 0\n" % len(P))
        for i, p in enumerate(P, 1):
            f.write("%d %r %r %r\n" % (i, float(p[0]), float(p[1]), float(p[2])))


# ----------------------------------------------------------------------------- checks
def nearest(pts_out, q, tol):
    """(distance, index) of the nearest output point of each row of q; the fallback without
    scipy only looks within tol (cells of size tol, the 27 around each point)."""
    try:
        from scipy.spatial import cKDTree
        return cKDTree(pts_out).query(q)
    except ImportError:
        pass
    cells = {}
    for j, k in enumerate(map(tuple, np.floor(pts_out / tol).astype(np.int64).tolist())):
        cells.setdefault(k, []).append(j)
    dist = np.full(len(q), np.inf)
    idx = np.full(len(q), -1, dtype=np.int64)
    offs = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    for i, k in enumerate(map(tuple, np.floor(q / tol).astype(np.int64).tolist())):
        for o in offs:
            for j in cells.get((k[0] + o[0], k[1] + o[1], k[2] + o[2]), ()):
                d = float(np.linalg.norm(pts_out[j] - q[i]))
                if d < dist[i]:
                    dist[i], idx[i] = d, j
    return dist, idx


def given_check(pts_out, tets, given, nin, diag, tetmesher):
    used = np.zeros(len(pts_out), dtype=bool)
    used[tets.reshape(-1)] = True
    res = {}
    if len(pts_out):
        d, j = nearest(pts_out, given, MATCH_TOL * diag)
        ok = (d <= MATCH_TOL * diag) & (j >= 0)
        ok[ok] &= used[j[ok]]  # listed in the .node but in no tet is not a vertex
        res["given_found"] = int(ok.sum())
    else:
        res["given_found"] = 0
    if tetmesher:
        seg = pts_out[nin:nin + len(given)]
        # bit for bit (view as integers: -0.0 != 0.0), and each a vertex of a tet
        res["given_exact"] = "yes" if (seg.shape == given.shape and np.array_equal(
            seg.view(np.uint64), np.ascontiguousarray(given).view(np.uint64))
            and used[nin:nin + len(given)].all()) else "no"
    return res


# ----------------------------------------------------------------------------- running
def tool_job(tool, run, work, tetmesher):
    case = run["case"]
    d = os.path.join(work, run["label"], tool)
    os.makedirs(d, exist_ok=True)
    src = case["path"]
    if tool.startswith("tetmesher"):
        out = os.path.join(d, "out.vtu")
        cmd = [tetmesher, "mesh", src, "-o", out, "-q"]
        if tool == "tetmesher":
            cmd.append("--boundary-only")
        cmd += ["--points", run["node"]]
        return cmd, d, lambda: B.read_vtu(out), [out]
    if tool == "tetgen-pYi":
        # TetGen writes next to its input and reads in.a.node from there: its own copy of both
        inp = os.path.join(d, "in.off")
        if src.endswith(".off"):
            shutil.copyfile(src, inp)
        else:
            B.write_off(inp, case["pts"], case["tris"])
        shutil.copyfile(run["node"], os.path.join(d, "in.a.node"))
        stem = os.path.join(d, "in.1")
        return ["tetgen", "-pYi", "-Q", "in.off"], d, lambda: B.read_tetgen(stem), \
            [stem + ".node", stem + ".ele"]
    raise ValueError(tool)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--points", type=int, default=10000, help="given points per case")
    ap.add_argument("--counts", default=None, help="several counts per case, e.g. 2000,10000 "
                    "(overrides --points; a smaller count's points begin the larger's)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--margin", type=float, default=1e-4,
                    help="least distance of a point to the surface, x bbox diagonal")
    B.add_run_options(ap, TOOLS, "given")
    args = ap.parse_args()
    args.tetmesher = os.path.abspath(args.tetmesher)
    names = [c.strip() for c in args.cases.split(",") if c.strip()]
    counts = [int(x) for x in args.counts.split(",") if x.strip()] if args.counts else [args.points]
    if not counts or min(counts) < 1:
        sys.exit("counts must be positive")
    args.counts_used = counts
    tools = B.chosen_tools(args, TOOLS)
    work = args.work or tempfile.mkdtemp(prefix="tetmesher-bench-given-")
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(work, "runs.log")
    command = "/usr/bin/python3 scripts/benchmark_given.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    started = datetime.datetime.now(datetime.timezone.utc)
    # versions before the runs: colleagues commit while it runs, and the binary is what counts
    args.versions = B.versions(args.tetmesher)
    runs, gen = [], []
    for case in B.load_cases(names):
        t0 = time.perf_counter()
        allp, drawn = given_points(case, max(counts), args.seed, args.margin)
        gen.append((case["name"], drawn, time.perf_counter() - t0))
        for n in counts:
            label = "%s-n%d" % (case["name"], n)
            os.makedirs(os.path.join(work, label), exist_ok=True)
            node = os.path.join(work, label, "points.node")
            write_node(node, allp[:n])
            runs.append(dict(case=case, n=n, given=allp[:n], label=label, node=node))
    rows = []
    # The repeats go round the tools (B.run_rounds).
    for run, tool, (cmd, cwd, reader, outs), st in B.each_result(
            runs, lambda tool, run: tool_job(tool, run, work, args.tetmesher), tools, args, log):
        case, given = run["case"], run["given"]
        nin = len(case["pts"])
        diag = float(np.linalg.norm(case["pts"].max(0) - case["pts"].min(0)))

        def measure(pts_out, tets):
            res = B.analyse(case, pts_out, tets)
            res.pop("Q", None)
            res.update(given_check(pts_out, tets, given, nin, diag, tool.startswith("tetmesher")))
            # analyse counts the given points among its Steiner points (not input points)
            res["steiner"] -= res["given_found"]
            return res
        row = dict(case=case["name"], given=run["n"], input_points=nin, triangles=len(case["tris"]),
                   tool=tool, command=B.command_text(cmd))
        row.update(B.result_row(st, outs, reader, measure, args.timeout))
        err = row["error"]
        if row["success"] == "yes" and row["given_found"] < run["n"]:
            err = "%d of %d given points not vertices of the output" % (run["n"] - row["given_found"],
                                                                         run["n"])
        if row.get("given_exact") == "no":
            err = (err + "; " if err else "") + "given points not output %d.. in order, exactly" % nin
        row["error"] = err
        rows.append(row)
        print("%-15s %6d %-14s %-4s %8.3fs %8s tets bnd %-3s St %-6s given %6s %-3s Qmin %6s %s" % (
            case["name"], run["n"], tool, row["success"], row["time_s"], row.get("tets", ""),
            row.get("boundary_kept", "-"), row.get("steiner", ""), row.get("given_found", ""),
            row.get("given_exact", ""), B.fmt(row.get("q_min"), ".3f"), err), flush=True)
    finished = datetime.datetime.now(datetime.timezone.utc)
    ref = {(r["case"], r["given"]): r for r in rows if r["tool"] == "tetmesher" and r["success"] == "yes"}
    for r in rows:
        m = ref.get((r["case"], r["given"]))
        if m and r["success"] == "yes" and r["tool"] != "tetmesher" and m["time_s"] > 0:
            r["time_ratio"] = r["time_s"] / m["time_s"]
    write_outputs(args, rows, tools, gen, command, started, finished)
    print("results in %s (scratch: %s)" % (args.out, work))


COLS = ["case", "given", "input_points", "triangles", "tool", "success", "rc", "runs", "time_s",
        "time_ratio", "rss_mb", "tets", "points", "steiner", "steiner_on_boundary", "input_points_lost",
        "boundary_kept", "tri_missing", "tri_wrong_mult", "extra_boundary_faces", "nonmanifold_faces",
        "given_found", "given_exact", "q_min", "q_mean", "q_lt03", "dih_min", "dih_max", "flat_tets",
        "vol_relerr", "command", "error"]


def write_outputs(args, rows, tools, gen, command, started, finished):
    v = args.versions
    fmt = B.fmt
    md = B.begin_outputs(args, COLS, rows, "# TetMesher side-by-side benchmark, mode *given*: many given interior points (TetGen's -i)",
                         "given", started, finished, command)
    md.append("- versions: TetMesher git %s (Release; the tree when the run started), TetGen %s, VTK %s"
              % (v["tetmesher"], v["tetgen"], v["vtk"]))
    md.append("- points: N = %s per case, strictly inside the surface: numpy `default_rng(%d)`, "
              "batches of %d uniform in the surface's bounding box, kept when vtkSelectEnclosedPoints "
              "(tolerance 1e-6) puts them inside an outermost shell (each tested alone: on nested "
              "shells its crossing parity calls the inner ball outside) and their distance to the "
              "surface (vtkImplicitPolyDataDistance) is above %g x the bounding-box diagonal; the "
              "first N kept (a smaller N's points begin a larger N's). Candidates drawn: %s. Written "
              "as a TetGen .node (numbered from 1, repr() doubles: exact), given to TetMesher with "
              "`--points` and to TetGen as `in.a.node`."
              % (", ".join(str(n) for n in args.counts_used), args.seed, BATCH, args.margin,
                 ", ".join("%s %d (%.1f s)" % g for g in gen)))
    md.append("- tools (exact command of every run in %s.csv, column *command*): "
              "`tetmesher mesh IN -o OUT.vtu -q --boundary-only --points P.node` (*tetmesher*: the "
              "boundary mesh with the given points as vertices), the same without `--boundary-only` "
              "(*tetmesher-full*: refinement and optimisation too, the given points kept), "
              "`tetgen -pYi -Q in.off` (*tetgen-pYi*: boundary not split, reads `in.a.node`; .vtp "
              "converted to .off with exact doubles), each tool in its own folder." % args.name)
    md.append("- time: wall time of the whole process (reading the surface and the points, meshing, "
              "writing), median of up to %d runs (1 run if slower than %g s), the repeats going round "
              "the tools (A B C, A B C) so that a burst of load falls on every tool alike; time-out %g s. "
              "*x TM* = the tool's time / TetMesher's (*tetmesher*, same case and N)."
              % (args.repeat, args.slow, args.timeout))
    md.append("- checks (ours, on the output files, as in corpus.md): *bnd* = boundary kept exactly "
              "(every input triangle a face of the output, every output boundary face an input "
              "triangle, no Steiner point on the input surface); *St* = output points that are neither "
              "input points nor given points found; *bSt* = Steiner points on the boundary; *found* = given points whose nearest output "
              "point is within %g x the bounding-box diagonal and a vertex of a tet; *exact* "
              "(TetMesher) = output points N_in .. N_in+N-1 are the given points bit for bit, in order. "
              "Q = 2 sqrt(6) r_in/l_max; *flat* = tets of zero volume in double arithmetic; *dV* = (sum of tet volumes - enclosed volume) / enclosed volume."
              % MATCH_TOL)
    md.append("")
    md.append("## Per case\n")
    def cells(r):
        ok = r["success"] == "yes"
        return (r["case"], r["given"], r["tool"], r["success"], *B.time_cells(r),
                r.get("tets", "") if ok else "", r.get("points", "") if ok else "",
                r.get("steiner", "") if ok else "", r.get("steiner_on_boundary", "") if ok else "",
                r.get("boundary_kept", "") if ok else "",
                "%d/%d" % (r["given_found"], r["given"]) if ok else "", r.get("given_exact", "") if ok else "",
                fmt(r.get("q_min"), ".3f"), fmt(r.get("q_mean"), ".3f"), r.get("flat_tets", "") if ok else "",
                fmt(r.get("vol_relerr"), ".1e"), r["error"].replace("|", "/"))
    md.extend(B.md_table(["case", "N", "tool", "ok", "time s", "x TM", "RSS MB", "tets", "points", "St",
                          "bSt", "bnd", "found", "exact", "Q min", "Q mean", "flat", "dV", "note"],
                         rows, cells))
    md.append("")
    md.append("## Summary per tool\n")
    md.append("| tool | success | boundary kept | given points all present (TetMesher: and exact) | total time s | "
              "median time ratio vs TetMesher | median Q min |")
    md.append("|---|---|---|---|---|---|---|")
    for t in tools:
        rs, ok, kept, ratios = B.tool_summary(rows, t)
        allg = [r for r in ok if r.get("given_found") == r["given"] and r.get("given_exact") != "no"]
        md.append("| %s | %d/%d | %d/%d | %d/%d | %.2f | %s | %s |" % (
            t, len(ok), len(rs), len(kept), len(rs), len(allg), len(rs), sum(r["time_s"] for r in rs),
            fmt(statistics.median(ratios), ".2f") if ratios else "",
            fmt(statistics.median([r["q_min"] for r in ok]), ".3f") if ok else ""))
    md.append("")
    with open(os.path.join(args.out, args.name + ".md"), "w") as f:
        f.write("\n".join(md) + "\n")


if __name__ == "__main__":
    main()
