#!/usr/bin/env python3
"""Builds a wheel of the pure-Python package that bundles libmacrocon next to it.

usage: build_wheel.py --library build/lib/libmacrocon.so.0 --out DIR [--strip /usr/bin/strip]
No pip or setuptools needed: a wheel is a zip with a dist-info folder (PEP 427).
The bundled library is a `strip --strip-unneeded` copy (--strip: the tool, CMake passes
CMAKE_STRIP; default: `strip` on PATH); without a strip tool it is bundled unstripped, with a note
on stderr (stdout carries only the wheel's path).
"""
import argparse
import base64
import hashlib
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def version() -> str:
    text = (HERE / "pyproject.toml").read_text()
    return re.search(r'^version\s*=\s*"([^"]+)"', text, re.M).group(1)


def record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def library_bytes(library: Path, strip: str) -> bytes:
    """The library's bytes, stripped of debug info and the static symbol table if `strip` exists."""
    real = library.resolve()
    if not strip or shutil.which(strip) is None:
        print(f"build_wheel.py: no strip tool ({strip!r}): bundling {real} unstripped", file=sys.stderr)
        return real.read_bytes()
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / real.name
        subprocess.run([strip, "--strip-unneeded", "-o", str(out), str(real)], check=True)
        return out.read_bytes()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--library", required=True, type=Path)
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--strip", default=shutil.which("strip") or "", help="strip tool ('' = bundle unstripped)")
    args = ap.parse_args()
    ver = version()
    tag = f"py3-none-linux_{platform.machine()}"
    dist = f"macrocon-{ver}.dist-info"
    files = {}
    for path in sorted((HERE / "macrocon").iterdir()):
        if path.suffix in (".py", ".typed"):
            files[f"macrocon/{path.name}"] = path.read_bytes()
    files[f"macrocon/{args.library.name}"] = library_bytes(args.library, args.strip)
    files[f"{dist}/METADATA"] = (
        f"Metadata-Version: 2.1\nName: macrocon\nVersion: {ver}\nRequires-Python: >=3.8\nRequires-Dist: numpy\n"
        "Summary: Retrieval and re-embedding of macro constraints for quad meshing\n\n"
        + (HERE / "README.md").read_text()
    ).encode()
    files[f"{dist}/WHEEL"] = f"Wheel-Version: 1.0\nGenerator: macrocon build_wheel.py\nRoot-Is-Purelib: false\nTag: {tag}\n".encode()
    record = [record_line(n, d) for n, d in files.items()] + [f"{dist}/RECORD,,"]
    files[f"{dist}/RECORD"] = ("\n".join(record) + "\n").encode()
    args.out.mkdir(parents=True, exist_ok=True)
    wheel = args.out / f"macrocon-{ver}-{tag}.whl"
    with zipfile.ZipFile(wheel, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            info = zipfile.ZipInfo(name, date_time=(2026, 1, 1, 0, 0, 0))
            info.external_attr = (0o755 if name.endswith(".so") or ".so." in name else 0o644) << 16
            z.writestr(info, data, zipfile.ZIP_DEFLATED)
    print(wheel)


if __name__ == "__main__":
    main()
