#!/usr/bin/python3
"""Side-by-side benchmark: TetMesher vs TetGen vs Gmsh vs vtkDelaunay3D on the Data/ corpus.

Not part of the test suite. Run with Debian's /usr/bin/python3 (vtkmodules, numpy,
matplotlib). Usually started by scripts/benchmark.sh, which installs the tools and builds
the CLI first.

For every case x tool: exit code, output present, wall time (median of --repeat runs for
fast runs, one run for slow ones), peak RSS (/usr/bin/time -f %M), tetrahedra, tets/s, and
our own checks of the output (nothing the tools print is trusted):
  * boundary kept exactly: output points are mapped to input points by exact coordinate
    equality; every input triangle (sorted vertex-id triple) must be a face of exactly the
    expected number of output tets (1, or 2 for a shell enclosed by another shell: an
    interface), and every output boundary face (a face of one tet) must be an input
    triangle; Steiner points on the boundary (output points that are not input points but
    lie on the input surface) are counted;
  * quality Q = 2*sqrt(6)*r_in/l_max (1 for the regular tet), r_in = 3V/sum(face areas):
    min, mean, share < 0.3; min/max dihedral angle;
  * sum of tet volumes vs the enclosed volume (Data/corpus.csv, else divergence theorem).

Usage:
  /usr/bin/python3 scripts/benchmark.py [--quick] [--cases a,b,c] [--tools t1,t2]
      [--repeat 3] [--timeout 300] [--out Testing/Benchmarks/results]
"""

import argparse
import collections
import csv
import itertools
import datetime
import math
import os
import platform
import shlex
import signal
import statistics
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "Data")
QUICK = ["cubes", "star", "sphere", "icosphere", "torus", "nested_spheres", "gear"]
TOOLS = ["tetmesher", "tetmesher-norefine", "tetgen-pY", "tetgen-pYq1.2", "gmsh-delaunay", "gmsh-hxt", "vtkDelaunay3D"]
VTK_TETRA = 10


# ----------------------------------------------------------------------------- surfaces
def load_surface(path):
    """Points (n,3) float64 exactly as in the file, faces: a list of vertex-id lists
    (triangles, or polygons for some .off files)."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".off":
        # Line by line: COFF/NOFF vertex lines carry colours or normals after x y z, and face
        # lines may carry colours after their vertex ids.
        with open(path) as f:
            lines = [l.split("#")[0].split() for l in f]
        lines = [l for l in lines if l]
        assert lines[0][0].endswith("OFF"), path
        head = lines[0][1:] if len(lines[0]) > 1 else lines[1]
        first = 1 if len(lines[0]) > 1 else 2
        nv, nf = int(head[0]), int(head[1])
        pts = np.array([[float(w) for w in l[:3]] for l in lines[first:first + nv]],
                       dtype=np.float64).reshape(nv, 3)
        faces = [[int(x) for x in l[1:1 + int(l[0])]]
                 for l in lines[first + nv:first + nv + nf]]
        return pts, faces
    if ext == ".stl":
        from vtkmodules.vtkIOGeometry import vtkSTLReader
        r = vtkSTLReader()
        r.MergingOn()  # exact duplicates only (vtkMergePoints)
    elif ext == ".vtp":
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        r = vtkXMLPolyDataReader()
    elif ext == ".ply":
        from vtkmodules.vtkIOPLY import vtkPLYReader
        r = vtkPLYReader()
    else:
        raise ValueError(path)
    r.SetFileName(path)
    r.Update()
    pd = r.GetOutput()
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pts = vtk_to_numpy(pd.GetPoints().GetData()).astype(np.float64)
    polys = vtk_to_numpy(pd.GetPolys().GetConnectivityArray()).astype(np.int64)
    offs = vtk_to_numpy(pd.GetPolys().GetOffsetsArray()).astype(np.int64)
    return pts, [polys[offs[i]:offs[i + 1]].tolist() for i in range(len(offs) - 1)]


def triangulate(pts, faces):
    """Triangles (m,3): the faces themselves, polygons split as fans from their first vertex
    (as the triangle counts of Data/corpus.csv; .off polygons may be non-planar)."""
    return np.array([[f[0], f[i], f[i + 1]] for f in faces for i in range(1, len(f) - 1)],
                    dtype=np.int64).reshape(-1, 3)


def shells(tris, npts):
    """Shell id per triangle (connected by shared vertices)."""
    parent = np.arange(npts)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a
    for a, b, c in tris:
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    roots = np.array([find(t[0]) for t in tris])
    _, sid = np.unique(roots, return_inverse=True)
    return sid


def signed_volume(pts, tris):
    a, b, c = pts[tris[:, 0]], pts[tris[:, 1]], pts[tris[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def polydata(pts, tris):
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    vp = vtkPoints()
    vp.SetData(numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    ca = vtkCellArray()
    offs = np.arange(0, 3 * len(tris) + 1, 3, dtype=np.int64)
    ca.SetData(numpy_to_vtkIdTypeArray(offs, deep=True),
               numpy_to_vtkIdTypeArray(np.ascontiguousarray(tris.reshape(-1)), deep=True))
    pd = vtkPolyData()
    pd.SetPoints(vp)
    pd.SetPolys(ca)
    return pd


def nesting(pts, tris, sid):
    """parent[s] = the innermost shell that encloses shell s, or -1."""
    ns = int(sid.max()) + 1
    if ns == 1:
        return [-1]
    from vtkmodules.vtkFiltersModeling import vtkSelectEnclosedPoints
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    inside = np.zeros((ns, ns), dtype=bool)  # inside[a, b]: shell a inside shell b
    probe = [pts[tris[sid == s][0][0]] for s in range(ns)]
    for b in range(ns):
        surf = polydata(pts, tris[sid == b])
        sel = vtkSelectEnclosedPoints()
        sel.SetSurfaceData(surf)
        sel.SetTolerance(1e-9)
        sel.Initialize(surf)
        for a in range(ns):
            if a != b:
                inside[a, b] = bool(sel.IsInsideSurface(*probe[a]))
        sel.Complete()
    parent = []
    for a in range(ns):
        enc = [b for b in range(ns) if inside[a, b]]
        # innermost encloser = the one enclosed by the most others
        parent.append(max(enc, key=lambda b: inside[b].sum()) if enc else -1)
    return parent


def write_off(path, pts, tris):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(pts), len(tris)))
        for p in pts:
            f.write("%r %r %r\n" % (float(p[0]), float(p[1]), float(p[2])))
        for t in tris:
            f.write("3 %d %d %d\n" % tuple(t))


def write_gmsh_input(msh, geo, pts, tris, sid, parent, algo):
    """Discrete surface in MSH 2.2 ASCII (repr() = exact doubles), one elementary surface
    per shell, and a .geo with one volume per shell (its directly enclosed shells as holes,
    each of which gets its own volume), so that interfaces are meshed on both sides."""
    with open(msh, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(pts))
        for i, p in enumerate(pts):
            f.write("%d %r %r %r\n" % (i + 1, float(p[0]), float(p[1]), float(p[2])))
        f.write("$EndNodes\n$Elements\n%d\n" % len(tris))
        for i, t in enumerate(tris):
            s = int(sid[i]) + 1
            f.write("%d 2 2 0 %d %d %d %d\n" % (i + 1, s, t[0] + 1, t[1] + 1, t[2] + 1))
        f.write("$EndElements\n")
    ns = len(parent)
    with open(geo, "w") as f:
        f.write('Merge "%s";\n' % os.path.basename(msh))
        f.write("General.NumThreads = 1;\nMesh.Algorithm3D = %d;\n" % algo)
        for s in range(ns):
            f.write("Surface Loop(%d) = {%d};\n" % (s + 1, s + 1))
        for s in range(ns):
            holes = [c + 1 for c in range(ns) if parent[c] == s]
            f.write("Volume(%d) = {%s};\n" % (s + 1, ", ".join(str(x) for x in [s + 1] + holes)))


# ----------------------------------------------------------------------------- outputs
def read_vtu(path):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    if g.GetNumberOfPoints() == 0:
        return np.zeros((0, 3)), np.zeros((0, 4), dtype=np.int64)
    pts = vtk_to_numpy(g.GetPoints().GetData()).astype(np.float64)
    types = vtk_to_numpy(g.GetCellTypesArray())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).astype(np.int64)
    offs = vtk_to_numpy(g.GetCells().GetOffsetsArray()).astype(np.int64)
    sel = np.nonzero(types == VTK_TETRA)[0]
    tets = np.stack([conn[offs[sel] + k] for k in range(4)], axis=1) if len(sel) else \
        np.zeros((0, 4), dtype=np.int64)
    return pts, tets


def read_tetgen(stem):
    def table(path):
        rows = []
        with open(path) as f:
            for line in f:
                line = line.split("#")[0].split()
                if line:
                    rows.append(line)
        return rows
    node = table(stem + ".node")
    n = int(node[0][0])
    ids = np.array([int(r[0]) for r in node[1:n + 1]])
    pts = np.array([[float(x) for x in r[1:4]] for r in node[1:n + 1]], dtype=np.float64)
    first = int(ids[0]) if n else 0
    ele = table(stem + ".ele")
    m = int(ele[0][0])
    tets = np.array([[int(x) for x in r[1:5]] for r in ele[1:m + 1]], dtype=np.int64).reshape(-1, 4)
    return pts, tets - first


def read_msh2_binary(path):
    """Gmsh MSH 2.2 binary (doubles kept exactly)."""
    with open(path, "rb") as f:
        data = f.read()
    pos = 0
    pts_by_tag = {}
    tets = []

    def readline():
        nonlocal pos
        e = data.index(b"\n", pos)
        line = data[pos:e]
        pos = e + 1
        return line.strip()
    while pos < len(data):
        line = readline()
        if line == b"$MeshFormat":
            ver, ftype, dsize = readline().split()
            if ftype != b"1":
                raise ValueError("expected binary msh")
            pos += 4  # the int 1 (endianness)
            readline()
        elif line == b"$Nodes":
            n = int(readline())
            rec = np.frombuffer(data, dtype=np.dtype([("t", "<i4"), ("x", "<f8", 3)]), count=n, offset=pos)
            pos += rec.nbytes
            tags = rec["t"].astype(np.int64)
            xyz = rec["x"].astype(np.float64)
            readline()
        elif line == b"$Elements":
            m = int(readline())
            done = 0
            nn = {1: 2, 2: 3, 4: 4, 15: 1, 3: 4, 5: 8, 6: 6, 7: 5}
            while done < m:
                etype, cnt, ntags = struct.unpack_from("<3i", data, pos)
                pos += 12
                width = 1 + ntags + nn[etype]
                arr = np.frombuffer(data, dtype="<i4", count=cnt * width, offset=pos).reshape(cnt, width)
                pos += arr.nbytes
                if etype == 4:
                    tets.append(arr[:, 1 + ntags:].astype(np.int64))
                done += cnt
            readline()
        elif line.startswith(b"$End") or line == b"":
            continue
        elif line.startswith(b"$"):
            end = b"$End" + line[1:]
            pos = data.index(end, pos)
    index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
    index[tags] = np.arange(len(tags))
    tets = np.concatenate(tets) if tets else np.zeros((0, 4), dtype=np.int64)
    return xyz, index[tets]


# ----------------------------------------------------------------------------- analysis
def face_keys(tri, base):
    s = np.sort(tri, axis=1)
    return (s[:, 0] * base + s[:, 1]) * base + s[:, 2]


def run_rounds(jobs, tools, repeat, timeout, slow, log):
    """Runs each tool's job (cmd, cwd, reader, outs) up to `repeat` times, the repeats going round
    the tools (A B C, A B C, ...) so that a burst of load from the machine's other users falls on
    one round of every tool rather than on one tool. A tool stops repeating once it fails or
    takes longer than `slow` seconds. Returns per tool: walls, rsss (KB), and the last rc, msg."""
    state = {tool: dict(walls=[], rsss=[], rc=None, msg="", done=False) for tool in tools}
    for _ in range(max(1, repeat)):
        for tool in tools:
            st = state[tool]
            if st["done"]:
                continue
            cmd, cwd, reader, outs = jobs[tool]
            for o in outs:
                if os.path.exists(o):
                    os.remove(o)
            rc, wall, rss, msg = run_timed(cmd, timeout, cwd, log)
            st["walls"].append(wall)
            if rss is not None:
                st["rsss"].append(rss)
            st["rc"], st["msg"] = rc, msg
            if rc != 0 or wall > slow:
                st["done"] = True
    return state


# The smallest closed surface, one tetrahedron (outward triangles): each tool's time on it is its
# process floor (exec, loading, start-up, reading and writing a file), which no meshing speed
# lowers. Small cases run within a few ms of it, so their wall-time ratios say little about
# the meshers; times above the floor do.
FLOOR_POINTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
FLOOR_TRIANGLES = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]


def floor_case(work):
    """The one-tetrahedron case, written to work/floor-tet.off."""
    path = os.path.join(work, "floor-tet.off")
    pts = np.array(FLOOR_POINTS, dtype=float)
    tris = np.array(FLOOR_TRIANGLES, dtype=np.int64)
    write_off(path, pts, tris)
    return dict(name="floor-tet", path=path, pts=pts, tris=tris, faces=[list(t) for t in tris],
                sid=np.zeros(len(tris), dtype=np.int64), parent=[-1])


def process_floors(tools, make_job, repeat, timeout, log, work):
    """Median wall time of each tool's job on the one-tetrahedron case (make_job(tool, case)), and
    of /bin/true (the machine's exec floor, key "exec"), over max(7, 2 * repeat) runs going
    round the tools. A tool that fails there gets no floor."""
    case = floor_case(work)
    jobs = {tool: make_job(tool, case) for tool in tools}
    jobs["exec"] = (["/bin/true"], work, None, [])
    names = list(tools) + ["exec"]
    state = run_rounds(jobs, names, max(7, 2 * repeat), timeout, 1e9, log)
    return {t: statistics.median(state[t]["walls"]) for t in names if state[t]["rc"] == 0}


def above_floor(r, floors):
    """Row r's time above its tool's floor (None without one), also stored as
    time_above_floor_s."""
    if r["success"] != "yes" or r["tool"] not in floors:
        return None
    r["time_above_floor_s"] = r["time_s"] - floors[r["tool"]]
    return r["time_above_floor_s"]


def floors_line(floors):
    """The .md line that gives the floors."""
    return ("- process floor (median wall time on a single tetrahedron, the whole process: exec, "
            "start-up, reading, writing; `/bin/true` for the machine's exec alone): %s. *above "
            "floor*: a run's time minus its tool's floor, and the ratio of two such times (ours "
            "clamped to at least 1 ms)" % ", ".join(
                "%s %.1f ms" % ("`/bin/true`" if t == "exec" else t, 1e3 * v) for t, v in floors.items()))


def each_result(items, make_job, tools, args, log):
    """For each item (a case, a case at a size, ...) the tools' jobs make_job(tool, item) -> (cmd,
    cwd, reader, outs), run by run_rounds; yields (item, tool, job, its run_rounds state)."""
    for item in items:
        jobs = {tool: make_job(tool, item) for tool in tools}
        state = run_rounds(jobs, tools, args.repeat, args.timeout, args.slow, log)
        for tool in tools:
            yield item, tool, jobs[tool], state[tool]


def add_run_options(ap, tools, name):
    """The options that benchmark_sized.py and benchmark_given.py share: tools (default `tools`),
    repeats, time-outs, the CLI, where the results and scratch go, their stem `name`."""
    ap.add_argument("--tools", default=",".join(tools))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--slow", type=float, default=2.0)
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--tetmesher", default=os.path.join(ROOT, "build-bench", "bin", "tetmesher"))
    ap.add_argument("--out", default=os.path.join(ROOT, "Testing", "Benchmarks", "results"))
    ap.add_argument("--work", default=None, help="scratch folder (default: a temporary one)")
    ap.add_argument("--name", default=name, help="output stem (%s.md, %s.csv)" % (name, name))


def chosen_tools(args, known):
    """--tools as a list, each one of `known` (else exit naming it)."""
    tools = [t.strip() for t in args.tools.split(",") if t.strip()]
    for t in tools:
        if t not in known:
            sys.exit("unknown tool %s" % t)
    return tools


def md_table(columns, rows, cells):
    """A markdown table: the header of `columns`, then cells(r) (one string per column) per row."""
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        lines.append("| " + " | ".join(str(c) for c in cells(r)) + " |")
    return lines


def time_cells(r):
    """The per-case tables' time, time ratio and RSS cells of row r."""
    return ("timeout" if r["rc"] == "timeout" else fmt(r["time_s"], ".3f"),
            fmt(r.get("time_ratio"), ".2f"), fmt(r.get("rss_mb"), ".0f"))


def failure_message(rc, msg, timeout):
    """What a run that left no output said: its error line, else the defects TetMesher lists after
    its "cannot be meshed:" line, else its last line."""
    if rc == "timeout":
        return "time-out after %g s" % timeout
    lines = [l for l in msg.strip().split("\n") if l.strip()]
    errl = [l for l in lines if l.startswith("Error")] or \
        [l for l in lines if "rror" in l or "ERROR" in l or "failed" in l.lower()]
    # The defects TetMesher lists after its "cannot be meshed:" line, one per line, without the
    # closing note in brackets (it was all the table showed).
    head = next((i for i, l in enumerate(lines)
                 if l.startswith("tetmesher:") and l.rstrip().endswith(":")), None)
    listed = [l.strip() for l in lines[head + 1:] if not l.strip().startswith("(")] \
        if head is not None else []
    err = (errl[0] if errl else "; ".join(listed) if listed
           else (lines[-1] if lines else "no output")).strip()[:200]
    return "rc %s: %s" % (rc, err)


def command_text(cmd):
    """A command as the tables show it: paths inside the repository relative to it."""
    return " ".join(shlex.quote(os.path.relpath(x, ROOT) if os.path.isabs(x) and x.startswith(ROOT)
                                else x) for x in cmd)


def result_row(st, outs, reader, measure, timeout):
    """The fields every benchmark records for one tool's runs (run_rounds' state `st`): runs,
    median wall time, peak RSS, exit code; then, when the run left its outputs, measure(pts_out,
    tets) -> dict of checks merged in, else the error. success: an output with tets."""
    walls, rsss = st["walls"], st["rsss"]
    row = dict(rc=st["rc"], runs=len(walls), time_s=statistics.median(walls),
               rss_mb=(max(rsss) / 1024.0 if rsss else None))
    present = st["rc"] == 0 and all(os.path.exists(o) for o in outs)
    err = ""
    if present:
        try:
            pts_out, tets = reader()
            row.update(measure(pts_out, tets))
        except Exception as e:  # a broken output is data, too
            err = "reading/analysing the output failed: %r" % (e,)
            present = False
    else:
        err = failure_message(st["rc"], st["msg"], timeout)
    row["success"] = "yes" if present and row.get("tets", 0) > 0 else "no"
    if present and row.get("tets", 0) == 0 and not err:
        err = "no tetrahedra in the output"
    row["error"] = err
    return row


def tool_summary(rows, tool):
    """A tool's rows, those that succeeded, those that kept the boundary, and its time ratios."""
    rs = [r for r in rows if r["tool"] == tool]
    ok = [r for r in rs if r["success"] == "yes"]
    kept = [r for r in ok if r.get("boundary_kept") == "yes"]
    ratios = [r["time_ratio"] for r in ok if r.get("time_ratio")]
    return rs, ok, kept, ratios


def write_csv(path, cols, rows):
    """The rows as CSV, floats with 6 significant digits."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})


def begin_outputs(args, cols, rows, title, mode, started, finished, command):
    """For benchmark_sized.py and benchmark_given.py: writes the rows to args.out/args.name.csv
    and returns the first lines of the .md: title, date, machine and its load, the command."""
    write_csv(os.path.join(args.out, args.name + ".csv"), cols, rows)
    return [title + "\n",
            "- date: %s (UTC), %.0f s in all" % (started.strftime("%Y-%m-%d %H:%M"),
                                                (finished - started).total_seconds()),
            "- machine: %s; load average at the end %s (the machine is shared with other "
            "engineers' builds: wall times are noisy, compare ratios within a case)"
            % (machine(), " ".join("%.2f" % x for x in os.getloadavg())),
            "- command: `%s` (`bash scripts/benchmark.sh --mode %s ...` builds the CLI and runs "
            "this)" % (command, mode)]


def surface_q_bound(pts, tris):
    """The best Q min a mesh that keeps the surface can have (SurfaceQualityBound.h): a tet on a
    triangle has Q <= 2 sqrt(6) area / longest edge^2; capped at 1."""
    if len(tris) == 0:
        return 1.0
    a, b, c = (pts[tris[:, k]] for k in range(3))
    longest = np.maximum.reduce([((b - a) ** 2).sum(1), ((c - a) ** 2).sum(1), ((c - b) ** 2).sum(1)])
    with np.errstate(divide="ignore", invalid="ignore"):
        caps = 2 * np.sqrt(6) * 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1) / longest
    caps = np.where(longest > 0, caps, 0.0)
    return float(min(1.0, caps.min()))


def rounding_tets(P):
    """Tets (P: m x 4 x 3) whose volume's sign rounding could decide: |det| within the orient3d
    filter's error bound ((7 + 56 eps) eps times the sum of the terms' magnitudes), evaluated
    from vertex 0 and from vertex 3, as TetMesher's volumeCertainlyPositive does (TetQuality.h);
    either orientation (TetGen's tets are the other way round)."""
    eps = 2.0 ** -53
    bound = (7.0 + 56.0 * eps) * eps

    def uncertain(o, p, q, r):
        u, v, w = p - o, q - o, r - o
        m = [v[:, 1] * w[:, 2], v[:, 2] * w[:, 1], v[:, 2] * w[:, 0], v[:, 0] * w[:, 2],
             v[:, 0] * w[:, 1], v[:, 1] * w[:, 0]]
        det = u[:, 0] * (m[0] - m[1]) + u[:, 1] * (m[2] - m[3]) + u[:, 2] * (m[4] - m[5])
        per = np.abs(u[:, 0]) * (np.abs(m[0]) + np.abs(m[1])) + \
            np.abs(u[:, 1]) * (np.abs(m[2]) + np.abs(m[3])) + \
            np.abs(u[:, 2]) * (np.abs(m[4]) + np.abs(m[5]))
        return ~(np.abs(det) > bound * per)
    a, b, c, d = (P[:, k] for k in range(4))
    return int((uncertain(a, b, c, d) | uncertain(d, a, b, c)).sum())


def analyse(case, pts_out, tets):
    """Boundary check, quality, volume. case: dict with pts, tris, expected mult, volume."""
    res = {}
    pin, tin = case["pts"], case["tris"]
    nin = len(pin)
    res["tets"] = len(tets)
    res["points"] = len(pts_out)
    # map output points -> input ids by exact coordinate equality
    lookup = {(float(x), float(y), float(z)): i for i, (x, y, z) in enumerate(pin)}
    mapped = np.empty(len(pts_out), dtype=np.int64)
    extra = nin
    unmatched = []
    for j, p in enumerate(pts_out):
        i = lookup.get((float(p[0]), float(p[1]), float(p[2])))
        if i is None:
            mapped[j] = extra
            extra += 1
            unmatched.append(j)
        else:
            mapped[j] = i
    res["input_points_lost"] = int(nin - len(set(mapped[mapped < nin].tolist())))
    res["steiner"] = len(unmatched)
    bsteiner = 0
    if unmatched:
        from vtkmodules.vtkCommonDataModel import vtkStaticCellLocator
        from vtkmodules.vtkCommonCore import reference
        loc = vtkStaticCellLocator()
        surf = polydata(pin, tin)
        loc.SetDataSet(surf)
        loc.BuildLocator()
        diag = float(np.linalg.norm(pin.max(0) - pin.min(0)))
        tol2 = (1e-10 * diag) ** 2
        cp = [0.0, 0.0, 0.0]
        cid, sub, d2 = reference(0), reference(0), reference(0.0)
        for j in unmatched:
            loc.FindClosestPoint(pts_out[j].tolist(), cp, cid, sub, d2)
            if float(d2) <= tol2:
                bsteiner += 1
    res["steiner_on_boundary"] = bsteiner
    if len(tets) == 0:
        res["boundary_kept"] = "no"
        return res
    t = mapped[tets]
    base = max(extra, 1)
    faces = np.concatenate([t[:, [1, 2, 3]], t[:, [0, 2, 3]], t[:, [0, 1, 3]], t[:, [0, 1, 2]]])
    keys = face_keys(faces, base)
    ukeys, counts = np.unique(keys, return_counts=True)
    faces_in = case["faces"]
    if all(len(f) == 3 for f in faces_in):
        ikeys = face_keys(tin, base)
        pos = np.searchsorted(ukeys, ikeys)
        pos[pos >= len(ukeys)] = 0
        found = ukeys[pos] == ikeys
        icount = np.where(found, counts[pos], 0)
        res["tri_missing"] = int((icount == 0).sum())
        res["tri_wrong_mult"] = int(((icount != 0) & (icount != case["fmult"])).sum())
        bkeys = ukeys[counts == 1]
        res["extra_boundary_faces"] = int((~np.isin(bkeys, ikeys)).sum())
    else:
        # polygons (possibly non-planar): the output faces whose 3 vertices are vertices of
        # one input polygon must triangulate it: k-2 triangles, each polygon edge in one of
        # them, each other edge (a diagonal) in two; each with the expected number of tets
        owner = {}
        for fi, f in enumerate(faces_in):
            for tri in itertools.combinations(f, 3):
                owner[int(face_keys(np.array([tri]), base)[0])] = fi
        owned = [[] for _ in faces_in]
        wrong = np.zeros(len(faces_in), dtype=bool)
        ext = 0
        for k, c in zip(ukeys.tolist(), counts.tolist()):
            fi = owner.get(k)
            if fi is None:
                ext += c == 1
                continue
            if c != case["fmult"][fi]:
                continue  # e.g. an inner face between 4 vertices of a non-planar polygon
            owned[fi].append((k // (base * base), (k // base) % base, k % base))
        missing = np.zeros(len(faces_in), dtype=bool)
        for fi, f in enumerate(faces_in):
            tris_f = owned[fi]
            ec = collections.Counter()
            for a, b, c in tris_f:
                for e in ((a, b), (b, c), (a, c)):
                    ec[(min(e), max(e))] += 1
            pedges = {(min(f[i], f[i - 1]), max(f[i], f[i - 1])) for i in range(len(f))}
            missing[fi] = len(tris_f) != len(f) - 2 or any(
                ec[e] != (1 if e in pedges else 2) for e in ec) or any(ec[e] != 1 for e in pedges)
        res["tri_missing"] = int(missing.sum())
        res["tri_wrong_mult"] = 0  # polygons: a wrong count shows up as a missing face
        res["extra_boundary_faces"] = int(ext)
    res["nonmanifold_faces"] = int((counts > 2).sum())
    ok = res["tri_missing"] == 0 and res["tri_wrong_mult"] == 0 and \
        res["extra_boundary_faces"] == 0 and res["nonmanifold_faces"] == 0 and bsteiner == 0
    res["boundary_kept"] = "yes" if ok else "no"
    # quality
    P = pts_out[tets]  # (m,4,3)
    e01, e02, e03 = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]
    vol6 = np.einsum("ij,ij->i", e01, np.cross(e02, e03))
    V = np.abs(vol6) / 6.0
    # face k opposite vertex k; outward normals (not normalised)
    fidx = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]
    N = []
    for (a, b, c) in fidx:
        N.append(np.cross(P[:, b] - P[:, a], P[:, c] - P[:, a]))
    N = np.stack(N, axis=1) * np.sign(vol6)[:, None, None]  # outward for either orientation
    A = 0.5 * np.linalg.norm(N, axis=2)
    edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    L = np.stack([np.linalg.norm(P[:, i] - P[:, j], axis=1) for i, j in edges], axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        rin = 3.0 * V / A.sum(axis=1)
        Q = 2.0 * math.sqrt(6.0) * rin / L.max(axis=1)
        Q = np.nan_to_num(Q)
        Nu = N / np.linalg.norm(N, axis=2)[:, :, None]
        dih = []
        for a in range(4):
            for b in range(a + 1, 4):
                c = np.clip(np.einsum("ij,ij->i", Nu[:, a], Nu[:, b]), -1.0, 1.0)
                dih.append(180.0 - np.degrees(np.arccos(c)))
        dih = np.nan_to_num(np.stack(dih, axis=1), nan=0.0)
    res["Q"] = Q
    res["q_min"] = float(Q.min())
    res["q_mean"] = float(Q.mean())
    res["q_lt03"] = float((Q < 0.3).mean())
    res["dih_min"] = float(dih.min())
    res["dih_max"] = float(dih.max())
    res["flat_tets"] = int((vol6 == 0).sum())
    res["rounding_tets"] = rounding_tets(P)
    vsum = float(V.sum())
    res["vol_sum"] = vsum
    res["vol_relerr"] = (vsum - case["volume"]) / case["volume"]
    return res


# ----------------------------------------------------------------------------- running
def run_timed(cmd, timeout, cwd, log):
    """Returns (rc or 'timeout', wall s, peak RSS KiB, stderr tail)."""
    tf = os.path.join(cwd, ".time")
    full = ["/usr/bin/time", "-f", "%M", "-o", tf] + cmd
    t0 = time.perf_counter()
    proc = subprocess.Popen(full, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=timeout)
        wall = time.perf_counter() - t0
        rc = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
        return "timeout", float(timeout), None, out.decode(errors="replace")[-2000:]
    rss = None
    try:
        with open(tf) as f:
            lines = [l for l in f.read().split("\n") if l.strip()]
        rss = int(lines[-1])
    except (OSError, ValueError, IndexError):
        pass
    text = out.decode(errors="replace")
    with open(log, "a") as f:
        f.write("$ %s\n%s\n[rc %s, %.3f s]\n" % (" ".join(shlex.quote(c) for c in cmd), text, rc, wall))
    return rc, wall, rss, text[-2000:]


def tool_job(tool, case, work, tetmesher):
    """(command, cwd, output reader, output files) for tool on case."""
    name, src = case["name"], case["path"]
    d = os.path.join(work, name, tool)
    os.makedirs(d, exist_ok=True)
    if tool == "tetmesher":
        out = os.path.join(d, "out.vtu")
        return [tetmesher, "mesh", src, "-o", out, "-q", "--boundary-only"], d, lambda: read_vtu(out), [out]
    if tool == "tetmesher-norefine":  # the boundary mesh, then the optimisation (no size field)
        out = os.path.join(d, "out.vtu")
        return [tetmesher, "mesh", src, "-o", out, "-q", "--no-refine"], d, lambda: read_vtu(out), [out]
    if tool.startswith("tetgen"):
        # TetGen 1.5 reads .off itself; other formats are written as .off (exact doubles)
        inp = os.path.join(d, "in.off")
        if src.endswith(".off"):
            with open(src) as fi, open(inp, "w") as fo:
                fo.write(fi.read())
        else:
            write_off(inp, case["pts"], case["tris"])
        sw = "-pY" if tool == "tetgen-pY" else "-pYq1.2"
        stem = os.path.join(d, "in.1")
        return ["tetgen", sw, "-Q", "in.off"], d, lambda: read_tetgen(stem), [stem + ".node", stem + ".ele"]
    if tool.startswith("gmsh"):
        algo = 1 if tool == "gmsh-delaunay" else 10
        write_gmsh_input(os.path.join(d, "in.msh"), os.path.join(d, "in.geo"), case["pts"],
                         case["tris"], case["sid"], case["parent"], algo)
        out = os.path.join(d, "out.msh")
        return (["gmsh", "in.geo", "-3", "-nt", "1", "-setnumber", "Mesh.Algorithm3D", str(algo),
                 "-format", "msh2", "-bin", "-save_all", "-o", "out.msh"], d,
                lambda: read_msh2_binary(out), [out])
    if tool == "vtkDelaunay3D":
        out = os.path.join(d, "out.vtu")
        return ([sys.executable, os.path.abspath(__file__), "--delaunay3d", src, out], d,
                lambda: read_vtu(out), [out])
    raise ValueError(tool)


def delaunay3d_main(src, out):
    from vtkmodules.vtkFiltersCore import vtkDelaunay3D
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    pts, faces = load_surface(src)
    tris = triangulate(pts, faces)
    dl = vtkDelaunay3D()
    dl.SetInputData(polydata(pts, tris))
    dl.SetAlpha(0.0)      # convex hull of the points: not boundary-conforming
    dl.SetTolerance(1e-9)  # do not merge close input points (default 1e-3 of the bbox)
    dl.Update()
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(out)
    w.SetInputData(dl.GetOutput())
    w.SetDataModeToBinary()
    if not w.Write():
        sys.exit(1)


def load_cases(names, data=DATA):
    meta = {}
    if os.path.exists(os.path.join(data, "corpus.csv")):
        with open(os.path.join(data, "corpus.csv")) as f:
            for row in csv.DictReader(f):
                meta[row["name"]] = row
    files = {}
    for fn in sorted(os.listdir(data)):
        base, ext = os.path.splitext(fn)
        if ext in (".off", ".stl", ".vtp", ".ply"):
            files[base if base not in files else base + "-" + ext[1:]] = fn
    cases = []
    for key, fn in files.items():
        if names and key not in names:
            continue
        path = os.path.join(data, fn)
        pts, faces = load_surface(path)
        tris = triangulate(pts, faces)
        sid = shells(tris, len(pts))
        parent = nesting(pts, tris, sid)
        mult = np.array([2 if parent[s] >= 0 else 1 for s in sid])
        # per input face: the multiplicity of the shell of its first vertex
        vshell = np.zeros(len(pts), dtype=np.int64)
        vshell[tris.reshape(-1)] = np.repeat(sid, 3)
        fmult = np.array([2 if parent[vshell[f[0]]] >= 0 else 1 for f in faces])
        row = meta.get(key)
        if row and row["file"] == fn:
            volume = float(row["volume"])
        else:
            volume = sum(signed_volume(pts, tris[sid == s]) for s in range(len(parent)) if parent[s] < 0)
        cases.append(dict(name=key, file=fn, path=path, pts=pts, tris=tris, faces=faces, sid=sid,
                          parent=parent, mult=mult, fmult=fmult, volume=volume,
                          q_bound=surface_q_bound(pts, tris)))
    if names:
        missing = set(names) - set(c["name"] for c in cases)
        if missing:
            sys.exit("unknown case(s): %s" % ", ".join(sorted(missing)))
    cases.sort(key=lambda c: len(c["tris"]))
    return cases


def machine():
    model = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, nproc %d, %s" % (model, os.cpu_count(), platform.platform())


def versions(tetmesher):
    v = {}
    for tool, cmd in (("gmsh", ["gmsh", "--version"]),):
        try:
            v[tool] = subprocess.run(cmd, capture_output=True, text=True, timeout=30).stderr.strip() or \
                subprocess.run(cmd, capture_output=True, text=True, timeout=30).stdout.strip()
        except OSError:
            v[tool] = "missing"
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "tetgen"], capture_output=True, text=True)
        v["tetgen"] = out.stdout.strip()
    except OSError:
        v["tetgen"] = "?"
    from vtkmodules.vtkCommonCore import vtkVersion
    v["vtk"] = vtkVersion.GetVTKVersion()
    try:
        v["tetmesher"] = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                        capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--short", "--untracked-files=no", "--",
                                "Filters", "Apps", "CMakeLists.txt"],
                               capture_output=True, text=True).stdout.split("\n")
        dirty = [l.strip().split()[-1] for l in dirty if l.strip()]
        if dirty:
            v["tetmesher"] += " + uncommitted changes in " + ", ".join(dirty)
        exe = os.path.realpath(tetmesher)
        if os.path.exists(exe):
            v["tetmesher"] += " (binary built %s)" % datetime.datetime.fromtimestamp(
                os.path.getmtime(exe), datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    except OSError:
        v["tetmesher"] = "?"
    return v


def fmt(x, spec):
    if x is None or x == "":
        return ""
    if isinstance(x, float) and math.isnan(x):
        return ""
    return format(x, spec)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="a handful of small cases: " + ",".join(QUICK))
    ap.add_argument("--cases", help="comma-separated case names (corpus.csv names)")
    ap.add_argument("--data", default=DATA,
                    help="folder of input surfaces (.off .stl .vtp .ply; default Data/), e.g. "
                    "../shared/peer-tests/tetgentests-cgal")
    ap.add_argument("--tools", default=",".join(TOOLS), help="default: " + ",".join(TOOLS))
    ap.add_argument("--repeat", type=int, default=3, help="runs per fast job (median); slow jobs run once")
    ap.add_argument("--slow", type=float, default=2.0, help="a job slower than this many seconds runs once")
    ap.add_argument("--timeout", type=float, default=90.0, help="per run, seconds")
    ap.add_argument("--tetmesher", default=os.path.join(ROOT, "build-bench", "bin", "tetmesher"))
    ap.add_argument("--out", default=os.path.join(ROOT, "Testing", "Benchmarks", "results"))
    ap.add_argument("--work", default=None, help="scratch folder (default: a temporary one)")
    ap.add_argument("--hist-case", default="gear", help="case of the Q histogram PNG")
    ap.add_argument("--rewrite-md", action="store_true",
                    help="only regenerate the tables of OUT/corpus.md from OUT/corpus.csv")
    ap.add_argument("--delaunay3d", nargs=2, metavar=("IN", "OUT"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.delaunay3d:
        delaunay3d_main(*args.delaunay3d)
        return
    if args.rewrite_md:
        rewrite_md(args.out)
        return
    names = None
    if args.cases:
        names = [c.strip() for c in args.cases.split(",") if c.strip()]
    elif args.quick:
        names = QUICK
    args.tetmesher = os.path.abspath(args.tetmesher)
    tools = [t.strip() for t in args.tools.split(",") if t.strip()]
    for t in tools:
        if t not in TOOLS:
            sys.exit("unknown tool %s" % t)
    cases = load_cases(names, os.path.abspath(args.data))
    work = args.work or tempfile.mkdtemp(prefix="tetmesher-bench-")
    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(work, "runs.log")
    command = "/usr/bin/python3 scripts/benchmark.py " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    command = command.replace(" --tetmesher build-bench/bin/tetmesher", "")  # benchmark.sh's default
    started = datetime.datetime.now(datetime.timezone.utc)
    floors = process_floors(tools, lambda tool, case: tool_job(tool, case, work, args.tetmesher),
                            args.repeat, args.timeout, log, work)
    rows, qhist = [], {}
    # The repeats go round the tools (run_rounds).
    for case, tool, (cmd, cwd, reader, outs), st in each_result(
            cases, lambda tool, case: tool_job(tool, case, work, args.tetmesher), tools, args, log):

        def measure(pts_out, tets):
            res = analyse(case, pts_out, tets)
            Q = res.pop("Q", None)
            if case["name"] == args.hist_case and Q is not None:
                qhist[tool] = Q
            return res
        row = dict(case=case["name"], triangles=len(case["tris"]), input_points=len(case["pts"]),
                   shells=len(case["parent"]), surface_q_bound=case["q_bound"], tool=tool)
        row.update(result_row(st, outs, reader, measure, args.timeout))
        if row.get("tets") and row["success"] == "yes":
            row["tets_per_s"] = row["tets"] / row["time_s"]
        rows.append(row)
        print("%-22s %-14s %-4s %8.3fs %7s tets  boundary %-3s Qmin %s  %s" % (
            case["name"], tool, row["success"], row["time_s"], row.get("tets", ""),
            row.get("boundary_kept", "-"), fmt(row.get("q_min"), ".3f"), row["error"]), flush=True)
    finished = datetime.datetime.now(datetime.timezone.utc)
    # ratios vs TetMesher, by wall time and above the floors (ours clamped to 1 ms: a run at the
    # floor has no time above it to divide by)
    ref = {r["case"]: r for r in rows if r["tool"] == "tetmesher" and r["success"] == "yes"}
    for r in rows:
        above = above_floor(r, floors)
        m = ref.get(r["case"])
        if m and r["success"] == "yes" and r["tool"] != "tetmesher":
            r["time_ratio"] = r["time_s"] / m["time_s"] if m["time_s"] > 0 else None
            r["tets_ratio"] = r["tets"] / m["tets"]
            ours = above_floor(m, floors)
            if above is not None and ours is not None:
                r["ratio_above_floor"] = max(above, 0.0) / max(ours, 1e-3)
    write_outputs(args, rows, cases, tools, command, started, finished, qhist, floors)
    print("results in %s (scratch: %s)" % (args.out, work))


COLS = ["case", "triangles", "input_points", "shells", "surface_q_bound", "tool", "success", "rc", "runs", "time_s",
        "time_ratio", "time_above_floor_s", "ratio_above_floor", "rss_mb", "tets", "tets_ratio", "tets_per_s", "points", "steiner",
        "steiner_on_boundary", "input_points_lost", "boundary_kept", "tri_missing", "tri_wrong_mult",
        "extra_boundary_faces", "nonmanifold_faces", "q_min", "q_mean", "q_lt03", "dih_min",
        "dih_max", "flat_tets", "rounding_tets", "vol_sum", "vol_relerr", "error"]


def write_outputs(args, rows, cases, tools, command, started, finished, qhist, floors):
    suffix = "" if not (args.quick or args.cases) else "-partial"
    with open(os.path.join(args.out, "corpus%s.csv" % suffix), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    v = versions(args.tetmesher)
    md = []
    data = os.path.relpath(os.path.abspath(args.data), ROOT)
    md.append("# TetMesher side-by-side benchmark on the %s corpus\n" % (data + "/"))
    md.append("- date: %s (UTC), %.0f s in all" % (started.strftime("%Y-%m-%d %H:%M"),
                                                 (finished - started).total_seconds()))
    md.append("- machine: %s; load average at the end %s (the machine is shared: times are noisy)"
              % (machine(), " ".join("%.2f" % x for x in os.getloadavg())))
    md.append("- command: `bash scripts/benchmark.sh%s` = `%s`" % (
        "" if not command.split("benchmark.py")[1].strip() else " " + command.split("benchmark.py")[1].strip(),
        command))
    binary_dir = os.path.relpath(os.path.dirname(os.path.dirname(os.path.abspath(args.tetmesher))), ROOT)
    md.append("- versions: TetMesher git %s (Release, %s), TetGen %s, %s, VTK %s"
              % (v["tetmesher"], binary_dir, v["tetgen"], "Gmsh " + v["gmsh"], v["vtk"]))
    md.append("- tools: `tetmesher mesh IN -o OUT.vtu -q --boundary-only` (*tetmesher*) and `--no-refine` "
              "(*tetmesher-norefine*: the boundary mesh, then the optimisation); `tetgen -pY` and `tetgen -pYq1.2` (on .off; "
              ".vtp/.stl converted to .off with exact doubles); `gmsh in.geo -3 -nt 1` with "
              "Mesh.Algorithm3D=1 (Delaunay) / 10 (HXT) on the surface merged as a discrete MSH 2.2 mesh "
              "(one surface loop and volume per shell, enclosed shells as holes + own volume; Gmsh "
              "keeps the discrete surface but inserts interior points by default); `vtkDelaunay3D` "
              "(Alpha 0, Tolerance 1e-9, in a Python subprocess) on the surface points.")
    md.append("- time: wall time of the whole process (reading, meshing, writing), median of up to %d "
              "runs (1 run if slower than %g s), the repeats going round the tools (A B C, A B C) "
              "since 2026-11-30 09:40; RSS: peak resident set (`/usr/bin/time -f %%M`); "
              "time-out %g s per run." % (args.repeat, args.slow, args.timeout))
    md.append(floors_line(floors))
    md.append("- checks (ours, on the output files): *bnd* = boundary kept exactly: output points "
              "mapped to input points by exact coordinate equality, every input triangle a face of "
              "exactly 1 tet (2 for an enclosed shell = an interface), every output boundary face an "
              "input triangle, no Steiner point on the boundary (*bSt*; *St* = all Steiner points). "
              "Q = 2*sqrt(6)*r_in/l_max; *Q<0.3* = share of tets; dihedral min/max in degrees; "
              "*flat* = tets of zero volume in double arithmetic (/ tets whose volume is within its "
              "rounding error: the orient3d filter's bound, from two vertices; see TetQuality.h); "
              "*dV* = (sum of tet volumes - enclosed volume)/enclosed volume.")
    md.append("")
    md.extend(tables_md(rows, tools))
    plots = make_plots(args, rows, tools, qhist)
    for p in plots:
        md.append("![%s](%s)" % (p, p))
    with open(os.path.join(args.out, "corpus%s.md" % suffix), "w") as f:
        f.write("\n".join(md) + "\n")


def short(r):
    """One cell of the pivot table: time ratio vs TetMesher and boundary check, or the failure."""
    if r is None:
        return ""
    if r["rc"] == "timeout":
        return "time-out"
    if r["success"] != "yes":
        return "FAIL"
    t = "%.3g s" % r["time_s"] if r.get("time_ratio") in (None, "") else "x%.2g" % r["time_ratio"]
    return "%s, %s%s" % (t, "kept" if r.get("boundary_kept") == "yes" else "NOT kept",
                         ", Qmin %.2f" % r["q_min"] if r.get("q_min") not in (None, "") else "")


def tables_md(rows, tools):
    md = []
    # pivot: one line per case
    md.append("## Per case, TetMesher vs the others\n")
    md.append("Other tools: wall time as a multiple of TetMesher's (x0.5 = twice as fast as "
              "TetMesher), whether the boundary is kept exactly, Q min. *Q bound*: the highest Q min "
              "that a mesh keeping the surface can have, 2 sqrt(6) area / longest edge^2 of its "
              "worst triangle (a tet on a triangle cannot do better; capped at 1; a tool that splits "
              "the surface is not bound by it). Details below.\n")
    others = [t for t in tools if t != "tetmesher"]
    md.append("| case | tris | Q bound | TetMesher | %s |" % " | ".join(others))
    md.append("|---|---|---|---|%s" % ("---|" * len(others)))
    by = {(r["case"], r["tool"]): r for r in rows}
    for c in dict.fromkeys(r["case"] for r in rows):
        m = by.get((c, "tetmesher"))
        if m is None:
            cell = ""
        elif m["success"] == "yes":
            cell = "%.3g s, %s, Qmin %.2f" % (m["time_s"], "kept" if m.get("boundary_kept") == "yes"
                                              else "NOT kept", m["q_min"])
        else:
            cell = "**%s**" % ("time-out" if m["rc"] == "timeout" else "FAIL")
        tri = next(r["triangles"] for r in rows if r["case"] == c)
        bound = next((r.get("surface_q_bound") for r in rows if r["case"] == c), None)
        md.append("| %s | %s | %s | %s | %s |" % (c, tri, fmt(bound, ".2g"), cell,
                                                 " | ".join(short(by.get((c, t))) for t in others)))
    md.append("")
    # summary per tool
    md.append("## Summary per tool\n")
    md.append("*above floor*: the same ratio of the times above each tool's process floor (header); "
              "*TM at most half*: the cases where TetMesher took at most half the tool's time, "
              "wall / above the floors, of those both meshed.\n")
    md.append("| tool | success | boundary kept | total time s | median time ratio vs TetMesher | "
              "above floor | TM at most half | median Q min | median Q<0.3 | flat / within rounding, in all |")
    md.append("|---|---|---|---|---|---|---|---|---|---|")
    for t in tools:
        rs, ok, kept, ratios = tool_summary(rows, t)
        above = [r["ratio_above_floor"] for r in ok if r.get("ratio_above_floor") is not None]
        half = "%d / %s of %d" % (sum(1 for x in ratios if x >= 2),
                                  sum(1 for x in above if x >= 2) if above else "-",
                                  len(ratios)) if ratios else ""
        md.append("| %s | %d/%d | %d/%d | %.2f | %s | %s | %s | %s | %s | %d / %d |" % (
            t, len(ok), len(rs), len(kept), len(rs), sum(r["time_s"] for r in rs),
            fmt(statistics.median(ratios), ".2f") if ratios else "",
            fmt(statistics.median(above), ".2f") if above else "", half,
            fmt(statistics.median([r["q_min"] for r in ok]), ".3f") if ok else "",
            fmt(statistics.median([r["q_lt03"] for r in ok]), ".1%") if ok else "",
            sum(r.get("flat_tets", 0) for r in ok), sum(r.get("rounding_tets", 0) for r in ok)))
    md.append("")
    md.append("## Per case\n")
    md.append("| case | tris | tool | ok | time s | x TM | above floor s | x TM | RSS MB | tets | x TM | tets/s | bnd | "
              "miss/extra | St | bSt | Q min | Q mean | Q<0.3 | flat | dih min | dih max | dV | note |")
    md.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ok = r["success"] == "yes"
        wall, ratio, rss = time_cells(r)
        md.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["case"], r["triangles"], r["tool"], r["success"], wall, ratio,
            fmt(r.get("time_above_floor_s"), ".4f"), fmt(r.get("ratio_above_floor"), ".2f"), rss,
            r.get("tets", "") if ok else "", fmt(r.get("tets_ratio"), ".2f"),
            fmt(r.get("tets_per_s"), ".3g") if ok else "",
            r.get("boundary_kept", "") if ok else "",
            ("%d/%d" % (r["tri_missing"], r["extra_boundary_faces"]) if ok and "tri_missing" in r else ""),
            r.get("steiner", "") if ok else "", r.get("steiner_on_boundary", "") if ok else "",
            fmt(r.get("q_min"), ".3f"), fmt(r.get("q_mean"), ".3f"), fmt(r.get("q_lt03"), ".1%"),
            ("%s / %s" % (r.get("flat_tets", ""), r.get("rounding_tets", ""))) if ok else "", fmt(r.get("dih_min"), ".2f"), fmt(r.get("dih_max"), ".2f"),
            fmt(r.get("vol_relerr"), ".1e"), r["error"].replace("|", "/")))
    md.append("")
    return md


def rewrite_md(out):
    """Regenerate the tables of corpus.md from corpus.csv (header and plots kept)."""
    rows = []
    with open(os.path.join(out, "corpus.csv")) as f:
        for r in csv.DictReader(f):
            for k, v in list(r.items()):
                if k in ("case", "tool", "success", "boundary_kept", "error"):
                    continue
                if v == "":
                    r[k] = None
                elif k == "rc" and v == "timeout":
                    pass
                else:
                    x = float(v)
                    r[k] = int(x) if x.is_integer() and k not in ("time_s", "time_ratio", "time_above_floor_s",
                                                                   "ratio_above_floor", "rss_mb",
                                                                   "q_min", "q_mean", "q_lt03",
                                                                   "surface_q_bound") else x
            r["error"] = r["error"] or ""
            rows.append(r)
    tools = list(dict.fromkeys(r["tool"] for r in rows))
    path = os.path.join(out, "corpus.md")
    with open(path) as f:
        old = f.read()
    head = old.split("## Per case, TetMesher")[0].split("## Summary per tool")[0].rstrip("\n").split("\n")
    pics = [l for l in old.split("\n") if l.startswith("![")]
    with open(path, "w") as f:
        f.write("\n".join(head + [""] + tables_md(rows, tools) + pics) + "\n")


def make_plots(args, rows, tools, qhist):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    suffix = "" if not (args.quick or args.cases) else "-partial"
    out = []
    if qhist:
        fig, axes = plt.subplots(len(qhist), 1, figsize=(7, 1.8 * len(qhist)), sharex=True)
        axes = np.atleast_1d(axes)
        for ax, (t, Q) in zip(axes, qhist.items()):
            ax.hist(Q, bins=50, range=(0, 1), color="C%d" % tools.index(t))
            ax.set_ylabel("tets")
            ax.set_title("%s: %d tets, Q min %.3f, mean %.3f" % (t, len(Q), Q.min(), Q.mean()), fontsize=9)
        axes[-1].set_xlabel("Q = 2*sqrt(6)*r_in/l_max")
        fig.suptitle("Q histogram, case %s" % args.hist_case)
        fig.tight_layout()
        name = "q_hist_%s%s.png" % (args.hist_case, suffix)
        fig.savefig(os.path.join(args.out, name), dpi=90)
        plt.close(fig)
        out.append(name)
    fig, ax = plt.subplots(figsize=(7, 5))
    for t in tools:
        rs = [r for r in rows if r["tool"] == t and r["success"] == "yes"]
        if rs:
            ax.loglog([r["triangles"] for r in rs], [r["time_s"] for r in rs], "o", label=t,
                      color="C%d" % tools.index(t), alpha=0.8)
    ax.set_xlabel("input triangles")
    ax.set_ylabel("wall time s (whole process)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("scaling on the corpus")
    fig.tight_layout()
    name = "scaling%s.png" % suffix
    fig.savefig(os.path.join(args.out, name), dpi=90)
    plt.close(fig)
    out.append(name)
    return out


if __name__ == "__main__":
    main()
