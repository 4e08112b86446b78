"""Runs the add-on's authoring operator headless and checks the library it writes (run in Blender):

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/check_author.py -- \
        BODY.obj.gz OUT.mclb

Loads the body, adds point attributes (height = the vertex's y; side = 1 or 2 by the sign of x),
selects the edges of a path across the nose and one across the left eye, puts the 3D cursor on
the nose tip and runs `mesh.macrocon_author` (class nose, fields height and side); then again with
the cursor on the eye, appending to the same file. Checks with the Python binding: two entries;
the nose entry's guide lies on the selected path and leaves the eye path out; its fields hold the
host's values (blended on host edges). MACROCON_LIBRARY / MACROCON_PYTHON_PATH as for the add-on.
"""
import json
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(HERE, "..", "..", "tests", "scripts")]
import macrocon_blender  # noqa: E402
from edge_paths import shortest_edge_path  # noqa: E402

BODY, OUT = sys.argv[sys.argv.index("--") + 1:][:2]
NOSE, EYE = 297, 8021  # file vertices (0-based), as in the other samples
failures = []


def expect(cond, what):
    if not cond:
        failures.append(what)


def main():
    if os.path.exists(OUT):
        os.remove(OUT)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    macrocon_blender.register()
    obj = macrocon_blender.load_obj_object(BODY, "body")
    bpy.context.view_layer.objects.active = obj
    mesh = obj.data
    n = len(mesh.vertices)
    co = np.empty(n * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(n, 3).astype(np.float64)
    mesh.attributes.new("height", "FLOAT", "POINT").data.foreach_set("value", co[:, 1].astype(np.float32))
    mesh.attributes.new("side", "INT", "POINT").data.foreach_set("value", np.where(co[:, 0] >= 0, 1, 2).astype(np.int32))
    edges = [tuple(e.vertices) for e in mesh.edges]
    near = lambda v, d: int(np.argmin(((co - (co[v] + np.array(d))) ** 2).sum(1)))
    nose_path = shortest_edge_path(co, edges, near(NOSE, [-0.25, 0, 0]), near(NOSE, [0.25, 0, 0]))
    eye_path = shortest_edge_path(co, edges, near(EYE, [-0.2, 0, 0]), near(EYE, [0.2, 0, 0]))
    wanted = {frozenset(p) for path in (nose_path, eye_path) for p in zip(path, path[1:])}
    for e in mesh.edges:
        e.select = frozenset(e.vertices) in wanted

    results = []
    for center, radius, label in ((NOSE, 0.5, "nose"), (EYE, 0.6, "eye")):
        bpy.context.scene.cursor.location = obj.matrix_world @ mesh.vertices[center].co
        r = bpy.ops.mesh.macrocon_author(library_path=OUT, radius=radius, class_label=label,
                                         entry_name=label + "_blender", fields="height,side")
        expect(r == {"FINISHED"}, f"macrocon_author ({label}) returned {r}")
        summary = json.loads(bpy.context.scene["macrocon_last_author"])
        print(json.dumps(summary))
        results.append(summary)
    nose, eye = results
    expect(nose["vertex"] == NOSE and eye["vertex"] == EYE, "the 3D cursor did not pick the vertex under it")
    expect(nose["guides"] == 1 and eye["guides"] == 1, "each entry should keep its own path as one guide")
    expect(nose["selected_vertices_outside"] >= len(eye_path), "the eye path was not left out of the nose")
    expect(eye["entries"] == 2, "the second entry was not appended")

    import macrocon

    with macrocon.Context() as ctx, macrocon.Library.open(ctx, OUT) as lib:
        expect(len(lib) == 2, f"{len(lib)} entries in the file")
        entry = lib.entry("nose_blender")
        info = entry.info
        host = np.array(info.source_origin) + info.source_scale * entry.positions
        fields = entry.fields
        expect(sorted(fields) == ["height", "side"], f"fields {sorted(fields)}")
        err = float(np.abs(fields["height"].values[:, 0] - host[:, 1]).max())
        expect(err < 1e-5, f"height differs from the host's y by {err}")
        away = np.abs(host[:, 0]) > 0.06
        wrong = int((fields["side"].values[away, 0] != np.where(host[away, 0] >= 0, 1, 2)).sum())
        expect(wrong == 0, f"{wrong} side labels wrong away from the midline")
        guide = entry.polylines[0]
        points = np.einsum("nk,nkd->nd", guide.barycentric, host[entry.triangles[guide.faces]])
        off = float(np.min(np.linalg.norm(points[:, None] - co[nose_path][None], axis=2), axis=1).max())
        expect(off < 1e-5 and len(points) >= 5, f"the guide ({len(points)} points) is {off} off the selected path")
        print(f"nose entry: {info.vertex_count} vertices, guide of {len(points)} points ({off:.1e} off the path), "
              f"height error {err:.1e}")
    macrocon.shutdown()
    for f in failures:
        print("FAIL:", f)
    print(f"check_author: {len(failures)} failure(s)")
    sys.exit(1 if failures else 0)


main()
