"""Independent measurements of quad meshes with numpy (SVD and least squares),
sharing no code with monge: each returns the worst value relative to the
bounding-box diagonal of the points (dimensionless for unit lengths)."""

import numpy as np


def scale(vertices):
    """The bounding-box diagonal."""
    p = vertices.reshape(-1, 3)
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def faces(vertices):
    """The quads (F, 4, 3) in cyclic order (i, j), (i+1, j), (i+1, j+1), (i, j+1)."""
    v = vertices
    quads = np.stack([v[:-1, :-1], v[1:, :-1], v[1:, 1:], v[:-1, 1:]], axis=2)
    return quads.reshape(-1, 4, 3)


def plane_distances(points):
    """Per point set (…, n, 3): largest distance from its least-squares plane (SVD)."""
    centred = points - points.mean(axis=-2, keepdims=True)
    _, _, vt = np.linalg.svd(centred)
    normal = vt[..., -1, :]
    return np.abs(np.einsum("...ij,...j->...i", centred, normal)).max(axis=-1)


def face_planarity(vertices):
    return float(plane_distances(faces(vertices)).max()) / scale(vertices)


def circularity(vertices):
    """Largest deviation of a face corner from the least-squares circle of the
    face in its plane: solve x² + y² + a·x + b·y + c = 0 in plane coordinates."""
    quads = faces(vertices)
    worst = 0.0
    for q in quads:
        centre = q.mean(axis=0)
        _, _, vt = np.linalg.svd(q - centre)
        xy = (q - centre) @ vt[:2].T
        a = np.column_stack([xy, np.ones(4)])
        coef, *_ = np.linalg.lstsq(a, -(xy**2).sum(axis=1), rcond=None)
        c = -coef[:2] / 2
        r = np.sqrt(c @ c - coef[2])
        worst = max(worst, float(np.abs(np.linalg.norm(xy - c, axis=1) - r).max()))
    return worst / scale(vertices)


def line_planarity(vertices):
    """Largest distance of a vertex from the plane of its row or column."""
    rows = plane_distances(vertices).max() if vertices.shape[1] > 3 else 0.0
    cols = plane_distances(vertices.transpose(1, 0, 2)).max() if vertices.shape[0] > 3 else 0.0
    return float(max(rows, cols)) / scale(vertices)


def torsion(vertices, normals):
    """Node axes of neighbours are coplanar: |(q − p)·(n_p × n_q)| / |q − p|."""
    worst = 0.0
    for axis in (0, 1):
        p, q = (vertices[:-1], vertices[1:]) if axis == 0 else (vertices[:, :-1], vertices[:, 1:])
        n, m = (normals[:-1], normals[1:]) if axis == 0 else (normals[:, :-1], normals[:, 1:])
        e = q - p
        t = np.abs(np.einsum("...i,...i", e, np.cross(n, m))) / np.linalg.norm(e, axis=-1)
        worst = max(worst, float(t.max()))
    return worst


def face_normals(vertices):
    """Unit normals (rows − 1, cols − 1, 3) of the faces' least-squares planes."""
    r, c = vertices.shape[0] - 1, vertices.shape[1] - 1
    q = faces(vertices)
    _, _, vt = np.linalg.svd(q - q.mean(axis=1, keepdims=True))
    n = vt[:, -1, :]
    # orient like the diagonals' cross product
    d = np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])
    n *= np.sign(np.einsum("ij,ij->i", n, d))[:, None]
    return n.reshape(r, c, 3)


def conical(vertices):
    """At every interior vertex the four face normals lie on a circle of the unit
    sphere (a cone of normals): their tips are coplanar."""
    n = face_normals(vertices)
    around = np.stack([n[:-1, :-1], n[1:, :-1], n[1:, 1:], n[:-1, 1:]], axis=2)
    return float(plane_distances(around).max())
