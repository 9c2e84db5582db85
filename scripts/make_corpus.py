#!/usr/bin/python3
"""Generates TetMesher's procedural test surfaces into Data/ and writes Data/corpus.csv.

Every surface is a set of closed, consistently outward-oriented, pairwise disjoint triangle
shells (or shells sharing faces for multi-material cases), written as binary zlib-compressed
.vtp. The output is deterministic: running the script twice gives identical files.

Run with Debian's interpreter (it has VTK 9.1): /usr/bin/python3 scripts/make_corpus.py
Options:
  --out DIR        output folder (default: <repo>/Data)
  --check EXE      also run the C++ diagnosis (the CoreTestSurfaceDiagnosis test executable)
                   on every generated surface and on the copied real models
  --verify         only check that the files in Data/ match what the script generates

corpus.csv columns: name, file, triangles, points, shells, volume (the volume enclosed by the
outermost shells, i.e. the total volume a mesher must fill, from the divergence theorem),
shell_volumes (signed volume of each shell, ';'-separated; all positive: outward).
"""

import argparse
import csv
import io
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# ----------------------------------------------------------------------------------------------
# Mesh building blocks. A shell is (points Nx3 float64, triangles Mx3 int).


class Builder:
    """Accumulates points (optionally merged by an integer key) and triangles."""

    def __init__(self):
        self.points = []
        self.tris = []
        self.keys = {}

    def point(self, p, key=None):
        if key is not None and key in self.keys:
            return self.keys[key]
        self.points.append([float(p[0]), float(p[1]), float(p[2])])
        idx = len(self.points) - 1
        if key is not None:
            self.keys[key] = idx
        return idx

    def tri(self, a, b, c):
        self.tris.append((a, b, c))

    def quad(self, a, b, c, d):
        """Quad a,b,c,d counterclockwise seen from outside."""
        self.tri(a, b, c)
        self.tri(a, c, d)

    def shell(self):
        return np.array(self.points, dtype=np.float64), np.array(self.tris, dtype=np.int64)


def signed_volume(points, tris):
    a, b, c = points[tris[:, 0]], points[tris[:, 1]], points[tris[:, 2]]
    return float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6.0)


def orient_outward(shell):
    points, tris = shell
    if signed_volume(points, tris) < 0:
        tris = tris[:, ::-1].copy()
    return points, tris


def transform(shell, scale=1.0, translate=(0, 0, 0), rotate=None):
    points, tris = shell
    p = points * scale
    if rotate is not None:
        p = p @ np.asarray(rotate).T
    return p + np.asarray(translate, dtype=np.float64), tris


def rotation(axis, angle):
    c, s = math.cos(angle), math.sin(angle)
    if axis == "x":
        return [[1, 0, 0], [0, c, -s], [0, s, c]]
    if axis == "y":
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def box(nx, ny, nz, lo=(0, 0, 0), hi=(1, 1, 1)):
    """Box [lo,hi] with its faces split into an nx*ny*nz lattice, outward."""
    b = Builder()
    n = (nx, ny, nz)

    def pid(i, j, k):
        return b.point(
            [lo[a] + (hi[a] - lo[a]) * (v / n[a]) for a, v in enumerate((i, j, k))], key=(i, j, k)
        )

    for axis in range(3):
        a1, a2 = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, n[axis]):
            for u in range(n[a1]):
                for v in range(n[a2]):
                    corners = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        idx = [0, 0, 0]
                        idx[axis] = side
                        idx[a1] = u + du
                        idx[a2] = v + dv
                        corners.append(pid(*idx))
                    # (a1,a2) counterclockwise has normal +axis.
                    if side == 0:
                        corners.reverse()
                    b.quad(*corners)
    return b.shell()


def icosphere(levels, radius=1.0, center=(0, 0, 0)):
    t = (1 + math.sqrt(5)) / 2
    verts = [
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
        (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1),
    ]
    pts = [np.array(v, dtype=np.float64) / np.linalg.norm(v) for v in verts]
    faces = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
        (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
        (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    for _ in range(levels):
        mid = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                m = (pts[a] + pts[b]) / 2
                pts.append(m / np.linalg.norm(m))
                mid[key] = len(pts) - 1
            return mid[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    points = np.array(pts) * radius + np.asarray(center, dtype=np.float64)
    return orient_outward((points, np.array(faces, dtype=np.int64)))


def uv_sphere(theta, phi, radius=0.5):
    """vtkSphereSource's layout: two poles with fans of `theta` triangles, phi - 2 rings."""
    pts = [(0.0, 0.0, radius), (0.0, 0.0, -radius)]
    for j in range(1, phi - 1):
        p = math.pi * j / (phi - 1)
        for i in range(theta):
            t = 2 * math.pi * i / theta
            pts.append((radius * math.sin(p) * math.cos(t), radius * math.sin(p) * math.sin(t),
                        radius * math.cos(p)))
    rings = phi - 2

    def pid(ring, i):
        return 2 + ring * theta + i % theta

    tris = []
    for i in range(theta):
        tris.append((0, pid(0, i), pid(0, i + 1)))
        for ring in range(rings - 1):
            tris.append((pid(ring, i), pid(ring + 1, i), pid(ring + 1, i + 1)))
            tris.append((pid(ring, i), pid(ring + 1, i + 1), pid(ring, i + 1)))
        tris.append((1, pid(rings - 1, i + 1), pid(rings - 1, i)))
    return orient_outward((np.array(pts, dtype=np.float64), np.array(tris, dtype=np.int64)))


def torus(R, r, nu, nv, center=(0, 0, 0), rotate=None):
    """Torus around the z axis, nu steps along the big circle, nv around the tube."""
    b = Builder()
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            b.point([(R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u),
                     r * math.sin(v)])
    for i in range(nu):
        for j in range(nv):
            a = i * nv + j
            bb = ((i + 1) % nu) * nv + j
            c = ((i + 1) % nu) * nv + (j + 1) % nv
            d = i * nv + (j + 1) % nv
            b.quad(a, bb, c, d)
    return orient_outward(transform(b.shell(), translate=center, rotate=rotate))


def polar_prism(r_in, r_out, layers, height, nz, solid=False):
    """Extrusion along z of a polar-grid region between r_in[k] and r_out[k] at the angles
    2*pi*k/K: an annulus-like ring (r_in > 0) or, with solid=True, a disk (r_in ignored, a
    centre point with a fan). `layers` radial subdivisions, `nz` height subdivisions."""
    K = len(r_out)
    b = Builder()

    def ring_point(k, j, z):
        # Radial layer j of angle k; in the solid case layer 0 is the centre (see centre()).
        k %= K
        th = 2 * math.pi * k / K
        lo = 0.0 if solid else r_in[k]
        r = lo + (r_out[k] - lo) * j / layers
        return b.point([r * math.cos(th), r * math.sin(th), height * z / nz], key=("p", k, j, z))

    def centre(z):
        return b.point([0.0, 0.0, height * z / nz], key=("c", z))

    jmin = 1 if solid else 0
    # Caps: bottom (z=0, normal -z), top (z=nz, normal +z).
    for z, up in ((0, False), (nz, True)):
        for k in range(K):
            for j in range(jmin, layers):
                q = [ring_point(k, j, z), ring_point(k, j + 1, z), ring_point(k + 1, j + 1, z),
                     ring_point(k + 1, j, z)]  # counterclockwise seen from +z
                if not up:
                    q.reverse()
                b.quad(*q)
            if solid:
                t = [centre(z), ring_point(k, 1, z), ring_point(k + 1, 1, z)]
                if not up:
                    t.reverse()
                b.tri(*t)
    # Outer wall (normal outward) and inner wall (normal towards the axis).
    for z in range(nz):
        for k in range(K):
            b.quad(ring_point(k, layers, z), ring_point(k + 1, layers, z),
                   ring_point(k + 1, layers, z + 1), ring_point(k, layers, z + 1))
            if not solid:
                b.quad(ring_point(k, 0, z), ring_point(k, 0, z + 1), ring_point(k + 1, 0, z + 1),
                       ring_point(k + 1, 0, z))
    return b.shell()


def slot_profile(K, slots, base, depth, slot_steps):
    """Radii over K angles: `base` everywhere, `base+depth` inside the slots (slot_steps
    angular steps wide at the bottom), a step of one angle for each wall."""
    per = K // slots
    r = []
    for k in range(K):
        r.append(base + depth if (k % per) < slot_steps else base)
    return r


def helix_tube(R, pitch, turns, a, nu_per_turn, nv):
    """Tube of radius a around the helix (R cos t, R sin t, pitch t / 2pi), capped at both
    ends with a fan to the end centres."""
    b = Builder()
    nu = int(round(turns * nu_per_turn))
    c = pitch / (2 * math.pi)
    norm = math.sqrt(R * R + c * c)
    for i in range(nu + 1):
        t = 2 * math.pi * turns * i / nu
        p = np.array([R * math.cos(t), R * math.sin(t), c * t])
        T = np.array([-R * math.sin(t), R * math.cos(t), c]) / norm
        N = np.array([-math.cos(t), -math.sin(t), 0.0])
        B = np.cross(T, N)
        for j in range(nv):
            v = 2 * math.pi * j / nv
            b.point(p + a * (math.cos(v) * N + math.sin(v) * B))
    start = b.point([R, 0.0, 0.0])
    tend = 2 * math.pi * turns
    end = b.point([R * math.cos(tend), R * math.sin(tend), c * tend])
    for i in range(nu):
        for j in range(nv):
            p00, p01 = i * nv + j, i * nv + (j + 1) % nv
            p10, p11 = (i + 1) * nv + j, (i + 1) * nv + (j + 1) % nv
            b.quad(p00, p10, p11, p01)
    for j in range(nv):
        b.tri(start, j, (j + 1) % nv)
        b.tri(end, nu * nv + (j + 1) % nv, nu * nv + j)
    shell = b.shell()
    vol = signed_volume(*shell)
    # The quads and caps were written with one consistent orientation; flip all if inward.
    return orient_outward(shell) if vol != 0 else shell


def combine(shells):
    points, tris, offset = [], [], 0
    for p, t in shells:
        points.append(p)
        tris.append(t + offset)
        offset += len(p)
    return np.vstack(points), np.vstack(tris)


# ----------------------------------------------------------------------------------------------
# The corpus. Each entry: name -> (list of shells, list of outermost shell indices, what it
# exercises).


def circle_distance(c1, n1, R1, c2, n2, R2, samples=2000):
    """Minimum distance between two circles (sampled finely: a safety check, not exact)."""

    def pts(c, n, R):
        n = np.asarray(n, dtype=np.float64)
        n /= np.linalg.norm(n)
        u = np.cross(n, [1, 0, 0] if abs(n[0]) < 0.9 else [0, 1, 0])
        u /= np.linalg.norm(u)
        v = np.cross(n, u)
        t = np.linspace(0, 2 * math.pi, samples, endpoint=False)[:, None]
        return np.asarray(c) + R * (np.cos(t) * u + np.sin(t) * v)

    a, b = pts(c1, n1, R1), pts(c2, n2, R2)
    best = math.inf
    for i in range(0, len(a), 200):
        d = np.linalg.norm(a[i:i + 200, None, :] - b[None, :, :], axis=2)
        best = min(best, float(d.min()))
    return best


def make_cases():
    cases = {}

    cases["cube"] = (
        [box(8, 8, 8)], [0],
        "unit cube, faces split 8x8: flat faces full of co-planar and co-spherical points")

    cases["icosphere"] = (
        [icosphere(3)], [0], "icosphere, 1280 triangles: smooth convex surface")

    cases["torus"] = (
        [torus(1.0, 0.35, 48, 24)], [0], "torus: genus 1, a region that is not simply connected")

    cases["nested_spheres"] = (
        [icosphere(3, 1.0), icosphere(2, 0.5)], [0],
        "sphere inside a sphere: two nested shells, a cavity or two regions")

    cases["thin_plate"] = (
        [box(40, 40, 1, lo=(0, 0, 0), hi=(1, 1, 0.02))], [0],
        "1 x 1 x 0.02 plate: aspect ratio 50, faces far apart in index but close in space")

    K, slots = 216, 36
    stator_in = slot_profile(K, slots, 1.0, 0.45, 3)
    cases["stator_ring"] = (
        [polar_prism(stator_in, [1.8] * K, 3, 0.6, 3)], [0],
        "slotted stator ring: 36 deep, narrow slots (paper figs 7-8), genus 1")

    # Alternator-like: an air box around a stator ring and a salient-pole rotor, thin gap.
    rotor_out = [0.95 if (k % 54) < 36 else 0.7 for k in range(K)]
    rotor = polar_prism(None, rotor_out, 3, 0.6, 3, solid=True)
    stator = polar_prism(slot_profile(K, slots, 1.0, 0.45, 3), [1.8] * K, 3, 0.6, 3)
    air = box(6, 6, 4, lo=(-2.5, -2.5, -0.7), hi=(2.5, 2.5, 1.3))
    cases["alternator"] = (
        [air, stator, rotor], [0],
        "air box around a slotted stator and a 4-pole rotor with a 0.05 air gap: an exterior "
        "domain with nested shells and a thin gap")

    gear_out = []
    teeth = 24
    for k in range(K // teeth * teeth):
        phase = k % (K // teeth)
        gear_out.append(1.0 if phase < (K // teeth) // 2 else 0.85)
    gear = polar_prism([0.3] * len(gear_out), gear_out, 3, 0.25, 2)
    cases["gear"] = ([gear], [0], "spur gear with 24 teeth and a bore: many convex/concave corners")

    cases["helix_tube"] = (
        [helix_tube(1.0, 0.8, 2.5, 0.15, 48, 16)], [0],
        "tube along a 2.5-turn helix with capped ends: long, curved, close to itself")

    # Tangle: a chain of four linked (disjoint) thin tori, alternately in the xy and xz planes.
    r = 0.15
    tori = [
        ((0.0, 0, 0), None, (0, 0, 1)),
        ((1.2, 0, 0), rotation("x", math.pi / 2), (0, 1, 0)),
        ((2.4, 0, 0), None, (0, 0, 1)),
        ((3.6, 0, 0), rotation("x", math.pi / 2), (0, 1, 0)),
    ]
    shells = []
    for i, (c, rot, n) in enumerate(tori):
        for j in range(i):
            d = circle_distance(c, n, 1.0, tori[j][0], tori[j][2], 1.0)
            assert d > 2 * r + 0.05, f"tori {i},{j} too close: {d}"
        shells.append(torus(1.0, r, 64, 12, center=c, rotate=rot))
    cases["tori_tangle"] = (
        shells, [0, 1, 2, 3], "chain of four linked, disjoint thin tori: several interlocked shells")

    cases["uv_sphere"] = (
        [uv_sphere(100, 100)], [0],
        "latitude-longitude sphere laid out like vtkSphereSource 100x100: every point on one "
        "sphere (fully co-spherical Delaunay), pole fans of 100 thin triangles")

    return cases


# ----------------------------------------------------------------------------------------------
# Checks, output.


def check_closed_oriented(points, tris, name):
    """Every directed edge exactly once and its reverse exactly once (closed, manifold,
    consistently oriented); every point used; no degenerate triangle (by area)."""
    directed = {}
    for t in tris:
        for k in range(3):
            e = (int(t[k]), int(t[(k + 1) % 3]))
            directed[e] = directed.get(e, 0) + 1
    for (a, b), n in directed.items():
        if n != 1 or directed.get((b, a), 0) != 1:
            raise SystemExit(f"{name}: edge {a}-{b} is not closed/manifold/consistent")
    if len(np.unique(tris)) != len(points):
        raise SystemExit(f"{name}: unused points")
    area = np.linalg.norm(
        np.cross(points[tris[:, 1]] - points[tris[:, 0]], points[tris[:, 2]] - points[tris[:, 0]]),
        axis=1)
    if area.min() <= 0:
        raise SystemExit(f"{name}: degenerate triangle")


def to_polydata(points, tris):
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

    pts = vtkPoints()
    pts.SetDataTypeToDouble()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    offsets = np.arange(0, 3 * len(tris) + 1, 3, dtype=np.int64)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_to_vtkIdTypeArray(np.ascontiguousarray(tris.ravel(), dtype=np.int64),
                                          deep=True))
    poly = vtkPolyData()
    poly.SetPoints(pts)
    poly.SetPolys(cells)
    return poly


def write_vtp(path, points, tris):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    w = vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(to_polydata(points, tris))
    w.SetDataModeToBinary()
    w.SetCompressorTypeToZLib()
    w.SetHeaderTypeToUInt64()
    w.SetIdTypeToInt64()
    if not w.Write():
        raise SystemExit(f"could not write {path}")


def read_vtp(path):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    poly = r.GetOutput()
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    conn = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return points, conn


def write_off(path, points, tris):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(points)} {len(tris)} 0\n")
        for p in points:
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r}\n")
        for t in tris:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def read_off(path):
    """Minimal OFF reader (OFF/COFF/NOFF headers, polygons as fans, extra columns ignored)."""
    lines = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                lines.append(line.split())
    head = lines.pop(0)
    if head[0].endswith("OFF"):
        counts = head[1:] if len(head) > 1 else lines.pop(0)
    else:
        counts = head
    nv, nf = int(counts[0]), int(counts[1])
    points = np.array([[float(x) for x in lines[i][:3]] for i in range(nv)])
    tris = []
    for line in lines[nv:nv + nf]:
        n = int(line[0])
        ids = [int(x) for x in line[1:1 + n]]
        tris += [(ids[0], ids[k], ids[k + 1]) for k in range(1, n - 1)]
    return points, np.array(tris, dtype=np.int64)


def shell_count(n_points, tris):
    parent = list(range(n_points))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b, c in tris:
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    return len({find(int(i)) for i in np.unique(tris)})


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "Data"))
    ap.add_argument("--check", metavar="EXE", help="CoreTestSurfaceDiagnosis executable")
    ap.add_argument("--verify", action="store_true",
                    help="regenerate into a temporary folder and compare with --out")
    args = ap.parse_args()

    out = args.out
    if args.verify:
        tmp = tempfile.mkdtemp()
        out = tmp
    os.makedirs(out, exist_ok=True)

    rows = []
    offs = []
    tmpdir = tempfile.mkdtemp()
    for name, (shells, outer, what) in make_cases().items():
        for i, (p, t) in enumerate(shells):
            check_closed_oriented(p, t, f"{name} shell {i}")
        vols = [signed_volume(p, t) for p, t in shells]
        if min(vols) <= 0:
            raise SystemExit(f"{name}: a shell is not outward")
        points, tris = combine(shells)
        path = os.path.join(out, f"{name}.vtp")
        write_vtp(path, points, tris)
        rp, rt = read_vtp(path)
        assert np.array_equal(rp, points) and np.array_equal(rt, tris), name
        assert shell_count(len(points), tris) == len(shells), name
        rows.append({
            "name": name, "file": f"{name}.vtp", "triangles": len(tris), "points": len(points),
            "shells": len(shells), "volume": repr(sum(vols[i] for i in outer)),
            "shell_volumes": ";".join(repr(v) for v in vols), "exercises": what,
        })
        off = os.path.join(tmpdir, f"{name}.off")
        write_off(off, points, tris)
        offs.append(off)
        size = os.path.getsize(path)
        print(f"{name}: {len(tris)} triangles, {len(points)} points, {len(shells)} shells, "
              f"volume {rows[-1]['volume']}, {size} bytes")
        if size > 1 << 20:
            raise SystemExit(f"{name}: file larger than 1 MB")

    # Real models copied into Data/ (kept in their format): volume and shells too.
    for fname in sorted(os.listdir(args.out if os.path.isdir(args.out) else out)):
        if not fname.endswith(".off"):
            continue
        p, t = read_off(os.path.join(args.out, fname))
        rows.append({
            "name": fname[:-4], "file": fname, "triangles": len(t), "points": len(p),
            "shells": shell_count(len(p), t), "volume": repr(signed_volume(p, t)),
            "shell_volumes": "", "exercises": "real model (see README.md)",
        })

    csv_path = os.path.join(out, "corpus.csv")
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    with open(csv_path, "w") as f:
        f.write(buf.getvalue())

    if args.verify:
        bad = []
        for fname in sorted(os.listdir(out)):
            a, b = os.path.join(out, fname), os.path.join(args.out, fname)
            if not os.path.exists(b) or open(a, "rb").read() != open(b, "rb").read():
                bad.append(fname)
        if bad:
            raise SystemExit(f"Data/ differs from the generator: {bad}")
        print("Data/ matches the generator")

    if args.check:
        env = dict(os.environ, TETMESHER_DIAGNOSE_FILES=":".join(offs))
        res = subprocess.run([args.check, "--gtest_filter=*CorpusFiles*"], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        for line in res.stdout.splitlines():
            if line.startswith("/") or "Failure" in line or "FAILED" in line:
                print(line)
        if res.returncode != 0:
            raise SystemExit("diagnosis found defects")


if __name__ == "__main__":
    sys.exit(main())
