"""Independent checks of a boundary-conforming tet mesh, for the Python and pvpython tests.

Written apart from the C++ code on purpose: exact orientation with Python's Fractions
(every double is a rational), face sets by sorted id triples, the enclosed volume of the
input surface by the divergence theorem.
"""
from collections import Counter
from fractions import Fraction

import numpy as np


def orient_exact(a, b, c, d):
    """Sign of det[b-a, c-a, d-a] (VTK orientation: > 0 for a valid VTK_TETRA), exactly."""
    a, b, c, d = ([Fraction(float(x)) for x in p] for p in (a, b, c, d))
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
           + u[2] * (v[0] * w[1] - v[1] * w[0]))
    return (det > 0) - (det < 0)


def enclosed_volume(points, triangles):
    """Signed volume bounded by outward-oriented triangles (divergence theorem), exactly."""
    total = Fraction(0)
    for t in triangles:
        a, b, c = ([Fraction(float(x)) for x in points[i]] for i in t)
        total += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                  + a[2] * (b[0] * c[1] - b[1] * c[0]))
    return total / 6


def tet_volume_exact(points, tet):
    a, b, c, d = ([Fraction(float(x)) for x in points[i]] for i in tet)
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6


def shells(triangles):
    """Triangles grouped into connected shells (by shared vertices): a list of index lists."""
    parent = {}

    def find(v):
        while parent.setdefault(v, v) != v:
            parent[v] = parent[parent[v]]
            v = parent[v]
        return v
    for a, b, c in triangles:
        for u, w in ((a, b), (b, c)):
            ru, rw = find(int(u)), find(int(w))
            if ru != rw:
                parent[ru] = rw
    groups = {}
    for i, t in enumerate(triangles):
        groups.setdefault(find(int(t[0])), []).append(i)
    return list(groups.values())


def check_boundary_mesh(in_points, in_triangles, out_points, tets, regions=None, expected_volume=None):
    """Returns a list of problems (empty: the mesh is exact). in_triangles (m,3), tets (k,4).
    expected_volume: what the tets must add up to, exactly (default: the volume enclosed by
    the input triangles, right for a single shell)."""
    problems = []
    n = len(in_points)
    if len(out_points) < n or not np.array_equal(np.asarray(out_points[:n]), np.asarray(in_points)):
        problems.append("output points 0..n-1 are not the input points bit for bit")
    # Faces of the mesh: a face seen once is on the boundary; a face between two regions too.
    face_tets = {}
    for t, tet in enumerate(tets):
        for f in range(4):
            key = tuple(sorted(int(tet[k]) for k in range(4) if k != f))
            face_tets.setdefault(key, []).append(t)
    if any(len(ts) > 2 for ts in face_tets.values()):
        problems.append("a face is shared by more than two tets")
    boundary = set()
    for key, ts in face_tets.items():
        if len(ts) == 1 or (regions is not None and regions[ts[0]] != regions[ts[1]]):
            boundary.add(key)
    wanted = Counter(tuple(sorted(int(v) for v in t)) for t in in_triangles)
    if set(wanted) != boundary:
        missing = set(wanted) - boundary
        extra = boundary - set(wanted)
        problems.append(f"boundary != input triangles: {len(missing)} missing (e.g. {sorted(missing)[:3]}), "
                        f"{len(extra)} extra (e.g. {sorted(extra)[:3]})")
    # Steiner points never on the input surface: none of them is a vertex of a boundary face.
    steiner_on_boundary = {v for key in boundary for v in key if v >= n}
    if steiner_on_boundary:
        problems.append(f"Steiner points on the boundary: {sorted(steiner_on_boundary)[:5]}")
    inverted = [t for t, tet in enumerate(tets) if orient_exact(*(out_points[v] for v in tet)) <= 0]
    if inverted:
        problems.append(f"{len(inverted)} tets not positively oriented (e.g. {inverted[:5]})")
    total = sum((tet_volume_exact(out_points, tet) for tet in tets), Fraction(0))
    expected = enclosed_volume(in_points, in_triangles) if expected_volume is None else expected_volume
    if total != expected:
        problems.append(f"tet volumes sum to {float(total)!r}, expected exactly {float(expected)!r}")
    return problems
