#!/usr/bin/env python3
"""Macrocon sample (Python binding): the integration pattern of a DCC plugin.

    transfer_fields.py LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT.ply [--guides OUT.obj] [--rosy OUT.rosy]

1. the host mesh (numpy arrays; a plugin takes them from its host application) -> macrocon.Mesh
2. the user's region (a vertex + a geodesic radius) -> a normalized disk patch
3. query the constraint library for the three most similar macro constraints
4. re-embed the best one onto the region (macrocon.Map.compute)
5. transfer its per-vertex fields (uv, skin weights, colour, labels), guides and a cross field
6. write the fields back onto the host vertices (here a PLY file; a plugin sets mesh attributes)

Errors are macrocon.Error subclasses carrying the status and the SDK's message (NotADiskError: ask
the user for a smaller radius; InvalidLibraryError: a corrupt or foreign library file). Handles are
context managers; macrocon.shutdown() also runs at interpreter exit.

Run with Debian's /usr/bin/python3 (numpy) and the binding on PYTHONPATH; MACROCON_LIBRARY names
libmacrocon.so unless the package bundles it (wheel).
"""
import argparse
import gzip
import sys

import numpy as np

import macrocon


def load_obj(path):
    """(positions (n, 3) float32, triangles (m, 3) uint32); polygons are fanned, vertex numbers kept."""
    opener = gzip.open if path.endswith(".gz") else open
    positions, triangles = [], []
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                corners = [int(w.split("/")[0]) for w in line.split()[1:]]
                corners = [c - 1 if c > 0 else len(positions) + c for c in corners]
                triangles.extend([corners[0], corners[k], corners[k + 1]] for k in range(1, len(corners) - 1))
    return np.asarray(positions, np.float32), np.asarray(triangles, np.uint32)


def entry_patch(context, entry):
    """A library entry as a macrocon.Patch (its arrays, center and frame)."""
    info = entry.info
    return macrocon.Patch.from_arrays(context, entry.positions, entry.triangles, info.center_face,
                                      info.center_barycentric, info.source_origin, info.source_scale)


def suggest_and_transfer(context, library, host_mesh, center_vertex, radius, top=3):
    """Query, re-embed the best match and transfer everything onto the region.

    Returns a dict: region (Patch), suggestions [(id, class, distance, name)], map_info, fields
    {name: (kind, values per region vertex)}, outside (bool per region vertex), guides (PolylineSet),
    directions (cross field per region triangle), licence, author.
    """
    region = macrocon.Patch.extract(host_mesh, radius, center_vertex=center_vertex)
    result = library.query(region, n=top)
    suggestions = []
    for entry_id, index, distance in zip(result.ids, result.indices, result.distances):
        e = library.entry(int(index))
        suggestions.append((int(entry_id), e.class_label, float(distance), e.name))
    best = library.entry(int(result.indices[0]))
    source = entry_patch(context, best)
    phi = macrocon.Map.compute(source, region)  # seed 0: the same map on every run and thread count
    fields = {}
    for field in best.fields.values():
        if field.kind == macrocon.FieldKind.INTEGER_LABEL:
            fields[field.name] = (field.kind, phi.transfer_labels(field.values))  # never blended
        else:
            fields[field.name] = (field.kind, phi.transfer_field(field.values, field.kind))
    guides = phi.transfer_polylines(best.polylines)
    directions, _confidence = region.cross_field(guides)
    return {
        "region": region, "source": source, "map": phi, "suggestions": suggestions, "map_info": phi.info,
        "fields": fields, "outside": phi.outside_mask, "guides": guides, "directions": directions,
        "licence": best.licence, "author": best.author,
    }


def to_host(region, values, outside, host_vertex_count):
    """Region-vertex values -> host vertices: a region vertex that is a host vertex (v0 == v1,
    t == 0) carries its value back; vertices the cut made on host edges are skipped."""
    v0, v1, t = region.host_vertices
    keep = (v0 == v1) & (v0 != 0xFFFFFFFF) & (t == 0) & ~outside
    out = np.zeros((host_vertex_count,) + values.shape[1:], np.float64)
    out[v0[keep]] = values[keep]
    mask = np.zeros(host_vertex_count)
    mask[v0[keep]] = 1.0
    return out, mask


def write_ply(path, positions, triangles, attributes):
    """ASCII PLY; attributes: [(name, (n, d) array)]; 'color' becomes red/green/blue bytes."""
    names, columns = [], []
    for name, a in attributes:
        a = a.reshape(len(positions), -1)
        if name == "color":
            names += ["uchar red", "uchar green", "uchar blue"]
            columns.append(np.clip(np.rint(a * 255), 0, 255))
        elif a.shape[1] == 1:
            names.append(f"float {name}")
            columns.append(a)
        else:
            names += [f"float {name}_{c}" for c in range(a.shape[1])]
            columns.append(a)
    table = np.hstack([positions.astype(np.float64)] + columns)
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\ncomment written by the Macrocon Python sample\nelement vertex {len(positions)}\n")
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.writelines(f"property {n}\n" for n in names)
        f.write(f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n")
        for row in table:
            f.write(" ".join(f"{x:.9g}" for x in row) + "\n")
        for t in triangles:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("library")
    p.add_argument("host")
    p.add_argument("center_vertex", type=int)
    p.add_argument("radius", type=float)
    p.add_argument("out")
    p.add_argument("--guides", help="write the transferred guides as OBJ polylines")
    p.add_argument("--rosy", help="write the region's cross field (QuadWild .rosy)")
    args = p.parse_args(argv)

    positions, triangles = load_obj(args.host)
    try:
        with macrocon.Context() as context, macrocon.Library.open(context, args.library) as library:
            host = macrocon.Mesh(context, positions, triangles)
            r = suggest_and_transfer(context, library, host, args.center_vertex, args.radius)
            region_info = r["region"].info
            print(f"region: vertex {args.center_vertex}, radius {args.radius}: {region_info.vertex_count} vertices")
            for i, (entry_id, klass, distance, name) in enumerate(r["suggestions"], 1):
                print(f"suggestion {i}: id {entry_id}, class {klass}, distance {distance:.4f}: {name}")
            print(f"using entry {r['suggestions'][0][0]} by {r['author']}, licence {r['licence']}")
            m = r["map_info"]
            print(f"map: overlap {m.overlap_ratio:.3f}, matching score {m.matching_score:.3f}, {m.iterations} iterations, "
                  f"{'mirrored' if m.reflected else 'not mirrored'}, {m.flipped_triangles} flipped triangles")
            attributes, mask = [], None
            for name, (kind, values) in r["fields"].items():
                host_values, mask = to_host(r["region"], values.astype(np.float64), r["outside"], len(positions))
                attributes.append((name, host_values))
            write_ply(args.out, positions, triangles, [("macro_mask", mask)] + attributes)
            n_lines, n_points = r["guides"].counts
            if args.guides:
                sizes, closed, _ = r["guides"].polyline_arrays()
                _, _, xyz = r["guides"].point_arrays()
                with open(args.guides, "w") as f:
                    f.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in xyz)
                    start = 1
                    for size, c in zip(sizes, closed):
                        ids = list(range(start, start + int(size))) + ([start] if c else [])
                        f.write("l " + " ".join(map(str, ids)) + "\n")
                        start += int(size)
            if args.rosy:
                r["region"].write_rosy(r["directions"], args.rosy)
            print(f"transferred {len(attributes)} field(s) onto {int(mask.sum())} host vertices, "
                  f"{n_lines} guide polyline(s) -> {args.out}")
            for key in ("map", "guides", "source", "region"):
                r[key].close()
            host.close()
    except macrocon.NotADiskError as e:
        print(f"transfer_fields: the region is not a disk, try a smaller radius: {e}", file=sys.stderr)
        return 1
    except macrocon.Error as e:
        print(f"transfer_fields: {e}", file=sys.stderr)
        return 1
    macrocon.shutdown()  # also registered at exit; calling it explicitly is harmless
    return 0


if __name__ == "__main__":
    sys.exit(main())
