"""The ctypes structs of _native.py against the C header: every size and field offset, measured by
compiling a small C program against include/macrocon/macrocon.h (needs a C compiler, as CI has)."""
import ctypes
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from macrocon import _native

HEADER_DIR = Path(__file__).resolve().parents[3] / "include"


def c_name(cls) -> str:
    return "mcon_" + re.sub(r"(?<!^)(?=[A-Z])", "_", cls.__name__).lower()


STRUCTS = [v for v in vars(_native).values()
           if isinstance(v, type) and issubclass(v, ctypes.Structure) and v not in (ctypes.Structure, _native.Struct)]


def test_every_ctypes_struct_matches_the_header(tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    assert cc, "a C compiler is needed to measure the header's layout"
    assert (HEADER_DIR / "macrocon" / "macrocon.h").exists()
    assert len(STRUCTS) >= 16
    lines = ["#include <stddef.h>", "#include <stdio.h>", "#include \"macrocon/macrocon.h\"", "int main(void) {"]
    expected = []
    for cls in STRUCTS:
        name = c_name(cls)
        lines.append(f'  printf("{name} %zu\\n", sizeof({name}));')
        expected.append(f"{name} {ctypes.sizeof(cls)}")
        for field, _ in cls._fields_:
            lines.append(f'  printf("{name}.{field} %zu\\n", offsetof({name}, {field}));')
            expected.append(f"{name}.{field} {getattr(cls, field).offset}")
    lines += ["  return 0;", "}"]
    src = tmp_path / "layout.c"
    src.write_text("\n".join(lines) + "\n")
    exe = tmp_path / "layout"
    subprocess.run([cc, "-std=c99", "-I", str(HEADER_DIR), str(src), "-o", str(exe)], check=True)
    measured = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.split("\n")[:-1]
    assert measured == expected


def test_the_appended_map_fields_are_mirrored_last():
    """The fields appended to mcon_map_options / mcon_map_info must be in the mirrors (so the layout
    test above measures them) and stay at the end, where older struct_size values stop."""
    assert [f for f, _ in _native.MapOptions._fields_][-16:] == [
        "orientation", "source_guidance", "source_guidance_stride", "target_guidance", "target_guidance_stride",
        "guidance_dimension", "guidance_weight", "refine_sigma_factor", "use_world_frame", "world_frame_mirror",
        "world_frame_anchor", "use_up_hints", "source_up", "target_up", "coarse_stages", "coarse_vertices"]
    assert [f for f, _ in _native.MapInfo._fields_][-10:] == [
        "alignment_score_unreflected", "alignment_score_reflected", "orientation_compared",
        "level0_energy_unreflected", "level0_energy_reflected", "frame_decided", "coarse_vertices", "coarse_stages",
        "coarse_folds", "coarse_fallback"]
    assert _native.MapOptions in STRUCTS and _native.MapInfo in STRUCTS


def test_the_appended_mesh_desc_fields_are_mirrored_last():
    """mcon_mesh_desc.index_format and flags were appended: they must be the mirror's last fields
    (older struct_size values stop before them) and the mirror must be measured by the layout test."""
    assert [f for f, _ in _native.MeshDesc._fields_][-3:] == ["triangle_count", "index_format", "flags"]
    assert _native.MeshDesc in STRUCTS
    d = _native.MeshDesc()
    assert _native.lib.mcon_mesh_desc_init_sized(ctypes.byref(d), ctypes.sizeof(d)) == 0
    assert d.struct_size == ctypes.sizeof(_native.MeshDesc) and d.index_format == _native.INDEX_FORMAT_UINT32
    assert d.flags == 0
