import numpy as np
import pytest


def grid(n: int = 31, size: float = 1.0, dtype=np.float64):
    """n x n vertex grid on [0, size]^2, two triangles per cell, counter-clockwise."""
    xs = np.linspace(0.0, size, n)
    x, y = np.meshgrid(xs, xs)
    positions = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1).astype(dtype)
    cells = np.arange(n * n).reshape(n, n)[:-1, :-1].ravel()
    a, b, c, d = cells, cells + 1, cells + n + 1, cells + n
    triangles = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.uint32)
    return positions, triangles


@pytest.fixture
def context():
    import macrocon

    with macrocon.Context(max_threads=2) as ctx:
        yield ctx


def bumpy(n: int = 41, dtype=np.float64):
    """The grid of `grid` lifted to an asymmetric height field (curvature for the descriptors; no
    symmetry, so a map of a patch onto itself has one best answer: the identity)."""
    p, t = grid(n, dtype=np.float64)
    x, y = p[:, 0], p[:, 1]
    p[:, 2] = 0.15 * np.sin(5.0 * x + 1.0) * np.cos(3.0 * y) + 0.1 * x * x * y + 0.05 * np.sin(9.0 * x * y)
    return p.astype(dtype), t


def vertex_normals(p: np.ndarray, t: np.ndarray) -> np.ndarray:
    n = np.zeros_like(p)
    fn = np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])
    for k in range(3):
        np.add.at(n, t[:, k], fn)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


@pytest.fixture
def host(context):
    """A bumpy host mesh and its arrays."""
    import macrocon

    p, t = bumpy(41)
    with macrocon.Mesh(context, p, t) as mesh:
        yield mesh, p, t


def center(n: int, i: int, j: int) -> int:
    return j * n + i
