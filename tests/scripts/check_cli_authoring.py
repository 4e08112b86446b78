"""A library authored entirely from the CLI round-trips (issue: vendor readiness).

Guides and features drawn on the sample body (OBJ `l` lines along mesh edges), singularities
(x, y, z, index) and per-vertex fields (a PLY with extra vertex properties) go into entries with
`macrocon library build`; `library info` lists them, the Python binding reads them back with the
values the files gave, and `embed --source LIB --entry` transfers them onto a region. Bad inputs
fail with messages that name the fix.

usage: check_cli_authoring.py CLI BODY.obj.gz WORK   (MACROCON_LIBRARY and PYTHONPATH set for the
binding)
"""
import gzip
import json
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from edge_paths import shortest_edge_path  # noqa: E402

CLI, BODY, WORK = sys.argv[1:4]
BODY_FACES = 13378  # the body group of the sample OBJ (faces [0, 13378))
NOSE, EYE = 297, 8021  # file vertices (0-based) at the nose tip and the left eye


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def read_body():
    positions, faces = [], []
    with gzip.open(BODY, "rt") as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f ") and len(faces) < BODY_FACES:
                faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    return np.array(positions), faces


def shortest_path(positions, faces, a, b):
    """A path along mesh edges: a polyline that lies exactly on the surface."""
    return shortest_edge_path(positions, ((u, face[(i + 1) % len(face)]) for face in faces for i, u in enumerate(face)),
                              a, b)


def nearest_vertex(positions, used, point):
    candidates = sorted(used)
    d = np.linalg.norm(positions[candidates] - point, axis=1)
    return candidates[int(np.argmin(d))]


def write_lines(path, positions, lines):
    with open(path, "w") as f:
        f.write("# guides drawn on the sample body\n")
        first = 1
        for line in lines:
            for v in line:
                f.write("v %.17g %.17g %.17g\n" % tuple(positions[v]))
            f.write("l " + " ".join(str(first + k) for k in range(len(line))) + "\n")
            first += len(line)


def run(*args, expect_ok=True):
    r = subprocess.run([CLI, *args], capture_output=True, text=True)
    if expect_ok and r.returncode != 0:
        fail("macrocon %s failed (%d):\n%s" % (" ".join(args), r.returncode, r.stderr))
    if not expect_ok and r.returncode == 0:
        fail("macrocon %s should have failed" % " ".join(args))
    return r


def expect_error(args, text):
    r = run(*args, expect_ok=False)
    if text not in r.stderr:
        fail("macrocon %s: expected '%s' in the error, got:\n%s" % (" ".join(args), text, r.stderr))
    print("refused as expected: " + r.stderr.strip().splitlines()[-1][:160])


def make_inputs(positions, faces):
    used = {v for face in faces for v in face}
    offset = lambda v, d: nearest_vertex(positions, used, positions[v] + np.array(d))
    # A guide across the nose (left to right), a feature along it (up), a guide across the eye.
    nose_guide = shortest_path(positions, faces, offset(NOSE, [-0.25, 0, 0]), offset(NOSE, [0.25, 0, 0]))
    nose_feature = shortest_path(positions, faces, offset(NOSE, [0, -0.2, 0]), offset(NOSE, [0, 0.25, 0]))
    eye_guide = shortest_path(positions, faces, offset(EYE, [-0.2, 0, 0]), offset(EYE, [0.2, 0, 0]))
    write_lines(os.path.join(WORK, "guides.obj"), positions, [nose_guide, eye_guide])
    write_lines(os.path.join(WORK, "features.obj"), positions, [nose_feature])
    with open(os.path.join(WORK, "far.obj"), "w") as f:  # a line 5 units off the body
        f.write("v %r %r %r\nv %r %r %r\nl 1 2\n" % (*(positions[NOSE] + [0, 0, 5]), *(positions[NOSE] + [0, 0.1, 5])))
    with open(os.path.join(WORK, "singularities.csv"), "w") as f:
        f.write("x,y,z,index\n")
        f.write("%.17g,%.17g,%.17g,1\n" % tuple(positions[NOSE]))
        f.write("%.17g,%.17g,%.17g,-1  # at the eye: outside the nose entry\n" % tuple(positions[EYE]))
    # Fields: height (the file's y, so a blend along a host edge is exact), u/v and a side label.
    with open(os.path.join(WORK, "fields.ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(positions))
        for p in ("x", "y", "z"):
            f.write("property double %s\n" % p)
        f.write("property double height\nproperty float u\nproperty float v\nproperty int side\nelement face 0\n"
                "property list uchar int vertex_indices\nend_header\n")
        for p in positions:
            f.write("%.17g %.17g %.17g %.17g %g %g %d\n" % (p[0], p[1], p[2], p[1], p[0], p[2], 1 if p[0] >= 0 else 2))
    with open(os.path.join(WORK, "short.csv"), "w") as f:
        f.write("height\n1\n2\n")
    return nose_guide


def build_library(lib):
    entry_args = ["--guides", "guides.obj", "--features", "features.obj", "--singularities", "singularities.csv",
                  "--fields", "fields.ply", "--field", "height", "--field", "uv=u,v:uv", "--field", "side:label"]
    entry_args = [os.path.join(WORK, a) if a.endswith((".obj", ".csv", ".ply")) else a for a in entry_args]
    r = run("library", "build", "--out", lib, "--mesh", BODY, "--face-range", "0:%d" % BODY_FACES,
            "--vocabulary", "8", "--json",
            "--center-vertex", str(NOSE), "--radius", "0.5", "--class", "nose", "--name", "nose", *entry_args,
            "--center-vertex", str(EYE), "--radius", "0.6", "--class", "eye", "--name", "eye_l",
            "--guides", os.path.join(WORK, "guides.obj"))
    out = json.loads(r.stdout)
    nose, eye = out["authoring"]
    print("authoring reports: %s\n                   %s" % (nose, eye))
    checks = [
        (nose["guides"] == 1 and nose["features"] == 1, "the nose keeps one guide and one feature"),
        (nose["lines_outside"] == 1 and nose["points_outside"] > 0, "the eye guide is left out of the nose"),
        (nose["singularities"] == 1 and nose["singularities_outside"] == 1, "one singularity in, one out"),
        (nose["max_snap_distance"] < 1e-9, "points on mesh vertices snap at distance 0"),
        (nose["fields"] == ["height", "uv", "side"], "the three fields, in order"),
        (eye["guides"] == 1 and eye["lines_outside"] == 1 and eye["fields"] == [], "the eye keeps its own guide"),
    ]
    for ok, what in checks:
        if not ok:
            fail("library build --json: " + what)


def check_info(lib):
    info = json.loads(run("library", "info", "--library", lib, "--json").stdout)
    nose, eye = info["entry_list"]
    if (nose["guides"], nose["features"], nose["singularities"], nose["fields"]) != (1, 1, 1, ["height", "uv", "side"]):
        fail("library info lists %s for the nose" % nose)
    kinds = [(f["name"], f["kind"], f["dimension"]) for f in nose["field_kinds"]]
    if kinds != [("height", "scalar", 1), ("uv", "uv", 2), ("side", "label", 1)]:
        fail("library info lists field kinds %s for the nose" % kinds)
    if (eye["guides"], eye["features"], eye["singularities"]) != (1, 0, 0):
        fail("library info lists %s for the eye" % eye)


def check_values(lib, positions, nose_guide):
    import macrocon
    ctx = macrocon.Context()
    library = macrocon.Library.open(ctx, lib)
    entry = library.entry("nose")
    info = entry.info
    host = np.array(info.source_origin) + info.source_scale * entry.positions
    fields = entry.fields
    height_error = float(np.max(np.abs(fields["height"].values[:, 0] - host[:, 1])))
    uv_error = float(np.max(np.abs(fields["uv"].values - host[:, [0, 2]])))
    sides = fields["side"].values[:, 0]
    # A vertex on a host edge takes the nearer end's label: only those near the midline may differ.
    away = np.abs(host[:, 0]) > 0.06
    wrong_side = int(np.sum(sides[away] != np.where(host[away, 0] >= 0, 1, 2)))
    print("nose entry: height error %.2e, uv error %.2e, sides %s" % (height_error, uv_error, sorted(set(sides))))
    if height_error > 1e-5 or uv_error > 1e-5:
        fail("blended field values differ from the host coordinates they were written from")
    if sorted(set(sides)) != [1, 2] or wrong_side > 0:
        fail("the side label is wrong away from the midline")
    guide = entry.polylines[0]
    tris = entry.triangles
    points = np.einsum("nk,nkd->nd", guide.barycentric, host[tris[guide.faces]])
    error = float(np.max(np.min(np.linalg.norm(points[:, None, :] - positions[nose_guide][None, :, :], axis=2), axis=1)))
    print("nose guide: %d points, farthest %.2e from the drawn vertices" % (len(points), error))
    if error > 1e-6 or len(points) < 5:
        fail("the stored guide does not lie on the drawn one")
    return entry.id


def check_embed(lib, nose_id):
    out_dir = os.path.join(WORK, "embed")
    r = run("embed", "--source", lib, "--entry", "nose", "--target", BODY, "--face-range", "0:%d" % BODY_FACES,
            "--center-vertex", str(NOSE), "--radius", "0.45", "--out", out_dir, "--json", "--cut-guides")
    s = json.loads(r.stdout)
    src = s["source_constraints"]
    print("embed: guides %d -> %d, features %d -> %d, fields %s, singularities %s" %
          (s["guides_in"], s["guides_out"], s["features_in"], s["features_out"], src["fields"], src["singularities"]))
    if src["kind"] != "library_entry" or src["entry_id"] != str(nose_id):
        fail("embed did not use the entry")
    if (s["guides_in"], s["features_in"]) != (1, 1) or s["guides_out"] < 1 or s["features_out"] < 1:
        fail("embed lost the entry's guide or feature")
    if src["fields"] != ["height", "uv", "side"]:
        fail("embed transferred fields %s" % src["fields"])
    sing = src["singularities"]
    if len(sing) != 1 or not sing[0]["on_target"] or sing[0]["index_quarters"] != 1:
        fail("the singularity did not land on the target")
    for name in ("features.obj", "singularities.csv", "target.ply", "target_cut.ply"):
        if not os.path.exists(os.path.join(out_dir, name)):
            fail("embed wrote no " + name)
    header = open(os.path.join(out_dir, "target.ply"), "rb").read(2000).split(b"end_header")[0].decode()
    for prop in ("height", "uv_x", "uv_y", "side"):
        if "property float %s\n" % prop not in header:
            fail("target.ply has no property %s:\n%s" % (prop, header))
    # The same body at a slightly smaller radius: the map is near the identity, so the singularity
    # stays at the nose tip (within a tenth of the radius).
    tip = read_body()[0][NOSE]
    moved = float(np.linalg.norm(np.array(sing[0]["position"]) - tip))
    print("singularity moved %.4f (radius 0.45)" % moved)
    if moved > 0.045:
        fail("the singularity moved %.3f from the nose tip" % moved)
    # Its CSV is what --singularities reads back.
    lines = open(os.path.join(out_dir, "singularities.csv")).read().split()
    if lines[0] != "x,y,z,index" or len(lines) != 2:
        fail("singularities.csv: %s" % lines)
    run("embed", "--source", lib, "--entry", str(nose_id), "--target", BODY, "--face-range", "0:%d" % BODY_FACES,
        "--center-vertex", str(NOSE), "--radius", "0.45", "--out", out_dir + "_by_id", "--quiet")


def check_spec():
    """The same constraint keys in a --spec file (paths relative to it)."""
    spec = {"mesh": BODY, "face_range": "0:%d" % BODY_FACES,
            "entries": [{"center_vertex": NOSE, "radius": 0.5, "class": "nose", "name": "nose",
                         "guides": "guides.obj", "features": ["features.obj"], "singularities": "singularities.csv",
                         "fields": "fields.ply", "field": ["height", "side:label"], "max_snap_distance": 0.01}]}
    path = os.path.join(WORK, "spec.json")
    with open(path, "w") as f:
        json.dump(spec, f)
    out = json.loads(run("library", "build", "--out", os.path.join(WORK, "spec.mclb"), "--spec", path,
                         "--vocabulary", "8", "--json").stdout)
    r = out["authoring"][0]
    if (r["guides"], r["features"], r["singularities"], r["fields"]) != (1, 1, 1, ["height", "side"]):
        fail("--spec authoring gave %s" % r)


def check_up():
    """--up stores the mesh's up direction with the entries after it (and "up" in a spec); embed
    --entry then takes the source's from the entry and needs only the target's."""
    lib = os.path.join(WORK, "up.mclb")
    mesh = ["--mesh", BODY, "--face-range", "0:%d" % BODY_FACES]
    run("library", "build", "--out", lib, *mesh, "--vocabulary", "8",
        "--center-vertex", str(EYE), "--radius", "0.6", "--class", "eye", "--name", "eye_plain",
        "--up", "0,1,0", "--center-vertex", str(NOSE), "--radius", "0.5", "--class", "nose", "--name", "nose_up")
    eye, nose = json.loads(run("library", "info", "--library", lib, "--json").stdout)["entry_list"]
    if "up" in eye or nose.get("up") != [0, 1, 0]:
        fail("library info: up %s (eye, before --up) and %s (nose, after it)" % (eye.get("up"), nose.get("up")))
    target = ["--target", BODY, "--face-range", "0:%d" % BODY_FACES, "--center-vertex", str(NOSE), "--radius", "0.45",
              "--samples", "500", "--quiet", "--json"]
    s = json.loads(run("embed", "--source", lib, "--entry", "nose_up", *target, "--target-up", "0,1,0",
                       "--out", os.path.join(WORK, "embed_up")).stdout)
    if not s["up_hints"] or not s["up_from_entry"] or s["flips"] != 0:
        fail("embed --entry with a stored up: up_hints %s, up_from_entry %s" % (s["up_hints"], s["up_from_entry"]))
    plain = json.loads(run("embed", "--source", lib, "--entry", "nose_up", *target,
                           "--out", os.path.join(WORK, "embed_no_target_up")).stdout)
    if plain["up_hints"] or plain["up_from_entry"]:
        fail("without the target's up the entry's alone must not become a hint")
    expect_error(["embed", "--source", lib, "--entry", "eye_plain", *target, "--target-up", "0,1,0",
                  "--out", os.path.join(WORK, "bad")], "--target-up needs --source-up")
    expect_error(["library", "build", "--out", os.path.join(WORK, "bad.mclb"), *mesh, "--up", "0,0,0",
                  "--center-vertex", str(NOSE), "--radius", "0.5", "--class", "nose"], "up is the zero vector")
    expect_error(["library", "build", "--out", os.path.join(WORK, "bad.mclb"), *mesh, "--up", "0,1",
                  "--center-vertex", str(NOSE), "--radius", "0.5", "--class", "nose"], "--up expects X,Y,Z")
    spec = {"mesh": BODY, "face_range": "0:%d" % BODY_FACES, "up": [0, 0, 1],
            "entries": [{"center_vertex": NOSE, "radius": 0.5, "class": "nose"},
                        {"center_vertex": EYE, "radius": 0.6, "class": "eye", "up": [0, 1, 0]}]}
    path = os.path.join(WORK, "up_spec.json")
    with open(path, "w") as f:
        json.dump(spec, f)
    run("library", "build", "--out", lib, "--spec", path, "--vocabulary", "8")
    ups = [e.get("up") for e in json.loads(run("library", "info", "--library", lib, "--json").stdout)["entry_list"]]
    if ups != [[0, 0, 1], [0, 1, 0]]:
        fail("--spec \"up\": entries got %s" % ups)


def check_errors(lib):
    mesh = ["--mesh", BODY, "--face-range", "0:%d" % BODY_FACES]
    entry = ["--center-vertex", str(NOSE), "--radius", "0.5", "--class", "nose"]
    w = lambda name: os.path.join(WORK, name)
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--guides", w("far.obj")], "--max-snap-distance")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--fields", w("short.csv")],
                 "rows but the mesh file has")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--fields", w("fields.ply"), "--field", "u:curl"],
                 "unknown kind 'curl'")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--fields", w("fields.ply"), "--field", "w=u:uv"],
                 "takes 2 columns")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--fields", w("fields.ply"), "--field", "nope"],
                 "has no column 'nope'")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--singularities", w("fields.ply")],
                 "has no column 'index'")
    expect_error(["library", "add", "--library", lib, *mesh, *entry, "--guides", w("singularities.csv")],
                 "no polyline")
    target = ["--target", BODY, "--face-range", "0:%d" % BODY_FACES, "--center-vertex", str(NOSE), "--radius", "0.45"]
    expect_error(["embed", "--source", lib, "--entry", "mouth", *target], "has no entry with that name")
    expect_error(["embed", "--source", lib, "--entry", "nose", "--source-center-vertex", "3", *target],
                 "does not apply with --entry")
    # library add with constraints reports them too.
    r = run("library", "add", "--library", lib, *mesh, *entry, "--name", "nose_2", "--guides", w("guides.obj"), "--json")
    if json.loads(r.stdout)["authoring"]["guides"] != 1:
        fail("library add did not keep the nose guide")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    positions, faces = read_body()
    nose_guide = make_inputs(positions, faces)
    lib = os.path.join(WORK, "authored.mclb")
    build_library(lib)
    check_info(lib)
    nose_id = check_values(lib, positions, nose_guide)
    check_embed(lib, nose_id)
    check_spec()
    check_up()
    check_errors(lib)
    print("PASS")


main()
