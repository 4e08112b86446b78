"""Context(log=...): the C log callback (mcon_context_options.log_callback) through ctypes."""
import gc
import warnings

import numpy as np
import pytest

import macrocon
from conftest import grid


def _bad_index_mesh():
    p, t = grid(5)
    t[3, 2] = 999  # out of range: MCON_ERROR_INDEX_OUT_OF_RANGE (11)
    return p, t


def test_log_receives_status_and_the_exceptions_message():
    received = []
    with macrocon.Context(max_threads=2, log=lambda status, message: received.append((status, message))) as ctx:
        p, t = _bad_index_mesh()
        with pytest.raises(macrocon.InvalidMeshError) as err:
            macrocon.Mesh(ctx, p, t)
        assert err.value.status == 11
        assert received == [(11, err.value.message)]
        assert "999" in received[0][1]
        assert ctx.log_exceptions == []
        # Successful calls log nothing.
        good_p, good_t = grid(5)
        with macrocon.Mesh(ctx, good_p, good_t):
            pass
        assert len(received) == 1


def test_log_sees_errors_of_objects_made_in_the_context():
    received = []
    ctx = macrocon.Context(max_threads=2, log=lambda s, m: received.append((s, m)))
    p, t = grid(11)
    mesh = macrocon.Mesh(ctx, p, t)
    with pytest.raises(macrocon.InvalidArgumentError) as err:
        macrocon.Patch.extract(mesh, radius=-1.0, center_vertex=0)
    assert received == [(err.value.status, err.value.message)]
    # The context object is closed first: the mesh keeps the native context (and the callback) alive.
    ctx.close()
    del ctx
    gc.collect()
    with pytest.raises(macrocon.InvalidArgumentError) as err:
        macrocon.Patch.extract(mesh, radius=-2.0, center_vertex=0)
    assert received[-1] == (err.value.status, err.value.message)
    assert len(received) == 2
    mesh.close()


def test_other_contexts_do_not_log():
    received = []
    with macrocon.Context(max_threads=2, log=lambda s, m: received.append(m)):
        with macrocon.Context(max_threads=2) as plain:
            p, t = _bad_index_mesh()
            with pytest.raises(macrocon.InvalidMeshError):
                macrocon.Mesh(plain, p, t)
    assert received == []


def test_raising_log_callback_does_not_crash_and_the_error_surfaces():
    calls = []

    def bad_log(status, message):
        calls.append(status)
        raise RuntimeError("logger is broken")

    with macrocon.Context(max_threads=2, log=bad_log) as ctx:
        p, t = _bad_index_mesh()
        with pytest.warns(macrocon.LogCallbackWarning, match="logger is broken"):
            with pytest.raises(macrocon.InvalidMeshError) as err:
                macrocon.Mesh(ctx, p, t)
        assert err.value.status == 11 and "999" in err.value.message
        assert calls == [11]
        assert len(ctx.log_exceptions) == 1
        assert isinstance(ctx.log_exceptions[0], RuntimeError)
        # Warnings promoted to errors must not reach C either; the context keeps working.
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(macrocon.InvalidMeshError):
                macrocon.Mesh(ctx, p, t)
        assert calls == [11, 11] and len(ctx.log_exceptions) == 2
        good_p, good_t = grid(5)
        with macrocon.Mesh(ctx, good_p, good_t) as mesh:
            assert mesh.counts == (25, 32)


def test_log_must_be_callable():
    with pytest.raises(TypeError, match="log must be callable"):
        macrocon.Context(log="not a function")


def test_log_from_several_threads_gets_every_message_once():
    # Many failing calls from several Python threads at once; every message arrives exactly once.
    import threading

    received = []
    lock = threading.Lock()

    def log(status, message):
        with lock:
            received.append((status, message))

    with macrocon.Context(max_threads=2, log=log) as ctx:
        p, t = _bad_index_mesh()
        errors = []

        def worker():
            for _ in range(20):
                try:
                    macrocon.Mesh(ctx, p, t)
                except macrocon.InvalidMeshError as e:
                    errors.append((e.status, e.message))

        threads = [threading.Thread(target=worker) for _ in range(4)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
    assert len(errors) == 80
    assert sorted(received) == sorted(errors)
    assert np.all([s == 11 for s, _ in received])
