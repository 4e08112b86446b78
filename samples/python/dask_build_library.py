#!/usr/bin/env python3
"""Macrocon sample (Python binding): build a constraint library on a Dask distributed cluster.

    dask_build_library.py FOLDER REGIONS.json OUT.mclb [--scheduler ADDRESS] [--workers N]
                          [--threads-per-worker T] [--regions-per-task R] [--vocabulary-size K]
                          [--seed S] [--partials-dir DIR]

A vendor's library comes from thousands of assets: this is the path that scales.

1. the inputs: a folder of meshes (OBJ, .obj.gz) and region specs (a center vertex, 0-based, a
   geodesic radius in mesh units and a name per region; REGIONS.json, format below)
2. one Dask task per mesh (or per --regions-per-task regions of it): the worker loads the mesh,
   cuts each region (macrocon.Patch.extract) and adds it to a partial library (Library.add_entry
   computes the entry's descriptors: the expensive, independent part)
3. the client merges the partial libraries with Library.merge (mcon_library_merge), in input order,
   builds the vocabulary and the histograms once over all entries (Library.build_retrieval) and
   saves the library

The result is the library a single process builds from the same inputs (build_library_single_process):
same entries, ids, vocabulary and histograms, so the same answers to every query (the test
samples/python/test_dask_build_library.py checks it on 4 worker processes).

Without --scheduler a LocalCluster of --workers processes runs on this machine; with --scheduler
tcp://HOST:8786 (a `dask-scheduler` and `dask-worker`s started elsewhere) the same code runs on the
cluster. Every worker needs numpy and macrocon (the wheel bundles libmacrocon) and must be able to
read the mesh paths (a shared filesystem); with --partials-dir (a shared folder) the partial
libraries go through it instead of through the scheduler.

REGIONS.json is either a map from a mesh file (relative to FOLDER) to its regions
    {"body.obj.gz": [{"name": "eye_l", "center_vertex": 8021, "radius": 0.6}, ...], ...}
or the landmarks format of samples/data/makehuman-landmarks.json ({"classes": {name: {"center_vertex",
"radius"}}}), applied to every mesh of FOLDER (variants of one base topology, as MakeHuman's).

Run with Debian's /usr/bin/python3 (python3-numpy, python3-distributed) and the binding on PYTHONPATH;
MACROCON_LIBRARY names libmacrocon.so unless the package bundles it (wheel). Workers of a
LocalCluster inherit the environment.
"""
import argparse
import json
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional, Sequence, Tuple

import macrocon

try:  # the OBJ reader of the other Python sample (same folder)
    import transfer_fields
except ImportError:  # imported from elsewhere: put this folder first
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import transfer_fields
load_obj = transfer_fields.load_obj

try:
    # Dask sends a task's function to the workers with cloudpickle: by reference (the worker
    # imports the module) unless its module is registered by value. Registered, the workers need
    # macrocon and numpy but not this folder on their sys.path (a cluster's machines may not have it).
    import cloudpickle
    cloudpickle.register_pickle_by_value(transfer_fields)
    if __name__ != "__main__":  # __main__ (run as a script) always goes by value
        cloudpickle.register_pickle_by_value(sys.modules[__name__])
except ImportError:  # no Dask: build_library_single_process still works
    pass


@dataclass(frozen=True)
class Region:
    """A region spec: a geodesic disk of ``radius`` (mesh units) around host vertex ``center_vertex``
    (0-based), becoming the library entry ``name`` (class ``class_label``, default the name)."""

    name: str
    center_vertex: int
    radius: float
    class_label: str = ""


Item = Tuple[str, Sequence[Region]]  # (mesh path, its regions)


def read_regions(folder, regions_json) -> List[Item]:
    """The (mesh path, regions) list of a REGIONS.json (see the module docstring), meshes sorted by name."""
    folder = Path(folder)
    with open(regions_json) as f:
        spec = json.load(f)
    if "classes" in spec:  # landmarks format: the same regions on every mesh of the folder
        regions = [Region(name, int(c["center_vertex"]), float(c["radius"]), c.get("class", ""))
                   for name, c in spec["classes"].items()]
        meshes = sorted(p for p in folder.iterdir() if p.name.endswith((".obj", ".obj.gz")))
        if not meshes:
            raise FileNotFoundError(f"no .obj or .obj.gz mesh in {folder}")
        return [(str(p), regions) for p in meshes]
    items = []
    for mesh, rs in sorted(spec.items()):
        items.append((str(folder / mesh), [Region(r["name"], int(r["center_vertex"]), float(r["radius"]),
                                                  r.get("class", "")) for r in rs]))
    return items


def _entry_name(mesh_path: str, region: Region) -> str:
    stem = os.path.basename(mesh_path)
    for suffix in (".gz", ".obj"):
        stem = stem[: -len(suffix)] if stem.endswith(suffix) else stem
    return f"{stem}/{region.name}"


def add_regions(library, mesh, mesh_path: str, regions: Sequence[Region], first_id: int) -> None:
    """Cuts each region of ``mesh`` and appends it to ``library`` with id ``first_id + k``. The one
    place entries are made: the distributed and the single-process builds both call it."""
    for k, region in enumerate(regions):
        try:
            with macrocon.Patch.extract(mesh, region.radius, center_vertex=region.center_vertex) as patch:
                library.add_entry(patch, name=_entry_name(mesh_path, region),
                                  class_label=region.class_label or region.name,
                                  tags=["dask-sample"], id=first_id + k)
        except macrocon.Error as e:
            # A plain RuntimeError naming the input: it crosses the process boundary as it is.
            raise RuntimeError(f"{mesh_path}: region {region.name!r} (vertex {region.center_vertex}, "
                               f"radius {region.radius}): {e}") from None


def build_partial(task: dict):
    """Runs on a worker: one partial library (entries with their descriptors, no vocabulary).

    Handles (Context, Mesh, Patch, Library) wrap C pointers of this process and cannot be pickled,
    so the worker returns the partial library as the bytes of its file (Library.to_bytes; the
    client opens them with Library.open_memory, which validates the checksum). With a partials
    folder (shared by the cluster) it saves the file there and returns its path instead, so large
    partial libraries do not travel through the scheduler. Returns (index, bytes or path, stats).
    """
    start = time.perf_counter()
    regions = [Region(*r) for r in task["regions"]]
    positions, triangles = load_obj(task["mesh_path"])
    with macrocon.Context(max_threads=task["threads"]) as context, \
            macrocon.Mesh(context, positions, triangles) as mesh, macrocon.Library(context) as partial:
        add_regions(partial, mesh, task["mesh_path"], regions, task["first_id"])
        if task["partials_dir"]:
            path = os.path.join(task["partials_dir"], f"partial-{task['index']:06d}.mclb")
            partial.save(path)
            payload = path
        else:
            payload = partial.to_bytes()
    stats = {"mesh": task["mesh_path"], "entries": len(regions), "seconds": time.perf_counter() - start,
             "pid": os.getpid()}
    return task["index"], payload, stats


def _tasks(items: Sequence[Item], regions_per_task: Optional[int], threads: int, partials_dir) -> List[dict]:
    """The tasks, as plain data (builtins only: what pickle sends to any worker as it is). ``first_id``:
    the id of a task's first entry; ids follow the input order, so they are a single-process build's."""
    tasks, next_id = [], 1
    for mesh_path, regions in items:
        regions = list(regions)
        step = regions_per_task or max(1, len(regions))
        for s in range(0, len(regions), step):
            chunk = [(r.name, r.center_vertex, r.radius, r.class_label) for r in regions[s:s + step]]
            tasks.append({"index": len(tasks), "mesh_path": str(mesh_path), "regions": chunk, "first_id": next_id,
                          "threads": threads, "partials_dir": partials_dir})
            next_id += len(chunk)
    return tasks


def build_library_dask(client, items: Sequence[Item], context, *, regions_per_task: Optional[int] = None,
                       threads_per_task: int = 1, partials_dir=None, log=None, **retrieval):
    """The library of ``items`` ([(mesh path, [Region, ...]), ...]) built on the Dask ``client``'s
    cluster; returns an open macrocon.Library in ``context`` (the caller closes it).

    ``retrieval``: Library.build_retrieval's options (descriptor, vocabulary_size, rings, sigma_bof,
    seed). ``log(message)`` (optional) hears what each task did.

    Why the vocabulary is built here and not on the workers: a vocabulary is a k-means clustering
    of the descriptors of all entries. Partial libraries with their own vocabularies would have
    incomparable histograms (Library.merge then drops them), and no partial vocabulary is the
    global one. The workers do the per-entry work (cutting, descriptors); the client clusters once.

    Merge order: Dask finishes tasks in any order, but client.gather returns them in submission
    (input) order, and the partial libraries are merged in that order: the entries (and so the
    k-means input: another order gives another vocabulary and other distances) are those of a
    single-process build on every run and cluster size. Ids are given from the input order, so merge renumbers none.
    """
    tasks = _tasks(items, regions_per_task, threads_per_task, os.fspath(partials_dir) if partials_dir else None)
    # pure=False: a rerun recomputes (a mesh file may have changed under the same path).
    futures = [client.submit(build_partial, t, pure=False) for t in tasks]
    # In the order of `futures`, whatever order they finished in. gather holds every partial at
    # once: with very many assets use partials_dir (paths, not bytes) or merge as they arrive
    # (distributed.as_completed) with a buffer that keeps the input order.
    results = client.gather(futures)
    merged = macrocon.Library(context)
    try:
        for expected, (index, payload, stats) in enumerate(results):
            assert index == expected, "partial libraries must be merged in input order"
            if isinstance(payload, bytes):
                part = macrocon.Library.open_memory(context, payload)
            else:
                part = macrocon.Library.open(context, payload)
            with part:
                merged.merge(part)  # no vocabulary yet: a plain append of the entries
            if log:
                log(f"task {index}: {stats['entries']} entries of {stats['mesh']} in {stats['seconds']:.2f} s "
                    f"(worker pid {stats['pid']})")
        merged.build_retrieval(**retrieval)
    except BaseException:
        merged.close()
        raise
    return merged


def build_library_single_process(items: Sequence[Item], context, **retrieval):
    """The reference: the same library built in this process, one entry after the other."""
    library = macrocon.Library(context)
    next_id = 1
    try:
        for mesh_path, regions in items:
            positions, triangles = load_obj(str(mesh_path))
            with macrocon.Mesh(context, positions, triangles) as mesh:
                add_regions(library, mesh, str(mesh_path), regions, next_id)
            next_id += len(regions)
        library.build_retrieval(**retrieval)
    except BaseException:
        library.close()
        raise
    return library


def _retrieval_options(args) -> dict:
    out = {"seed": args.seed}
    if args.vocabulary_size is not None:
        out["vocabulary_size"] = args.vocabulary_size
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("folder", help="the folder of meshes (.obj, .obj.gz)")
    p.add_argument("regions", help="REGIONS.json: the regions per mesh (see --help's module docstring)")
    p.add_argument("out", help="the library file to write (.mclb)")
    p.add_argument("--scheduler", help="a Dask scheduler's address (tcp://HOST:8786); default: a LocalCluster")
    p.add_argument("--workers", type=int, default=4, help="LocalCluster worker processes (default 4)")
    p.add_argument("--threads-per-worker", type=int, default=1,
                   help="Dask threads per LocalCluster worker, and macrocon threads per task (default 1)")
    p.add_argument("--regions-per-task", type=int, help="split a mesh's regions into tasks of this many "
                   "(default: one task per mesh, which loads it once)")
    p.add_argument("--vocabulary-size", type=int, help="k of the vocabulary (default: the library's, 128)")
    p.add_argument("--seed", type=int, default=0, help="k-means seed (default 0)")
    p.add_argument("--partials-dir", help="a folder every worker and this client share: partial libraries "
                   "are written there instead of being sent through the scheduler")
    args = p.parse_args(argv)

    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        print("dask_build_library: Dask is not installed (Debian: apt-get install python3-distributed)",
              file=sys.stderr)
        return 2
    items = read_regions(args.folder, args.regions)
    n_regions = sum(len(r) for _, r in items)
    print(f"{n_regions} regions on {len(items)} meshes")
    cluster = None
    try:
        if args.scheduler:
            client = Client(args.scheduler)
        else:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=args.threads_per_worker,
                                   processes=True, dashboard_address=None)
            client = Client(cluster)
        with client, macrocon.Context() as context:
            print(f"cluster: {len(client.scheduler_info()['workers'])} workers ({client.scheduler.address})")
            start = time.perf_counter()
            with build_library_dask(client, items, context, regions_per_task=args.regions_per_task,
                                    threads_per_task=args.threads_per_worker, partials_dir=args.partials_dir,
                                    log=print, **_retrieval_options(args)) as library:
                library.save(args.out)
                info = library.info
                print(f"{info.entry_count} entries, vocabulary {info.vocabulary_size} words, "
                      f"{time.perf_counter() - start:.2f} s -> {args.out}")
    except (macrocon.Error, RuntimeError, OSError) as e:
        print(f"dask_build_library: {e}", file=sys.stderr)
        return 1
    finally:
        if cluster is not None:
            cluster.close()
    return 0


if __name__ == "__main__":
    status = main()
    macrocon.shutdown()  # also registered at exit; not in main(), which a caller's process may run
    sys.exit(status)
