"""macrocon.starter_library(): the path of starter.mclb (next to the package in the wheel; beside
the native library's lib folder in the build tree and an install prefix; MACROCON_STARTER_LIBRARY
overrides)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

import macrocon


def test_starter_library_is_an_existing_mclb_file():
    path = Path(macrocon.starter_library())
    assert path.is_file(), path
    assert path.name == "starter.mclb"
    assert path.read_bytes()[4:8] == b"MCLB"  # the FlatBuffers file identifier


def test_starter_library_opens_and_has_entries(context):
    lib = macrocon.Library.open(context, macrocon.starter_library())
    assert lib.info.entry_count > 0


def _run(env_value):
    env = dict(os.environ)
    env["MACROCON_STARTER_LIBRARY"] = env_value
    code = "import macrocon\ntry:\n    print(macrocon.starter_library())\nexcept FileNotFoundError as e:\n    print('missing:', e)\n"
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout


def test_environment_variable_overrides(tmp_path):
    copy = tmp_path / "other.mclb"
    copy.write_bytes(Path(macrocon.starter_library()).read_bytes())
    assert _run(str(copy)).strip() == str(copy)


def test_missing_override_is_an_error_not_a_fallback(tmp_path):
    out = _run(str(tmp_path / "nope.mclb"))
    assert out.startswith("missing:") and "MACROCON_STARTER_LIBRARY" in out, out
