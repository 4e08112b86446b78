"""Checks a .blend saved by macrocon_blender.py against its JSON summary (run inside Blender):

    blender -b OUT.blend --factory-startup --python-exit-code 1 --python samples/blender/check_blend.py -- SUMMARY.json

 - the host object has every attribute the summary lists, on the point domain;
 - macro_mask marks exactly the summary's host vertex count, and there the skin weights sum to 1
   (the starter library stores a partition of unity), uv lies in the unit disk;
 - the guides curve object has the summary's splines and points (closed ones cyclic);
 - the three suggestions are there, the first one chosen by default, the map has no flips.
"""
import json
import sys

import bpy
import numpy as np

summary = json.load(open(sys.argv[sys.argv.index("--") + 1]))
failures = []


def expect(cond, what):
    if not cond:
        failures.append(what)


obj = bpy.data.objects.get(summary["object"])
expect(obj is not None, f"object {summary['object']} missing")
if obj is not None:
    mesh = obj.data
    n = len(mesh.vertices)
    for name in summary["attributes"]:
        a = mesh.attributes.get(name)
        expect(a is not None and a.domain == "POINT", f"attribute {name} missing or not on points")

    def values(name, key="value", width=1):
        out = np.empty(n * width, np.float32)
        mesh.attributes[name].data.foreach_get(key, out)
        return out.reshape(n, width) if width > 1 else out

    mask = values("macro_mask") == 1
    expect(int(mask.sum()) == summary["host_vertices_with_fields"],
           f"macro_mask marks {int(mask.sum())} vertices, summary says {summary['host_vertices_with_fields']}")
    expect(mask.sum() >= 100, f"only {int(mask.sum())} vertices received fields")
    weights = [w for w in summary["attributes"] if w.startswith("skin_weight_")]
    expect(len(weights) >= 3, f"skin weights {weights}")
    total = sum(values(w) for w in weights)
    worst = float(np.abs(total[mask] - 1).max()) if mask.any() else 1.0
    expect(worst < 1e-4, f"skin weights sum to 1 only within {worst}")
    expect(float(np.abs(total[~mask]).max()) == 0.0, "skin weights outside the mask")
    if "uv" in summary["attributes"]:
        uv = values("uv", "vector", 2)
        expect(float((uv[mask] ** 2).sum(1).max()) <= 1 + 1e-5, "uv leaves the unit disk")

guides = summary["guides"]
if guides["splines"]:
    curve = bpy.data.objects.get(guides["object"])
    expect(curve is not None and curve.type == "CURVE", f"guide curve {guides['object']} missing")
    if curve is not None:
        splines = curve.data.splines
        expect(len(splines) == guides["splines"], f"{len(splines)} splines, summary says {guides['splines']}")
        expect(sum(len(s.points) for s in splines) == guides["points"], "guide point count differs")
        expect(sum(1 for s in splines if s.use_cyclic_u) == guides["closed"], "closed guide count differs")
expect(len(summary["suggestions"]) == 3, f"{len(summary['suggestions'])} suggestions")
expect(summary["chosen"] == summary["suggestions"][0]["id"], "the first suggestion was not the one applied")
expect(summary["map"]["flipped_triangles"] == 0, "the map has flipped triangles")
expect(all("example" in s["tags"] for s in summary["suggestions"]), "suggestions not tagged 'example'")

for f in failures:
    print("FAIL:", f)
print(f"check_blend: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
