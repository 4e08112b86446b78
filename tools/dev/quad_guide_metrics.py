#!/usr/bin/env python3
"""How well a quad mesh follows the guides it was given (docs/design.md §15).

    quad_guide_metrics.py CUT.obj CUT.sharp QUADS.obj [--json OUT.json] [--max-distance 0.05]
                          [--max-angle 5] [--min-quad-angle 30]

CUT.obj/CUT.sharp are what mcon_cut_mesh_write_quadwild wrote (the triangle mesh and its guide
edges as QuadWild features); QUADS.obj is QuadWild's result. Guide edges are sampled at 4 points
each; for every sample the nearest quad edge gives a distance (reported in mean quad edge lengths)
and two angles (degrees, 0-90): to the guide edge itself (angle_*, the bound's measure) and to the
guide's tangent over two chain vertices each way (tangent_angle_*, reported only). Quads within two rings
of a guide (the quads owning a nearest edge, grown twice over shared vertices) are checked for a
corner angle under --min-quad-angle. Prints one JSON object; exit status 1 if a bound is missed
(all-quad, mean distance, mean angle, small angles near guides), 2 on unreadable input.
"""
import argparse
import json
import sys

import numpy as np


def read_obj(path):
    """Vertices (n, 3) and faces (lists of 0-based indices) of an OBJ; 'l' lines are ignored."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                faces.append([int(tok.split("/")[0]) - 1 for tok in line.split()[1:]])
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), faces


def read_sharp(path, faces):
    """Guide edges (k, 2) from a QuadWild .sharp: count, then 'kind,face,edge' per line."""
    with open(path) as f:
        lines = [l.strip() for l in f if l.strip()]
    count = int(lines[0])
    edges = []
    for l in lines[1 : 1 + count]:
        _, face, edge = (int(x) for x in l.split(","))
        tri = faces[face]
        edges.append((tri[edge], tri[(edge + 1) % len(tri)]))
    return np.array(edges, dtype=np.int64).reshape(-1, 2)


def quad_edges(faces):
    """Distinct edges (m, 2) of the quad mesh and, per edge, the faces that own it."""
    owner = {}
    for fi, f in enumerate(faces):
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            owner.setdefault((min(a, b), max(a, b)), []).append(fi)
    keys = list(owner)
    return np.array(keys, dtype=np.int64).reshape(-1, 2), [owner[k] for k in keys]


def chain_tangents(guides, cv, window=2):
    """Per guide edge a tangent of its guide smoothed over `window` chain vertices each way: the
    cut chain's own edges zig-zag a little across the mesh, the guide it stands for does not."""
    neighbours = {}
    for a, b in guides:
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)

    def walk(prev, at, steps):
        for _ in range(steps):
            nxt = [v for v in neighbours[at] if v != prev]
            if len(neighbours[at]) != 2 or not nxt:
                break  # an end, or a junction of several guides
            prev, at = at, nxt[0]
        return at

    out = np.zeros((len(guides), 3))
    for i, (a, b) in enumerate(guides):
        t = cv[walk(a, b, window)] - cv[walk(b, a, window)]
        n = np.linalg.norm(t)
        out[i] = t / n if n > 0 else (cv[b] - cv[a]) / np.linalg.norm(cv[b] - cv[a])
    return out


def nearest_edges(points, qv, qe, vertex_edges, k=8):
    """Per point the nearest quad edge among those incident to its k nearest quad vertices, and the
    distance to it (exact whenever the nearest edge has an end among those vertices)."""
    best_edge = np.zeros(len(points), dtype=np.int64)
    best_dist = np.full(len(points), np.inf)
    for start in range(0, len(points), 256):
        chunk = points[start : start + 256]
        d2 = ((chunk[:, None, :] - qv[None, :, :]) ** 2).sum(-1)
        near = np.argpartition(d2, min(k, len(qv) - 1), axis=1)[:, : min(k, len(qv))]
        for i, p in enumerate(chunk):
            cand = np.unique(np.concatenate([vertex_edges[v] for v in near[i]]))
            a, b = qv[qe[cand, 0]], qv[qe[cand, 1]]
            ab = b - a
            t = np.clip(((p - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0, 1)
            dist = np.linalg.norm(a + t[:, None] * ab - p, axis=1)
            j = int(np.argmin(dist))
            best_edge[start + i], best_dist[start + i] = cand[j], dist[j]
    return best_edge, best_dist


def corner_angles(qv, face):
    """Corner angles of one polygon in degrees."""
    out = []
    for k in range(len(face)):
        p, a, b = qv[face[k]], qv[face[k - 1]], qv[face[(k + 1) % len(face)]]
        u, w = a - p, b - p
        c = np.dot(u, w) / max(np.linalg.norm(u) * np.linalg.norm(w), 1e-300)
        out.append(np.degrees(np.arccos(np.clip(c, -1, 1))))
    return out


def metrics(cut_obj, cut_sharp, quads_obj, samples_per_edge=4):
    cv, cf = read_obj(cut_obj)
    guides = read_sharp(cut_sharp, cf)
    qv, qf = read_obj(quads_obj)
    if len(guides) == 0 or len(qf) == 0:
        raise ValueError("no guide edges in %s or no faces in %s" % (cut_sharp, quads_obj))
    qe, owners = quad_edges(qf)
    vertex_edges = [[] for _ in range(len(qv))]
    for e, (a, b) in enumerate(qe):
        vertex_edges[a].append(e)
        vertex_edges[b].append(e)
    vertex_edges = [np.array(x, dtype=np.int64) for x in vertex_edges]
    quad_edge_length = float(np.linalg.norm(qv[qe[:, 1]] - qv[qe[:, 0]], axis=1).mean())

    s = (np.arange(samples_per_edge) + 0.5) / samples_per_edge
    a, b = cv[guides[:, 0]], cv[guides[:, 1]]
    points = (a[:, None, :] + s[None, :, None] * (b - a)[:, None, :]).reshape(-1, 3)
    lengths = np.linalg.norm(b - a, axis=1)
    directions = np.repeat((b - a) / lengths[:, None], samples_per_edge, axis=0)
    weights = np.repeat(lengths, samples_per_edge)  # per unit of guide length
    edge, dist = nearest_edges(points, qv, qe, vertex_edges)
    qd = qv[qe[edge, 1]] - qv[qe[edge, 0]]
    qd /= np.linalg.norm(qd, axis=1)[:, None]
    angle = np.degrees(np.arccos(np.clip(np.abs((qd * directions).sum(1)), 0, 1)))
    tangents = np.repeat(chain_tangents(guides, cv), samples_per_edge, axis=0)
    smooth_angle = np.degrees(np.arccos(np.clip(np.abs((qd * tangents).sum(1)), 0, 1)))

    # Quads within two rings of a guide: the owners of nearest edges, grown twice over vertices.
    vertex_faces = [[] for _ in range(len(qv))]
    for fi, f in enumerate(qf):
        for v in f:
            vertex_faces[v].append(fi)
    near = set(fi for e in np.unique(edge) for fi in owners[e])
    for _ in range(2):
        near |= set(g for fi in list(near) for v in qf[fi] for g in vertex_faces[v])
    near_min = [min(corner_angles(qv, qf[fi])) for fi in sorted(near)]
    all_min = [min(corner_angles(qv, f)) for f in qf]
    sizes = np.array([len(f) for f in qf])
    return {
        "cut_mesh": cut_obj,
        "quads": quads_obj,
        "faces": int(len(qf)),
        "non_quad_faces": int((sizes != 4).sum()),
        "guide_edges": int(len(guides)),
        "samples": int(len(points)),
        "mean_quad_edge_length": quad_edge_length,
        "distance_mean": float(dist.mean() / quad_edge_length),
        "distance_median": float(np.median(dist) / quad_edge_length),
        "distance_p90": float(np.percentile(dist, 90) / quad_edge_length),
        "angle_mean": float(angle.mean()),
        "angle_median": float(np.median(angle)),
        "angle_p90": float(np.percentile(angle, 90)),
        "angle_length_mean": float((angle * weights).sum() / weights.sum()),
        "tangent_angle_length_mean": float((smooth_angle * weights).sum() / weights.sum()),
        "tangent_angle_mean": float(smooth_angle.mean()),
        "tangent_angle_median": float(np.median(smooth_angle)),
        "quads_near_guides": len(near_min),
        "min_quad_angle_near_guides": float(min(near_min)) if near_min else None,
        "quads_near_guides_under_30": int(sum(a < 30 for a in near_min)),
        "min_quad_angle": float(min(all_min)),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cut_obj")
    ap.add_argument("cut_sharp")
    ap.add_argument("quads_obj")
    ap.add_argument("--json", help="also write the JSON here")
    ap.add_argument("--max-distance", type=float, default=0.05)
    ap.add_argument("--max-angle", type=float, default=5.0)
    ap.add_argument("--min-quad-angle", type=float, default=30.0)
    args = ap.parse_args()
    try:
        m = metrics(args.cut_obj, args.cut_sharp, args.quads_obj)
    except (OSError, ValueError, IndexError) as e:
        print("quad_guide_metrics: %s" % e, file=sys.stderr)
        return 2
    failed = []
    if m["non_quad_faces"]:
        failed.append("%d faces are not quads" % m["non_quad_faces"])
    if m["distance_mean"] > args.max_distance:
        failed.append("mean distance %.3f > %.3f quad edges" % (m["distance_mean"], args.max_distance))
    if m["angle_mean"] > args.max_angle:
        failed.append("mean angle %.2f > %.2f degrees" % (m["angle_mean"], args.max_angle))
    if m["min_quad_angle_near_guides"] is not None and m["min_quad_angle_near_guides"] < args.min_quad_angle:
        failed.append("a quad near a guide has a %.1f degree corner (< %.0f)" % (m["min_quad_angle_near_guides"],
                                                                                  args.min_quad_angle))
    m["failed"] = failed
    text = json.dumps(m, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
