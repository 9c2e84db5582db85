"""An independent numpy implementation of the tet quality measures, for the Python tests.

Q = 2*sqrt(6) * r_in / l_max with r_in = 3 V / (sum of face areas); dihedral angles from
the face normals. Written separately from the C++ code on purpose.
"""
import numpy as np


def tet_quality(points, tets):
    """points (n,3), tets (m,4) in VTK order -> (Q, min dihedral, max dihedral) arrays."""
    p = points[tets]  # (m, 4, 3)
    a, b, c, d = p[:, 0], p[:, 1], p[:, 2], p[:, 3]
    volume = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0
    faces = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]  # opposite vertex 0..3
    normals = [np.cross(p[:, j] - p[:, i], p[:, k] - p[:, i]) for i, j, k in faces]
    area = sum(np.linalg.norm(n, axis=1) for n in normals) / 2.0
    edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    lengths = np.stack([np.linalg.norm(p[:, i] - p[:, j], axis=1) for i, j in edges], axis=1)
    q = np.where(volume > 0, 2 * np.sqrt(6) * (3 * volume / area) / lengths.max(axis=1), 0.0)
    angles = []
    for i, j in edges:
        k, l = [v for v in range(4) if v not in (i, j)]
        nk, nl = normals[k], normals[l]
        cos = np.einsum("ij,ij->i", nk, nl) / (np.linalg.norm(nk, axis=1) * np.linalg.norm(nl, axis=1))
        angles.append(180.0 - np.degrees(np.arccos(np.clip(cos, -1, 1))))
    angles = np.stack(angles, axis=1)
    return np.minimum(q, 1.0), angles.min(axis=1), angles.max(axis=1)
