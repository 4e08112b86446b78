#!/usr/bin/env python3
"""Checks a host PLY written by a transfer sample (C, C++, Python, C#): the transferred fields are
where they should be and keep the properties the starter library gave them.

    check_transfer_output.py OUT.ply [--min-vertices N] [--guides G.obj] [--rosy R.rosy --region R.obj]

 - macro_mask marks at least N host vertices (default 100);
 - on those vertices the skin weights (skin_weight_center + skin_weight_0..2) sum to 1: the
   starter library stores a partition of unity and interpolation keeps it;
 - uv lies in the closed unit disk, the colour in [0, 1] (PLY bytes), region labels in 0..5;
 - off the mask every transferred value is 0 (nothing leaks outside the region);
 - --guides: the OBJ has at least one 'l' polyline, every index names one of its vertices;
 - --rosy with --region: a QuadWild .rosy with symmetry 4 and one unit direction per region
   triangle, each tangent to its triangle (|d . n| small).
Exit status 0 if all hold; otherwise each failure is printed.
"""
import gzip
import sys


def read_ascii_ply(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        if f.readline().strip() != "ply":
            raise SystemExit(f"{path}: not a PLY file")
        names, count = [], None
        element = None
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "format" and words[1] != "ascii":
                raise SystemExit(f"{path}: only ASCII PLY is checked here")
            if words[0] == "element":
                element = words[1]
                if element == "vertex":
                    count = int(words[2])
            elif words[0] == "property" and element == "vertex":
                names.append(words[-1])
            elif words[0] == "end_header":
                break
        rows = [list(map(float, f.readline().split()[: len(names)])) for _ in range(count)]
    return names, rows


def read_obj(path):
    verts, faces, lines = [], [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append(tuple(map(float, w[1:4])))
            elif w[0] == "f":
                faces.append([int(x.split("/")[0]) - 1 for x in w[1:]])
            elif w[0] == "l":
                lines.append([int(x) - 1 for x in w[1:]])
    return verts, faces, lines


def check_guides(path):
    verts, _, lines = read_obj(path)
    if not lines:
        return [f"{path}: no polyline"]
    if any(i < 0 or i >= len(verts) for l in lines for i in l):
        return [f"{path}: a polyline index is out of range"]
    if any(len(l) < 2 for l in lines):
        return [f"{path}: a polyline with fewer than 2 points"]
    return []


def check_rosy(rosy_path, region_path):
    verts, faces, _ = read_obj(region_path)
    with open(rosy_path) as f:
        words = f.read().split()
    count, symmetry = int(words[0]), int(words[1])
    out = []
    if count != len(faces) or symmetry != 4:
        return [f"{rosy_path}: {count} directions, symmetry {symmetry}; the region has {len(faces)} triangles"]
    worst_norm = worst_normal = 0.0
    for i, face in enumerate(faces):
        d = [float(x) for x in words[2 + 3 * i: 5 + 3 * i]]
        a, b, c = (verts[k] for k in face)
        u = [b[j] - a[j] for j in range(3)]
        v = [c[j] - a[j] for j in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        nn = sum(x * x for x in n) ** 0.5
        dn = sum(x * x for x in d) ** 0.5
        worst_norm = max(worst_norm, abs(dn - 1))
        if nn > 0:
            worst_normal = max(worst_normal, abs(sum(d[j] * n[j] for j in range(3))) / nn)
    if worst_norm > 1e-4:  # the file has 6 decimals
        out.append(f"{rosy_path}: directions are not unit vectors (off by {worst_norm:.2g})")
    if worst_normal > 1e-3:
        out.append(f"{rosy_path}: directions leave their triangle's plane (|d.n| up to {worst_normal:.2g})")
    return out


def main():
    path = sys.argv[1]
    min_vertices = 100
    if "--min-vertices" in sys.argv:
        min_vertices = int(sys.argv[sys.argv.index("--min-vertices") + 1])
    names, rows = read_ascii_ply(path)
    col = {n: i for i, n in enumerate(names)}
    failures = []
    needed = ["macro_mask", "uv_0", "uv_1", "skin_weight_center", "skin_weight_0", "skin_weight_1",
              "skin_weight_2", "red", "green", "blue", "region"]
    missing = [n for n in needed if n not in col]
    if missing:
        raise SystemExit(f"{path}: missing vertex properties {missing} (has {names})")
    weights = ["skin_weight_center", "skin_weight_0", "skin_weight_1", "skin_weight_2"]
    masked = [r for r in rows if r[col["macro_mask"]] == 1.0]
    if len(masked) < min_vertices:
        failures.append(f"only {len(masked)} host vertices received fields (expected >= {min_vertices})")
    worst_sum = max((abs(sum(r[col[w]] for w in weights) - 1.0) for r in masked), default=0.0)
    if worst_sum > 1e-4:
        failures.append(f"skin weights do not sum to 1 on the region (worst deviation {worst_sum:.3g})")
    worst_uv = max((r[col["uv_0"]] ** 2 + r[col["uv_1"]] ** 2 for r in masked), default=0.0)
    if worst_uv > 1.0 + 1e-5:
        failures.append(f"uv leaves the unit disk (|uv|^2 up to {worst_uv:.6f})")
    labels = {r[col["region"]] for r in masked}
    if not labels <= {0.0, 1.0, 2.0, 3.0, 4.0, 5.0}:
        failures.append(f"region labels outside 0..5: {sorted(labels)}")
    if len(labels) < 2:
        failures.append(f"the region label is constant ({sorted(labels)}): the transfer lost its structure")
    leaks = [r for r in rows if r[col["macro_mask"]] != 1.0 and any(r[col[w]] != 0.0 for w in weights)]
    if leaks:
        failures.append(f"{len(leaks)} vertices outside the mask carry skin weights")
    if any(not (0 <= r[col[c]] <= 255) for r in masked for c in ("red", "green", "blue")):
        failures.append("colour bytes out of range")
    if "--guides" in sys.argv:
        failures += check_guides(sys.argv[sys.argv.index("--guides") + 1])
    if "--rosy" in sys.argv and "--region" in sys.argv:
        failures += check_rosy(sys.argv[sys.argv.index("--rosy") + 1], sys.argv[sys.argv.index("--region") + 1])
    for f in failures:
        print(f"FAIL {path}: {f}")
    if not failures:
        print(f"ok {path}: {len(masked)} host vertices, skin weights sum to 1 within {worst_sum:.2g}, "
              f"{len(labels)} region labels")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
