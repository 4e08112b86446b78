"""The Dask sample (dask_build_library.py) against a single-process build of the same inputs.

Registered with ctest as samples.python_dask_library only when /usr/bin/python3 imports
`distributed` (Debian package python3-distributed, tools/debian-packages-extra.txt); the CMake
configuration says so when it is not. Here a missing Dask is an error, not a skip.

The inputs: the bundled MakeHuman body (samples/data) and three reshaped variants of it (same
topology, so the benchmark landmarks of samples/data/makehuman-landmarks.json are valid regions on
each), 52 regions; 4 worker processes (LocalCluster(n_workers=4, threads_per_worker=1, processes=True)).
"""
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from dask.distributed import Client, LocalCluster

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "data"
sys.path.insert(0, str(HERE))

import macrocon  # noqa: E402
import dask_build_library as sample  # noqa: E402

LANDMARKS = DATA / "makehuman-landmarks.json"
BODY = DATA / "makehuman-body.obj.gz"
# Query regions that are not library entries (other radii, another mesh), as a user's would be.
QUERIES = [("body", 8021, 0.55), ("body", 297, 0.45), ("body", 537, 0.6), ("body", 3197, 1.2),
           ("body", 11412, 1.8), ("tall", 12222, 0.45), ("broad", 131, 0.95)]


def write_obj(path, positions, triangles):
    with open(path, "w") as f:
        f.writelines(f"v {x:.7g} {y:.7g} {z:.7g}\n" for x, y, z in positions)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder of four meshes: the body (a copy of the bundled file) and three variants."""
    out = tmp_path_factory.mktemp("meshes")
    (out / "body.obj.gz").write_bytes(BODY.read_bytes())
    p, t = sample.load_obj(str(BODY))
    p = p.astype(np.float64)
    y = (p[:, 1] - p[:, 1].min()) / np.ptp(p[:, 1])
    variants = {
        "tall": p * [1.0, 1.12, 1.0],
        "broad": p * [1.18, 1.0, 1.1],
        "bent": p + np.stack([0.08 * np.sin(3.0 * y), np.zeros_like(y), 0.12 * y * y], 1),
    }
    for name, q in variants.items():
        write_obj(out / f"{name}.obj", q, t)
    return out


@pytest.fixture(scope="module")
def items(folder):
    items = sample.read_regions(folder, LANDMARKS)
    assert [Path(m).name for m, _ in items] == ["bent.obj", "body.obj.gz", "broad.obj", "tall.obj"]
    return items


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=4, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as c:
        c.wait_for_workers(4)
        yield c


@pytest.fixture(scope="module")
def context():
    with macrocon.Context(max_threads=1) as ctx:
        yield ctx


@pytest.fixture(scope="module")
def single(items, context):
    start = time.perf_counter()
    lib = sample.build_library_single_process(items, context, seed=3)
    print(f"\nsingle-process build: {len(lib)} entries in {time.perf_counter() - start:.2f} s")
    yield lib
    lib.close()


def region(folder, context, mesh, vertex, radius):
    path = folder / ("body.obj.gz" if mesh == "body" else f"{mesh}.obj")
    p, t = sample.load_obj(str(path))
    with macrocon.Mesh(context, p, t) as m:
        return macrocon.Patch.extract(m, radius, center_vertex=vertex)


def assert_same_answers(merged, single, folder, context):
    assert len(merged) == len(single) == 52
    assert [e.id for e in merged] == [e.id for e in single] == list(range(1, 53))
    assert [e.name for e in merged] == [e.name for e in single]
    assert [e.class_label for e in merged] == [e.class_label for e in single]
    mi, si = merged.info, single.info
    assert (mi.vocabulary_size, mi.histogram_length, mi.sigma_bof, mi.seed) == \
        (si.vocabulary_size, si.histogram_length, si.sigma_bof, si.seed)
    assert mi.vocabulary_size > 0
    # The whole file (entries, descriptors, normalization, vocabulary, histograms) is the same.
    assert merged.to_bytes() == single.to_bytes()
    for mesh, vertex, radius in QUERIES:
        with region(folder, context, mesh, vertex, radius) as q:
            a, b = merged.query(q, n=10), single.query(q, n=10)
            assert len(a) == 10
            assert a.ids.tolist() == b.ids.tolist(), (mesh, vertex, radius)
            assert a.distances.tolist() == b.distances.tolist(), (mesh, vertex, radius)  # bit for bit
            assert merged.query_distinct(q, n=4) == single.query_distinct(q, n=4)


def test_dask_build_on_4_workers_answers_queries_as_a_single_process_build(client, items, single, folder, context):
    assert len(client.scheduler_info()["workers"]) == 4
    lines = []
    start = time.perf_counter()
    # 3 regions per task: 20 tasks, finishing in any order on the 4 workers; merged in input order.
    with sample.build_library_dask(client, items, context, regions_per_task=3, log=lines.append, seed=3) as merged:
        seconds = time.perf_counter() - start
        print(f"Dask build (4 workers, 20 tasks): {len(merged)} entries in {seconds:.2f} s")
        pids = {int(line.rsplit("pid ", 1)[1].rstrip(")")) for line in lines}
        assert len(lines) == 20
        assert os.getpid() not in pids and len(pids) >= 2, pids  # the work ran in the worker processes
        assert_same_answers(merged, single, folder, context)


def small(items):
    """Four regions on each of two meshes: enough for the other paths of the sample."""
    return [(mesh, regions[:4]) for mesh, regions in items[:2]]


def test_partials_through_a_shared_folder(client, items, context, tmp_path):
    with sample.build_library_dask(client, small(items), context, partials_dir=tmp_path, seed=3) as merged, \
            sample.build_library_single_process(small(items), context, seed=3) as single:
        assert sorted(p.name for p in tmp_path.iterdir()) == ["partial-000000.mclb", "partial-000001.mclb"]
        assert len(merged) == 8 and merged.to_bytes() == single.to_bytes()


def test_command_line_against_a_scheduler_address(client, folder, items, context, tmp_path, capsys):
    """The same code against a scheduler's address (here the LocalCluster's), with a REGIONS.json
    in the per-mesh format."""
    regions = {Path(mesh).name: [{"name": r.name, "center_vertex": r.center_vertex, "radius": r.radius}
                                 for r in rs] for mesh, rs in small(items)}
    (tmp_path / "regions.json").write_text(json.dumps(regions))
    out = tmp_path / "library.mclb"
    rc = sample.main([str(folder), str(tmp_path / "regions.json"), str(out), "--scheduler", client.scheduler.address,
                      "--seed", "3", "--regions-per-task", "1"])
    printed = capsys.readouterr().out
    assert rc == 0, printed
    assert "8 regions on 2 meshes" in printed and "cluster: 4 workers" in printed, printed
    with macrocon.Library.open(context, out) as lib, \
            sample.build_library_single_process(small(items), context, seed=3) as single:
        assert lib.to_bytes() == single.to_bytes()


def test_merge_order_matters_which_is_why_it_is_the_input_order(items, folder, context):
    """Why build_library_dask merges in input order: the same entries in another order give
    another vocabulary (k-means) and other distances, so a merge in completion order would not
    be reproducible."""
    body = [(mesh, regions) for mesh, regions in items if mesh.endswith("body.obj.gz")]
    backwards = [(mesh, list(reversed(regions))) for mesh, regions in body]
    with sample.build_library_single_process(body, context, seed=3, vocabulary_size=16) as a, \
            sample.build_library_single_process(backwards, context, seed=3, vocabulary_size=16) as b, \
            region(folder, context, "body", 8021, 0.55) as q:
        assert a.info.sigma_bof != b.info.sigma_bof
        assert a.query(q, n=5).distances.tolist() != b.query(q, n=5).distances.tolist()


def test_a_region_that_fails_names_its_mesh_and_region(client, folder, context):
    bad = [(str(folder / "tall.obj"), [sample.Region("everything", 0, 1000.0)])]
    with pytest.raises(Exception, match=r"tall\.obj: region 'everything' \(vertex 0, radius 1000.0\)"):
        sample.build_library_dask(client, bad, context)
