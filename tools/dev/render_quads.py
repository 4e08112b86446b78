"""Renders a QuadWild result with the guides it was given (the README picture), headless in Blender:

    blender -b --factory-startup -P tools/dev/render_quads.py -- QUADS.obj CUT.obj CUT.sharp OUT.png
            [--focus CUT.obj CUT.sharp] [--margin 0.25] [--size 1200x900] [--view front|left|right]

OUT.png, or OUT.jpg for a smaller file.
QUADS.obj is QuadWild's quad mesh; CUT.obj / CUT.sharp are what mcon_cut_mesh_write_quadwild wrote
(the guides are the .sharp edges, drawn as red tubes). The camera is orthographic along the view
(front: looking down -Z, the MakeHuman body's facing direction) and frames the guides of the
--focus pair (default: the guides drawn) grown by --margin, or the whole quad mesh with --margin
alone if there are none. Workbench engine: flat studio light, quads light grey, quad edges dark.
"""
import math
import sys

import bpy
import mathutils


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                faces.append([int(tok.split("/")[0]) - 1 for tok in line.split()[1:]])
    return vertices, faces


def read_sharp_edges(path, faces):
    with open(path) as f:
        lines = [l.strip() for l in f if l.strip()]
    edges = []
    for l in lines[1 : 1 + int(lines[0])]:
        _, face, edge = (int(x) for x in l.split(","))
        tri = faces[face]
        edges.append((tri[edge], tri[(edge + 1) % len(tri)]))
    return edges


def material(name, rgba):
    m = bpy.data.materials.new(name)
    m.diffuse_color = rgba
    return m


def mesh_object(name, vertices, faces, mat):
    me = bpy.data.meshes.new(name)
    me.from_pydata(vertices, [], faces)
    me.update()
    ob = bpy.data.objects.new(name, me)
    ob.data.materials.append(mat)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def guide_curve(name, vertices, edges, radius, mat):
    cu = bpy.data.curves.new(name, "CURVE")
    cu.dimensions = "3D"
    cu.bevel_depth = radius
    cu.bevel_resolution = 2
    for a, b in edges:
        sp = cu.splines.new("POLY")
        sp.points.add(1)
        sp.points[0].co = (*vertices[a], 1.0)
        sp.points[1].co = (*vertices[b], 1.0)
    ob = bpy.data.objects.new(name, cu)
    ob.data.materials.append(mat)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def parse(argv):
    args = argv[argv.index("--") + 1 :] if "--" in argv else []
    if len(args) < 4:
        raise SystemExit(__doc__)
    opts = {"quads": args[0], "cut": args[1], "sharp": args[2], "out": args[3], "focus": None, "margin": 0.25,
            "size": (1200, 900), "view": "front"}
    rest = args[4:]
    i = 0
    while i < len(rest):
        if rest[i] == "--focus":
            opts["focus"] = (rest[i + 1], rest[i + 2])
            i += 3
        elif rest[i] == "--margin":
            opts["margin"] = float(rest[i + 1])
            i += 2
        elif rest[i] == "--size":
            w, h = rest[i + 1].split("x")
            opts["size"] = (int(w), int(h))
            i += 2
        elif rest[i] == "--view":
            opts["view"] = rest[i + 1]
            i += 2
        else:
            raise SystemExit("render_quads: unknown option %s" % rest[i])
    return opts


def main():
    o = parse(sys.argv)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    qv, qf = read_obj(o["quads"])
    cv, cf = read_obj(o["cut"])
    guides = read_sharp_edges(o["sharp"], cf)
    edge_length = sum((mathutils.Vector(qv[f[0]]) - mathutils.Vector(qv[f[1]])).length for f in qf) / max(len(qf), 1)

    quads = mesh_object("quads", qv, qf, material("quad", (0.82, 0.82, 0.80, 1)))
    wire = mesh_object("quad_edges", qv, qf, material("edge", (0.12, 0.12, 0.14, 1)))
    mod = wire.modifiers.new("wire", "WIREFRAME")
    mod.thickness = 0.08 * edge_length
    mod.use_replace = True
    guide_curve("guides", cv, guides, 0.06 * edge_length, material("guide", (0.85, 0.1, 0.08, 1)))
    del quads

    # What to frame: the focus guides' box, else the drawn guides', else the quads'.
    if o["focus"]:
        fv, ff = read_obj(o["focus"][0])
        pts = [fv[v] for e in read_sharp_edges(o["focus"][1], ff) for v in e]
    else:
        pts = [cv[v] for e in guides for v in e] or qv
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    center = mathutils.Vector([(lo[k] + hi[k]) / 2 for k in range(3)])
    views = {"front": ((0, 0, 1), (0, 1)), "left": ((1, 0, 0), (2, 1)), "right": ((-1, 0, 0), (2, 1))}
    direction, (ax_u, ax_v) = views[o["view"]]
    extent_u, extent_v = hi[ax_u] - lo[ax_u], hi[ax_v] - lo[ax_v]
    w, h = o["size"]
    # ortho_scale spans the longer side of the image.
    fit = max(extent_u, extent_v * w / h) if w >= h else max(extent_v, extent_u * h / w)
    scale = fit * (1 + 2 * o["margin"])

    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = scale
    cam_data.clip_end = 1000
    cam = bpy.data.objects.new("camera", cam_data)
    d = mathutils.Vector(direction)
    cam.location = center + 50 * d
    # The camera looks down its -Z with +Y up: columns x = up x d, y = world up (+Y), z = d.
    up = mathutils.Vector((0, 1, 0))
    x = up.cross(d).normalized()
    cam.rotation_euler = mathutils.Matrix((x, d.cross(x), d)).transposed().to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam

    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "STUDIO"
    scene.display.shading.color_type = "MATERIAL"
    scene.display.shading.show_cavity = False
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.world = bpy.data.worlds.new("world")
    if o["out"].lower().endswith((".jpg", ".jpeg")):  # smaller files for the docs
        scene.render.image_settings.file_format = "JPEG"
        scene.render.image_settings.quality = 88
    else:
        scene.render.image_settings.file_format = "PNG"
        scene.render.image_settings.compression = 90
    scene.render.image_settings.color_mode = "RGB"
    scene.render.filepath = o["out"]
    bpy.ops.render.render(write_still=True)
    print("render_quads: %s (%d quads, %d guide edges, view %s, ortho scale %.3f)" % (
        o["out"], len(qf), len(guides), o["view"], scale))


main()
