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
