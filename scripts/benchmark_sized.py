#!/usr/bin/python3
"""Side-by-side benchmark, mode "sized": the full pipeline (boundary mesh, interior points for
a constant target edge length h, quality optimisation) of TetMesher vs TetGen vs Gmsh.

Companion of scripts/benchmark.py (mode "boundary"), whose surface loading, tool inputs
(.off / discrete MSH 2.2 with exact doubles), output readers, timing and exact checks it
reuses; nothing the tools print is trusted. Not part of the test suite. Run with Debian's
/usr/bin/python3, usually via `bash scripts/benchmark.sh --mode sized`.

Per case a constant h: the mean length of the input's boundary edges (and h/2 on a few
cases, --fine). Per case x h x tool: exit code, wall time (median of --repeat runs for fast
runs), peak RSS, tets, tets/s, boundary kept exactly (benchmark.analyse: input triangles =
output boundary faces, no Steiner point on the boundary), Q min/mean/share < 0.3, min/max
dihedral, share of the mesh's edges with length in [0.7, 1.42]*h (all edges, and interior
edges = edges not on an input triangle), and ratios vs TetMesher's default run.

Tools:
  tetmesher        tetmesher mesh IN -o OUT.vtu -q --size H
  tetmesher-dt0    ... --dihedral-target 0 (the Q stage alone, no dihedral stage)
  tetgen-q         tetgen -pq1.2a<V>   (V = h^3/(6*sqrt(2)), the volume of the regular tet of
                   edge h; TetGen may split boundary edges/faces: Steiner points on the boundary)
  tetgen-qO9       tetgen -pq1.2a<V>O9/7 (optimisation level 9 of 0-9, all operations 7 =
                   flips 1 + smoothing 2 + insertion/deletion 4; TetGen's default is -O2/7;
                   it only works on tets with a dihedral angle > 165 deg, TetGen's default o/165)
  tetgen-qO9o150   tetgen -pq1.2a<V>O9/7o/150 (the same, aiming at max dihedral 150 deg)
  tetgen-Yq        tetgen -pYq1.2a<V>  (boundary not split, comparable with TetMesher)
  gmsh-delaunay    gmsh in.geo -3 -nt 1, Mesh.Algorithm3D=1, -clmin H -clmax H
  gmsh-hxt         same with Mesh.Algorithm3D=10

Usage:
  /usr/bin/python3 scripts/benchmark_sized.py [--cases a,b] [--fine a,b] [--tools ...]
      [--repeat 3] [--timeout 120] [--out Testing/Benchmarks/results]
"""

import argparse
import datetime
import math
import os
import shlex
import statistics
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchmark as B  # noqa: E402

ROOT = B.ROOT
CASES = ["cube", "icosphere", "torus", "nested_spheres", "gear", "sphere", "fandisk", "knot1"]
FINE = ["cube", "torus"]
TOOLS = ["tetmesher", "tetmesher-dt0", "tetgen-q", "tetgen-qO9", "tetgen-qO9o150", "tetgen-Yq",
         "gmsh-delaunay", "gmsh-hxt"]


def mean_edge(pts, tris):
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [0, 2]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    return float(np.linalg.norm(pts[e[:, 0]] - pts[e[:, 1]], axis=1).mean())


def edge_stats(pts_out, tets, case, h):
    """Shares of edges with length in [0.7, 1.42]*h: all edges and interior ones (an edge is
    a boundary edge when both ends are input points and it is an edge of an input triangle)."""
    e = np.concatenate([tets[:, [i, j]] for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))])
    e = np.unique(np.sort(e, axis=1), axis=0)
    L = np.linalg.norm(pts_out[e[:, 0]] - pts_out[e[:, 1]], axis=1) / h
    ok = (L >= 0.7) & (L <= 1.42)
    # boundary edges: map output points to input ids by exact coordinates
    lookup = {(float(x), float(y), float(z)): i for i, (x, y, z) in enumerate(case["pts"])}
    ids = np.array([lookup.get((float(p[0]), float(p[1]), float(p[2])), -1) for p in pts_out])
    t = case["tris"]
    be = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [0, 2]]])
    be = np.sort(be, axis=1)
    n = len(case["pts"]) + 1
    bkeys = set((be[:, 0] * n + be[:, 1]).tolist())
    a, b = ids[e[:, 0]], ids[e[:, 1]]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    isb = np.array([(l >= 0 and (l * n + m) in bkeys) for l, m in zip(lo.tolist(), hi.tolist())],
                   dtype=bool)
    inner = ~isb
    return dict(edges=int(len(e)), edge_in_range=float(ok.mean()),
                inner_edge_in_range=float(ok[inner].mean()) if inner.any() else None,
                edge_len_median=float(np.median(L)))


def tool_job(tool, case, h, work, tetmesher):
    name = "%s-h%s" % (case["name"], case["hlabel"])
    d = os.path.join(work, name, tool)
    os.makedirs(d, exist_ok=True)
    src = case["path"]
    hs = repr(float(h))
    if tool.startswith("tetmesher"):
        out = os.path.join(d, "out.vtu")
        cmd = [tetmesher, "mesh", src, "-o", out, "-q", "--size", hs]
        if tool == "tetmesher-dt0":
            cmd += ["--dihedral-target", "0"]
        return cmd, d, lambda: B.read_vtu(out), [out]
    if tool.startswith("tetgen"):
        inp = os.path.join(d, "in.off")
        if src.endswith(".off"):
            with open(src) as fi, open(inp, "w") as fo:
                fo.write(fi.read())
        else:
            B.write_off(inp, case["pts"], case["tris"])
        V = h ** 3 / (6.0 * math.sqrt(2.0))
        sw = {"tetgen-q": "-pq1.2a%.6g", "tetgen-qO9": "-pq1.2a%.6gO9/7",
              "tetgen-qO9o150": "-pq1.2a%.6gO9/7o/150",
              "tetgen-Yq": "-pYq1.2a%.6g"}[tool] % V
        stem = os.path.join(d, "in.1")
        return ["tetgen", sw, "-Q", "in.off"], d, lambda: B.read_tetgen(stem), \
            [stem + ".node", stem + ".ele"]
    if tool.startswith("gmsh"):
        algo = 1 if tool == "gmsh-delaunay" else 10
        B.write_gmsh_input(os.path.join(d, "in.msh"), os.path.join(d, "in.geo"), case["pts"],
                           case["tris"], case["sid"], case["parent"], algo)
        out = os.path.join(d, "out.msh")
        return (["gmsh", "in.geo", "-3", "-nt", "1", "-setnumber", "Mesh.Algorithm3D", str(algo),
                 "-clmin", hs, "-clmax", hs, "-format", "msh2", "-bin", "-save_all", "-o", "out.msh"],
                d, lambda: B.read_msh2_binary(out), [out])
    raise ValueError(tool)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--fine", default=",".join(FINE), help="cases also run with h/2")
    B.add_run_options(ap, TOOLS, "sized")
    args = ap.parse_args()
    args.tetmesher = os.path.abspath(args.tetmesher)
    names = [c.strip() for c in args.cases.split(",") if c.strip()]
    fine = [c.strip() for c in args.fine.split(",") if c.strip()]
    tools = B.chosen_tools(args, TOOLS)
    base = B.load_cases(names)
    runs = []
    for c in base:
        h = mean_edge(c["pts"], c["tris"])
        runs.append(dict(c, h=h, hlabel="1"))
        if c["name"] in fine:
            runs.append(dict(c, h=h / 2.0, hlabel="0.5"))
    work = args.work or tempfile.mkdtemp(prefix="tetmesher-bench-sized-")
    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(work, "runs.log")
    command = "/usr/bin/python3 scripts/benchmark_sized.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    started = datetime.datetime.now(datetime.timezone.utc)
    # versions before the runs: colleagues commit while it runs, and the binary is what counts
    args.versions = B.versions(args.tetmesher)
    # Each tool's process floor: its run on one tetrahedron at h = 1 (B.process_floors).
    args.floors = B.process_floors(
        tools, lambda tool, case: tool_job(tool, dict(case, hlabel="1"), 1.0, work, args.tetmesher),
        args.repeat, args.timeout, log, work)
    rows = []
    # The repeats go round the tools (B.run_rounds).
    for case, tool, (cmd, cwd, reader, outs), st in B.each_result(
            runs, lambda tool, case: tool_job(tool, case, case["h"], work, args.tetmesher), tools, args, log):
        h = case["h"]

        def measure(pts_out, tets):
            res = B.analyse(case, pts_out, tets)
            res.pop("Q", None)
            if len(tets):
                res.update(edge_stats(pts_out, tets, case, h))
            return res
        row = dict(case=case["name"], h_factor=case["hlabel"], h=h, triangles=len(case["tris"]),
                   tool=tool, command=B.command_text(cmd))
        row.update(B.result_row(st, outs, reader, measure, args.timeout))
        if row["success"] == "yes":
            row["tets_per_s"] = row["tets"] / row["time_s"]
            # Tets per second of the time above the tool's floor (at least 1 ms of it).
            above = B.above_floor(row, args.floors)
            if above is not None:
                row["tets_per_s_above_floor"] = row["tets"] / max(above, 1e-3)
        rows.append(row)
        print("%-15s h%-4s %-14s %-4s %8.3fs %8s tets bnd %-3s bSt %-5s Qmin %6s dih %6s edges %6s %s" % (
            case["name"], case["hlabel"], tool, row["success"], row["time_s"], row.get("tets", ""),
            row.get("boundary_kept", "-"), row.get("steiner_on_boundary", ""),
            B.fmt(row.get("q_min"), ".3f"), B.fmt(row.get("dih_min"), ".1f"),
            B.fmt(row.get("edge_in_range"), ".1%"), row["error"]), flush=True)
    finished = datetime.datetime.now(datetime.timezone.utc)
    ref = {(r["case"], r["h_factor"]): r for r in rows if r["tool"] == "tetmesher" and r["success"] == "yes"}
    for r in rows:
        m = ref.get((r["case"], r["h_factor"]))
        if m and r["success"] == "yes" and r["tool"] != "tetmesher":
            r["time_ratio"] = r["time_s"] / m["time_s"]
            r["tets_ratio"] = r["tets"] / m["tets"]
            r["rate_ratio"] = r["tets_per_s"] / m["tets_per_s"]
            if r.get("tets_per_s_above_floor") and m.get("tets_per_s_above_floor"):
                r["rate_ratio_above_floor"] = r["tets_per_s_above_floor"] / m["tets_per_s_above_floor"]
    write_outputs(args, rows, tools, command, started, finished)
    print("results in %s (scratch: %s)" % (args.out, work))


COLS = ["case", "h_factor", "h", "triangles", "tool", "success", "rc", "runs", "time_s", "time_ratio",
        "rss_mb", "tets", "tets_ratio", "tets_per_s", "rate_ratio", "tets_per_s_above_floor",
        "rate_ratio_above_floor", "points", "steiner",
        "steiner_on_boundary", "input_points_lost", "boundary_kept", "tri_missing", "tri_wrong_mult",
        "extra_boundary_faces", "nonmanifold_faces", "q_min", "q_mean", "q_lt03", "dih_min", "dih_max",
        "flat_tets", "vol_relerr", "edges", "edge_in_range", "inner_edge_in_range", "edge_len_median",
        "command", "error"]


def write_outputs(args, rows, tools, command, started, finished):
    v = args.versions
    fmt = B.fmt
    md = B.begin_outputs(args, COLS, rows, "# TetMesher side-by-side benchmark, mode *sized*: the full pipeline at a constant h",
                         "sized", started, finished, command)
    md.append("- versions: TetMesher git %s (Release; the tree when the run started), TetGen %s, Gmsh %s, VTK %s"
              % (v["tetmesher"], v["tetgen"], v["gmsh"], v["vtk"]))
    md.append("- h: constant per case, the mean length of the input's (unique) boundary edges "
              "(*h x1*), and half of it (*h x0.5*) on %s." % ", ".join(
                  sorted({r["case"] for r in rows if r["h_factor"] == "0.5"})))
    md.append("- tools (exact command of every run in sized.csv, column *command*): "
              "`tetmesher mesh IN -o OUT.vtu -q --size H` (*tetmesher*) and with "
              "`--dihedral-target 0` (*tetmesher-dt0*: no dihedral stage); `tetgen -pq1.2a<V>` (*tetgen-q*), "
              "`tetgen -pq1.2a<V>O9/7` (*tetgen-qO9*: optimisation level 9 = TetGen 1.5's maximum, "
              "all operations; the default is O2/7; TetGen only optimises tets with a dihedral angle above "
              "its `o/` bound, default 165 deg), `tetgen -pq1.2a<V>O9/7o/150` (*tetgen-qO9o150*: "
              "bound 150 deg) and `tetgen -pYq1.2a<V>` (*tetgen-Yq*: boundary "
              "not split) with V = h^3/(6 sqrt 2), the volume of the regular tet of edge h, on the "
              ".off (.vtp converted with exact doubles); `gmsh in.geo -3 -nt 1 -clmin H -clmax H` "
              "with Mesh.Algorithm3D = 1 (*gmsh-delaunay*) or 10 (*gmsh-hxt*) on the surface merged "
              "as a discrete MSH 2.2 mesh (Gmsh keeps the discrete surface; Mesh.Optimize=1 default).")
    md.append("- time: wall time of the whole process (read, mesh, write), median of up to %d runs "
              "(1 run if slower than %g s), the repeats going round the tools (A B C, A B C) so that "
              "a burst of load falls on every tool alike; time-out %g s. *tets/s* = tets / wall time; *rate x TM* "
              "= the tool's tets/s / TetMesher's (default run, same case and h)."
              % (args.repeat, args.slow, args.timeout))
    md.append(B.floors_line(args.floors) + "; in the tables, *above floor* is the rate ratio of each "
              "tool's tets per second of its time above its floor (at least 1 ms)")
    md.append("- checks (ours, on the output files, as in corpus.md): *bnd* = boundary kept exactly "
              "(every input triangle a face of the output, every output boundary face an input "
              "triangle, no Steiner point on the input surface); *bSt* = Steiner points on the "
              "boundary. Q = 2 sqrt(6) r_in/l_max; *Q<0.3* share of tets; dihedral angles in degrees; "
              "*e∈h* = share of all mesh edges with length in [0.7, 1.42]·h, *ie∈h* = the same for "
              "the edges not on an input triangle.")
    md.append("")
    md.append("## Per case\n")
    def cells(r):
        ok = r["success"] == "yes"
        return (r["case"], "x%s = %.4g" % (r["h_factor"], r["h"]), r["tool"], r["success"],
                B.time_cells(r)[0],
                r.get("tets", "") if ok else "", fmt(r.get("tets_per_s"), ".3g") if ok else "",
                fmt(r.get("rate_ratio"), ".2f"), fmt(r.get("rate_ratio_above_floor"), ".2f"),
                fmt(r.get("tets_ratio"), ".2f"),
                r.get("boundary_kept", "") if ok else "", r.get("steiner_on_boundary", "") if ok else "",
                fmt(r.get("q_min"), ".3f"), fmt(r.get("q_mean"), ".3f"), fmt(r.get("q_lt03"), ".1%"),
                fmt(r.get("dih_min"), ".1f"), fmt(r.get("dih_max"), ".1f"),
                fmt(r.get("edge_in_range"), ".1%"), fmt(r.get("inner_edge_in_range"), ".1%"),
                r["error"].replace("|", "/"))
    md.extend(B.md_table(["case", "h", "tool", "ok", "time s", "tets", "tets/s", "rate x TM", "above floor", "tets x TM",
                          "bnd", "bSt", "Q min", "Q mean", "Q<0.3", "dih min", "dih max", "e∈h", "ie∈h",
                          "note"], rows, cells))
    md.append("")
    md.append("## Summary per tool (medians over the runs that succeeded)\n")
    md.append("| tool | success | boundary kept | total time s | median rate x TM | above floor | median Q min | "
              "median Q mean | median Q<0.3 | median dih min | median dih max | median e∈h |")
    md.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for t in tools:
        rs = [r for r in rows if r["tool"] == t]
        ok = [r for r in rs if r["success"] == "yes"]
        kept = [r for r in ok if r.get("boundary_kept") == "yes"]

        def med(k, spec):
            xs = [r[k] for r in ok if r.get(k) is not None]
            return fmt(statistics.median(xs), spec) if xs else ""
        md.append("| %s | %d/%d | %d/%d | %.1f | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            t, len(ok), len(rs), len(kept), len(rs), sum(r["time_s"] for r in rs),
            med("rate_ratio", ".2f"), med("rate_ratio_above_floor", ".2f"), med("q_min", ".3f"), med("q_mean", ".3f"), med("q_lt03", ".2%"),
            med("dih_min", ".1f"), med("dih_max", ".1f"), med("edge_in_range", ".1%")))
    md.append("")
    with open(os.path.join(args.out, args.name + ".md"), "w") as f:
        f.write("\n".join(md) + "\n")


if __name__ == "__main__":
    main()
