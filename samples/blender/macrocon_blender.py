"""Macrocon for Blender: suggest macro constraints at a vertex and re-embed one (add-on + headless script).

Headless (CI, pipelines):

    blender -b --factory-startup --python-exit-code 1 --python samples/blender/macrocon_blender.py -- \
        --library build/share/macrocon/starter.mclb --mesh samples/data/makehuman-body.obj.gz \
        --vertex 8021 --radius 0.55 --out /tmp/macrocon.blend [--json summary.json] [--choice 0]

loads the mesh (OBJ, optionally .gz; vertex numbers are the file's) or, without --mesh, uses the
active object; suggests the top-3 macro constraints of the library for the geodesic disk of
--radius around --vertex; re-embeds suggestion --choice (default the first); stores the transferred
per-vertex fields as mesh attributes (point domain: FLOAT, FLOAT2 for uv, FLOAT_COLOR for colours,
FLOAT_VECTOR for vectors, INT for labels, plus a "macro_mask"), the guides and features as a
curve object and the singularities as a vertex-only mesh object; saves the .blend and prints a
JSON summary (also written to --json).

Inside Blender: install this file as an add-on (see samples/blender/README.md); the 3D view's
sidebar gets a "Macrocon" tab.

The SDK comes in through its Python binding: the folder holding the `macrocon` package is taken
from --binding, the add-on preference, or the MACROCON_PYTHON_PATH environment variable, and
libmacrocon.so from MACROCON_LIBRARY (or next to the package, as the wheel installs it).
"""
import gzip
import json
import os
import sys
import time

import bpy
import numpy as np

bl_info = {
    "name": "Macrocon macro constraints",
    "author": "Macrocon",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Macrocon",
    "description": "Suggest and re-embed macro constraints (guides, fields) from a constraint library",
    "category": "Mesh",
}


def import_macrocon(binding_dir=None):
    """The binding package; binding_dir (or MACROCON_PYTHON_PATH) is put on sys.path first."""
    for d in (binding_dir, os.environ.get("MACROCON_PYTHON_PATH")):
        if d and d not in sys.path:
            sys.path.insert(0, d)
    import macrocon  # noqa: E402 - after the path is set

    return macrocon


# ---- mesh in and out ----------------------------------------------------------------------------


def load_obj_object(path, name="host"):
    """An OBJ (optionally .gz) as a new mesh object; polygons and vertex order as in the file."""
    opener = gzip.open if path.endswith(".gz") else open
    verts, faces = [], []
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("v "):
                verts.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                c = [int(w.split("/")[0]) for w in line.split()[1:]]
                faces.append([i - 1 if i > 0 else len(verts) + i for i in c])
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.validate()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def mesh_arrays(mesh):
    """(positions (n, 3) float32, triangles (m, 3) uint32) of a Blender mesh, in object space."""
    n = len(mesh.vertices)
    positions = np.empty(n * 3, np.float32)
    mesh.vertices.foreach_get("co", positions)
    mesh.calc_loop_triangles()
    tris = np.empty(len(mesh.loop_triangles) * 3, np.int32)
    mesh.loop_triangles.foreach_get("vertices", tris)
    return positions.reshape(n, 3), tris.astype(np.uint32).reshape(-1, 3)


def set_point_attribute(mesh, name, values, kind):
    """Stores per-vertex values (n, d) as a point-domain attribute of the matching type."""
    import macrocon

    if name in mesh.attributes:
        mesh.attributes.remove(mesh.attributes[name])
    d = values.shape[1]
    if kind == macrocon.FieldKind.INTEGER_LABEL and d == 1:
        attr = mesh.attributes.new(name, "INT", "POINT")
        attr.data.foreach_set("value", values[:, 0].astype(np.int32))
    elif kind == macrocon.FieldKind.VECTOR3 and name.startswith("colo"):
        attr = mesh.attributes.new(name, "FLOAT_COLOR", "POINT")
        rgba = np.hstack([np.clip(values, 0, 1), np.ones((len(values), 1))]).astype(np.float32)
        attr.data.foreach_set("color", rgba.ravel())
    elif d == 3:
        attr = mesh.attributes.new(name, "FLOAT_VECTOR", "POINT")
        attr.data.foreach_set("vector", values.astype(np.float32).ravel())
    elif d == 2:
        attr = mesh.attributes.new(name, "FLOAT2", "POINT")
        attr.data.foreach_set("vector", values.astype(np.float32).ravel())
    elif d == 1:
        attr = mesh.attributes.new(name, "FLOAT", "POINT")
        attr.data.foreach_set("value", values[:, 0].astype(np.float32))
    else:  # more channels than an attribute type holds: one FLOAT attribute per channel
        for c in range(d):
            set_point_attribute(mesh, f"{name}_{c}", values[:, c:c + 1], macrocon.FieldKind.SCALAR)
        return [f"{name}_{c}" for c in range(d)]
    return [name]


def polylines_object(name, sizes, closed, xyz, matrix):
    """The transferred polylines as one curve object (a POLY spline per polyline)."""
    curve = bpy.data.curves.new(name, "CURVE")
    curve.dimensions = "3D"
    start = 0
    for size, is_closed in zip(sizes, closed):
        spline = curve.splines.new("POLY")
        spline.points.add(int(size) - 1)
        pts = np.hstack([xyz[start:start + int(size)], np.ones((int(size), 1))]).astype(np.float32)
        spline.points.foreach_set("co", pts.ravel())
        spline.use_cyclic_u = bool(is_closed)
        start += int(size)
    obj = bpy.data.objects.new(name, curve)
    obj.matrix_world = matrix
    bpy.context.scene.collection.objects.link(obj)
    return obj


def points_object(name, xyz, index_quarters, matrix):
    """Singularities as a vertex-only mesh with an INT attribute index_quarters (+1 = valence 3)."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(p) for p in xyz], [], [])
    attr = mesh.attributes.new("index_quarters", "INT", "POINT")
    attr.data.foreach_set("value", np.asarray(index_quarters, np.int32))
    obj = bpy.data.objects.new(name, mesh)
    obj.matrix_world = matrix
    bpy.context.scene.collection.objects.link(obj)
    return obj


# ---- the job --------------------------------------------------------------------------------------


def suggest(macrocon, context, library, host_mesh, vertex, radius, top=3):
    """(region patch, [suggestion dicts]) for the disk of `radius` around `vertex`."""
    region = macrocon.Patch.extract(host_mesh, radius, center_vertex=vertex)
    result = library.query(region, n=top)
    suggestions = []
    for entry_id, index, distance in zip(result.ids, result.indices, result.distances):
        e = library.entry(int(index))
        suggestions.append({"id": int(entry_id), "index": int(index), "class": e.class_label, "name": e.name,
                            "distance": float(distance), "licence": e.licence, "author": e.author,
                            "tags": e.tags})
    return region, suggestions


def apply_suggestion(macrocon, context, library, obj, region, suggestion):
    """Re-embeds one suggestion onto the region and writes its fields and constraints into Blender."""
    entry = library.entry(suggestion["index"])
    info = entry.info
    source = macrocon.Patch.from_arrays(context, entry.positions, entry.triangles, info.center_face,
                                        info.center_barycentric, info.source_origin, info.source_scale)
    phi = macrocon.Map.compute(source, region)
    mesh = obj.data
    n_host = len(mesh.vertices)
    v0, v1, t = region.host_vertices
    outside = phi.outside_mask
    # Region vertices that are host vertices carry values back; cut vertices on host edges do not.
    keep = (v0 == v1) & (v0 != 0xFFFFFFFF) & (t == 0) & ~outside
    host_index = v0[keep]
    mask = np.zeros((n_host, 1))
    mask[host_index] = 1
    attributes = set_point_attribute(mesh, "macro_mask", mask, macrocon.FieldKind.SCALAR)
    for field in entry.fields.values():
        if field.kind == macrocon.FieldKind.INTEGER_LABEL:
            values = phi.transfer_labels(field.values)
        else:
            values = phi.transfer_field(field.values, field.kind)
        host_values = np.zeros((n_host, values.shape[1]), values.dtype)
        host_values[host_index] = values[keep]
        attributes += set_point_attribute(mesh, field.name, host_values, field.kind)

    summary = {"attributes": attributes, "host_vertices_with_fields": int(keep.sum())}
    polylines = entry.polylines
    guides = phi.transfer_polylines(polylines) if polylines else None
    if guides is not None and guides.counts[0] > 0:
        sizes, closed, _ = guides.polyline_arrays()
        _, _, xyz = guides.point_arrays()
        curve = polylines_object(f"macrocon_guides_{suggestion['class']}", sizes, closed, xyz, obj.matrix_world)
        summary["guides"] = {"object": curve.name, "splines": len(sizes), "points": int(sizes.sum()),
                             "closed": int(closed.sum())}
    else:
        summary["guides"] = {"object": None, "splines": 0, "points": 0, "closed": 0}
    sing = entry.singularities
    if len(sing.index_quarters):
        tri, _, xyz = phi.transfer_points(sing.faces, sing.barycentric)
        inside = tri != 0xFFFFFFFF
        if inside.any():
            points_object("macrocon_singularities", xyz[inside], sing.index_quarters[inside], obj.matrix_world)
        summary["singularities"] = int(inside.sum())
    else:
        summary["singularities"] = 0
    m = phi.info
    summary["map"] = {"overlap_ratio": m.overlap_ratio, "matching_score": m.matching_score,
                      "reflected": bool(m.reflected), "flipped_triangles": int(m.flipped_triangles),
                      "iterations": int(m.iterations)}
    mesh.update()
    for h in (guides, phi, source):
        if h is not None:
            h.close()
    return summary


def run(obj, vertex, radius, library_path, choice=0, binding_dir=None):
    """Suggest + apply on a Blender mesh object; returns the JSON-able summary."""
    macrocon = import_macrocon(binding_dir)
    t0 = time.perf_counter()
    positions, triangles = mesh_arrays(obj.data)
    with macrocon.Context() as context, macrocon.Library.open(context, library_path) as library:
        with macrocon.Mesh(context, positions, triangles) as host_mesh:
            region, suggestions = suggest(macrocon, context, library, host_mesh, vertex, radius)
            if not suggestions:
                raise RuntimeError("the library returned no suggestion")
            chosen = suggestions[min(choice, len(suggestions) - 1)]
            summary = apply_suggestion(macrocon, context, library, obj, region, chosen)
            region_vertices = region.vertex_count
            region.close()
    summary.update({"object": obj.name, "vertex": vertex, "radius": radius, "library": library_path,
                    "region_vertices": region_vertices, "suggestions": suggestions, "chosen": chosen["id"],
                    "seconds": round(time.perf_counter() - t0, 3)})
    return summary


# ---- authoring: a library entry from the artist's work -----------------------------------------

NO_HOST = 0xFFFFFFFF


def selected_edge_chains(mesh):
    """The selected edges as vertex chains: open chains end where the selection branches or stops,
    a loop of selected edges is one closed chain. Returns [(vertices, closed)]."""
    neighbours = {}
    for e in mesh.edges:
        if e.select:
            a, b = e.vertices
            neighbours.setdefault(a, []).append(b)
            neighbours.setdefault(b, []).append(a)
    used, chains = set(), []

    def walk(start, nxt):
        chain, prev, cur = [start], start, nxt
        used.add(frozenset((start, nxt)))
        while True:
            chain.append(cur)
            if len(neighbours[cur]) != 2 or cur == start:
                return chain
            following = [w for w in neighbours[cur] if frozenset((cur, w)) not in used]
            if not following:
                return chain
            prev, cur = cur, following[0]
            used.add(frozenset((prev, cur)))

    for v in sorted(neighbours):  # open chains first, from their ends or branch points
        if len(neighbours[v]) != 2:
            for w in neighbours[v]:
                if frozenset((v, w)) not in used:
                    chains.append((walk(v, w), False))
    for v in sorted(neighbours):  # what is left are loops
        for w in neighbours[v]:
            if frozenset((v, w)) not in used:
                chain = walk(v, w)
                closed = chain[-1] == chain[0]
                chains.append((chain[:-1] if closed else chain, closed))
    return chains


def patch_polylines(macrocon, region, chains):
    """Host vertex chains as polylines of patch surface points; the parts outside the patch are
    left out (a chain leaving the disk becomes its pieces on it). Returns (polylines, left_out)."""
    v0, v1, t = region.host_vertices
    tris = region.triangles
    at_host = {int(h): w for w, h in enumerate(v0) if h != NO_HOST and v1[w] == h and t[w] == 0}
    corner = {}
    for f, tri in enumerate(tris):
        for k, w in enumerate(tri):
            corner.setdefault(int(w), (f, k))
    polylines, left_out = [], 0
    for chain, closed in chains:
        inside = [h in at_host for h in chain]
        left_out += inside.count(False)
        if closed and not all(inside):  # start after a vertex outside, so no piece wraps around
            first = inside.index(False) + 1
            chain, inside, closed = chain[first:] + chain[:first], inside[first:] + inside[:first], False
        pieces, piece = [], []
        for h, ok in zip(chain, inside):
            if ok:
                piece.append(at_host[h])
            elif piece:
                pieces.append(piece)
                piece = []
        pieces.append(piece)
        for piece in pieces:
            if len(piece) < (3 if closed else 2):
                continue
            faces = np.array([corner[w][0] for w in piece], np.uint32)
            bary = np.zeros((len(piece), 3))
            bary[np.arange(len(piece)), [corner[w][1] for w in piece]] = 1
            polylines.append(macrocon.Polyline(faces, bary, macrocon.PolylineKind.GUIDE, closed))
    return polylines, left_out


ATTRIBUTE_KINDS = {"FLOAT": ("value", 1), "INT": ("value", 1), "FLOAT2": ("vector", 2),
                   "FLOAT_VECTOR": ("vector", 3)}


def patch_field(macrocon, mesh, region, name):
    """A point-domain attribute of the host as a field of the patch: vertices on a host edge blend
    its two ends (INT attributes, labels, take the nearer end's), vertices filling a hole take a
    neighbour's value."""
    attr = mesh.attributes.get(name)
    if attr is None or attr.domain != "POINT" or attr.data_type not in ATTRIBUTE_KINDS:
        raise ValueError(f"'{name}' is not a point attribute of type {', '.join(ATTRIBUTE_KINDS)}")
    key, width = ATTRIBUTE_KINDS[attr.data_type]
    labels = attr.data_type == "INT"
    host = np.empty(len(mesh.vertices) * width, np.int32 if labels else np.float32)
    attr.data.foreach_get(key, host)
    host = host.reshape(-1, width)
    v0, v1, t = region.host_vertices
    known = v0 != NO_HOST
    a, b = np.where(known, v0, 0), np.where(known, v1, 0)
    if labels:
        values = np.where((t < 0.5)[:, None], host[a], host[b]).astype(np.int32)
    else:
        values = (1 - t)[:, None] * host[a] + t[:, None] * host[b]
    tris = region.triangles
    while not known.all():  # hole fills: spread values inward from the known ring
        spread = False
        for tri in tris:
            k = known[tri]
            if k.any() and not k.all():
                src = tri[np.argmax(k)]
                for w in tri[~k]:
                    values[w], known[w], spread = values[src], True, True
        if not spread:
            raise ValueError("patch vertices not connected to any host vertex")
    kind = (macrocon.FieldKind.INTEGER_LABEL if labels else
            {1: macrocon.FieldKind.SCALAR, 2: macrocon.FieldKind.UV, 3: macrocon.FieldKind.VECTOR3}[width])
    return macrocon.Field(name, kind, values)


def nearest_vertex(obj, world_point):
    """The vertex of obj nearest to a world-space point (the 3D cursor)."""
    local = obj.matrix_world.inverted() @ world_point
    n = len(obj.data.vertices)
    co = np.empty(n * 3, np.float32)
    obj.data.vertices.foreach_get("co", co)
    return int(np.argmin(((co.reshape(n, 3) - np.array(local)) ** 2).sum(1)))


def author(obj, vertex, radius, library_path, class_label, name="", field_names=(), author_name="",
           licence="", binding_dir=None):
    """Appends an entry to library_path (created if missing, saved atomically): the disk of `radius`
    around `vertex`, the selected edges as guides, the named point attributes as fields."""
    macrocon = import_macrocon(binding_dir)
    positions, triangles = mesh_arrays(obj.data)
    chains = selected_edge_chains(obj.data)
    with macrocon.Context() as context:
        library = (macrocon.Library.open(context, library_path) if os.path.exists(library_path)
                   else macrocon.Library(context))
        with library, macrocon.Mesh(context, positions, triangles) as host_mesh:
            region = macrocon.Patch.extract(host_mesh, radius, center_vertex=vertex)
            polylines, left_out = patch_polylines(macrocon, region, chains)
            fields = [patch_field(macrocon, obj.data, region, f) for f in field_names]
            entry_id = library.add_entry(region, name=name, class_label=class_label, author=author_name,
                                         licence=licence, polylines=polylines, fields=fields)
            if library.info.vocabulary_size == 0:  # a new library: make it queryable
                library.build_retrieval(vocabulary_size=min(128, region.vertex_count))
            library.save(library_path)
            summary = {"library": library_path, "id": entry_id, "entries": len(library), "vertex": vertex,
                       "radius": radius, "region_vertices": region.vertex_count, "guides": len(polylines),
                       "guide_points": int(sum(len(p.faces) for p in polylines)),
                       "selected_vertices_outside": left_out, "fields": list(field_names)}
            region.close()
    return summary


# ---- Blender UI (add-on) -------------------------------------------------------------------------


class MacroconPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    library_path: bpy.props.StringProperty(name="Constraint library (.mclb)", subtype="FILE_PATH")
    binding_dir: bpy.props.StringProperty(name="Folder of the macrocon Python package", subtype="DIR_PATH")

    def draw(self, _context):
        self.layout.prop(self, "library_path")
        self.layout.prop(self, "binding_dir")


def _prefs(context):
    addon = context.preferences.addons.get(__name__)
    return addon.preferences if addon else None


def _active_vertex(obj):
    """The active (last selected) vertex of an object in edit mode, else None."""
    import bmesh

    if obj.mode != "EDIT":
        return None
    bm = bmesh.from_edit_mesh(obj.data)
    active = bm.select_history.active
    return active.index if isinstance(active, bmesh.types.BMVert) else None


class MESH_OT_macrocon_apply(bpy.types.Operator):
    """Suggest the top-3 macro constraints at the active vertex and re-embed one of them"""

    bl_idname = "mesh.macrocon_apply"
    bl_label = "Suggest and apply macro constraint"
    bl_options = {"REGISTER", "UNDO"}

    radius: bpy.props.FloatProperty(name="Radius", default=0.5, min=1e-6, description="Geodesic radius (scene units)")
    choice: bpy.props.IntProperty(name="Suggestion", default=0, min=0, max=2, description="0 = best match")

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def execute(self, context):
        obj = context.active_object
        vertex = _active_vertex(obj)
        if vertex is None:
            self.report({"ERROR"}, "Select a vertex in Edit Mode first")
            return {"CANCELLED"}
        prefs = _prefs(context)
        library = (prefs.library_path if prefs else "") or os.environ.get("MACROCON_STARTER_LIBRARY", "")
        bpy.ops.object.mode_set(mode="OBJECT")  # attributes are written to the object-mode mesh
        try:
            summary = run(obj, vertex, self.radius, bpy.path.abspath(library), self.choice,
                          bpy.path.abspath(prefs.binding_dir) if prefs and prefs.binding_dir else None)
        except Exception as e:  # noqa: BLE001 - shown to the user (macrocon.Error carries the SDK message)
            self.report({"ERROR"}, f"Macrocon: {e}")
            return {"CANCELLED"}
        context.scene["macrocon_last"] = json.dumps(summary)
        names = ", ".join(f"{s['class']} #{s['id']} ({s['distance']:.3f})" for s in summary["suggestions"])
        self.report({"INFO"}, f"Suggestions: {names}; applied #{summary['chosen']}")
        return {"FINISHED"}


class MESH_OT_macrocon_author(bpy.types.Operator):
    """Append the region under the 3D cursor to a library: selected edges become guides, the named
    point attributes fields"""

    bl_idname = "mesh.macrocon_author"
    bl_label = "Add region to constraint library"
    bl_options = {"REGISTER"}

    library_path: bpy.props.StringProperty(name="Library (.mclb)", subtype="FILE_PATH",
                                           description="Appended to; created if missing")
    radius: bpy.props.FloatProperty(name="Radius", default=0.5, min=1e-6, description="Geodesic radius (scene units)")
    class_label: bpy.props.StringProperty(name="Class", default="")
    entry_name: bpy.props.StringProperty(name="Name", default="")
    fields: bpy.props.StringProperty(name="Fields", default="",
                                     description="Point attributes to store, separated by commas")

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def execute(self, context):
        obj = context.active_object
        if not self.class_label:
            self.report({"ERROR"}, "Give the entry a class (e.g. nose)")
            return {"CANCELLED"}
        prefs = _prefs(context)
        library = bpy.path.abspath(self.library_path or (prefs.library_path if prefs else ""))
        if not library:
            self.report({"ERROR"}, "Give a library file (.mclb) to append to")
            return {"CANCELLED"}
        if obj.mode == "EDIT":
            bpy.ops.object.mode_set(mode="OBJECT")  # the edge selection is read from the object-mode mesh
        vertex = nearest_vertex(obj, context.scene.cursor.location)
        names = [f.strip() for f in self.fields.split(",") if f.strip()]
        try:
            summary = author(obj, vertex, self.radius, library, self.class_label, self.entry_name, names,
                             binding_dir=bpy.path.abspath(prefs.binding_dir) if prefs and prefs.binding_dir else None)
        except Exception as e:  # noqa: BLE001 - shown to the user (macrocon.Error carries the SDK message)
            self.report({"ERROR"}, f"Macrocon: {e}")
            return {"CANCELLED"}
        context.scene["macrocon_last_author"] = json.dumps(summary)
        self.report({"INFO"}, f"Added entry #{summary['id']} ({summary['guides']} guides, "
                              f"{len(summary['fields'])} fields) to {library}")
        return {"FINISHED"}


class VIEW3D_PT_macrocon(bpy.types.Panel):
    bl_label = "Macrocon"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Macrocon"

    def draw(self, context):
        layout = self.layout
        layout.operator(MESH_OT_macrocon_apply.bl_idname)
        layout.operator(MESH_OT_macrocon_author.bl_idname)
        last = context.scene.get("macrocon_last")
        if last:
            summary = json.loads(last)
            for i, s in enumerate(summary["suggestions"]):
                layout.label(text=f"{i}: {s['class']} #{s['id']}  d={s['distance']:.3f}")
            layout.label(text=f"applied #{summary['chosen']}, overlap {summary['map']['overlap_ratio']:.2f}")


_classes = (MacroconPreferences, MESH_OT_macrocon_apply, MESH_OT_macrocon_author, VIEW3D_PT_macrocon)


def register():
    for c in _classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)


# ---- headless entry point ------------------------------------------------------------------------


def main(argv):
    import argparse

    p = argparse.ArgumentParser(prog="macrocon_blender.py", description="Suggest and re-embed macro constraints")
    p.add_argument("--library", required=True, help="constraint library (.mclb)")
    p.add_argument("--mesh", help="OBJ (optionally .gz) to load; default: the active object")
    p.add_argument("--vertex", type=int, required=True)
    p.add_argument("--radius", type=float, required=True)
    p.add_argument("--choice", type=int, default=0, help="which of the top-3 suggestions to re-embed (0 = best)")
    p.add_argument("--out", required=True, help=".blend file to save")
    p.add_argument("--json", help="also write the summary here")
    p.add_argument("--binding", help="folder holding the macrocon Python package")
    args = p.parse_args(argv)

    if args.mesh:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        obj = load_obj_object(args.mesh, os.path.basename(args.mesh).split(".")[0])
    else:
        obj = bpy.context.active_object
        if obj is None or obj.type != "MESH":
            raise SystemExit("no --mesh and no active mesh object")
    summary = run(obj, args.vertex, args.radius, args.library, args.choice, args.binding)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.out))
    summary["blend"] = os.path.abspath(args.out)
    text = json.dumps(summary, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    import macrocon

    macrocon.shutdown()


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
