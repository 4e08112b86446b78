"""Shortest paths along mesh edges (Dijkstra): polylines that lie exactly on a surface, for the
authoring tests (check_cli_authoring.py and samples/blender/check_author.py)."""
import heapq

import numpy as np


def shortest_edge_path(positions, edges, a, b):
    """Vertices from a to b along `edges` ((u, w) pairs), shortest by edge length."""
    neighbours = {}
    for u, w in edges:
        neighbours.setdefault(u, set()).add(w)
        neighbours.setdefault(w, set()).add(u)
    dist, back, heap = {a: 0.0}, {}, [(0.0, a)]
    while heap:
        d, u = heapq.heappop(heap)
        if u == b:
            break
        if d > dist[u]:
            continue
        for w in neighbours[u]:
            nd = d + float(np.linalg.norm(positions[u] - positions[w]))
            if nd < dist.get(w, np.inf):
                dist[w], back[w] = nd, u
                heapq.heappush(heap, (nd, w))
    path = [b]
    while path[-1] != a:
        path.append(back[path[-1]])
    return path[::-1]
