#!/usr/bin/env python3
"""Builds a wheel of the pure-Python package that bundles libmacrocon next to it.

usage: build_wheel.py --library build/lib/libmacrocon.so.0 --starter-library build/share/macrocon/starter.mclb
                      --out DIR [--strip /usr/bin/strip]
No pip or setuptools needed: a wheel is a zip with a dist-info folder (PEP 427).
The bundled library is a `strip --strip-unneeded` copy (--strip: the tool, CMake passes
CMAKE_STRIP; default: `strip` on PATH); without a strip tool it is bundled unstripped, with a note
on stderr (stdout carries only the wheel's path).
The library's non-system runtime dependencies (libtbb, libz: whatever `ldd` resolves beyond glibc,
the loader, libstdc++ and libgcc_s) are bundled next to it under their sonames, stripped the same
way, with their Debian copyright files in macrocon/THIRD_PARTY_NOTICES.txt; the library's RUNPATH
$ORIGIN (src/CMakeLists.txt) makes the loader take them from the package folder. The same rules
as tests/scripts/packaged_library.cmake (the NuGet package), which python.wheel checks this against.
THIRD_PARTY_NOTICES.txt starts with the repository's THIRD_PARTY_NOTICES (what is compiled in);
the repository's LICENSE (Apache-2.0) is macrocon/LICENSE and <dist-info>/LICENSE, and METADATA
names it (License, License-File, the classifier). The starter constraint library is
macrocon/starter.mclb (macrocon.starter_library() returns its path).
"""
import argparse
import base64
import hashlib
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path
from typing import Dict

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent  # the repository: LICENSE, THIRD_PARTY_NOTICES


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


# The C/C++ runtime every Linux has; everything else the library needs is bundled.
SYSTEM_LIBRARY = re.compile(
    r"^(linux-vdso|linux-gate|ld-linux[-a-z0-9_]*|libc|libm|libmvec|libpthread|libdl|librt|libresolv|libutil"
    r"|libstdc\+\+|libgcc_s)\.so(\..*)?$")


def bundled_dependencies(library: Path) -> Dict[str, Path]:
    """soname -> resolved path of the library's non-system runtime dependencies (ldd, transitive)."""
    env = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "LD_PRELOAD")}
    out = subprocess.run(["ldd", str(library.resolve())], check=True, capture_output=True, text=True, env=env).stdout
    deps = {}
    for line in out.splitlines():
        m = re.match(r"\s*(\S+) => (\S+)", line)
        if not m:
            continue  # linux-vdso, the absolute loader path
        if m.group(2) == "not":
            raise SystemExit(f"build_wheel.py: {library} needs {m.group(1)}, which the loader does not find")
        if not SYSTEM_LIBRARY.match(m.group(1)):
            deps[m.group(1)] = Path(m.group(2))
    return dict(sorted(deps.items()))


def owning_package(path: Path) -> str:
    """The Debian package owning PATH (dpkg knows it under /lib or /usr/lib, as linked or real)."""
    candidates = []
    for p in (str(path), str(path.resolve())):
        candidates += [p, p[4:] if p.startswith("/usr/") else "/usr" + p]
    for p in candidates:
        r = subprocess.run(["dpkg-query", "-S", p], capture_output=True, text=True)
        if r.returncode == 0 and r.stdout:
            return re.match(r"[^:,]+", r.stdout).group(0)
    return ""


# Between the repository's notices and the bundled libraries' sections (packaged_library.cmake too).
BUNDLED_HEADING = "\n7. Libraries bundled in this package (wheel, NuGet package)\n" + "-" * 59 + "\n\n"


def notices(deps: Dict[str, Path]) -> bytes:
    """THIRD_PARTY_NOTICES.txt: per bundled library its Debian package, version and copyright file."""
    text = ((ROOT / "THIRD_PARTY_NOTICES").read_text() + BUNDLED_HEADING
            + "Third-party libraries bundled with libmacrocon (runtime dependencies, unmodified\n"
            "except for stripping), with their copyright and licence notices as shipped by Debian.\n")
    for soname, path in deps.items():
        pkg = owning_package(path)
        copyright_file = Path(f"/usr/share/doc/{pkg}/copyright")
        if not pkg or not copyright_file.is_file():
            raise SystemExit(f"build_wheel.py: no licence notice for {soname} ({path}): owning package {pkg!r} "
                             "has no /usr/share/doc/<package>/copyright; refusing to bundle it without one")
        ver = subprocess.run(["dpkg-query", "-W", "--showformat=${Version}", pkg],
                             capture_output=True, text=True).stdout
        text += f"\n==== {soname} ====\nDebian package {pkg} {ver}, {copyright_file}:\n\n{copyright_file.read_text()}"
    return text.encode()


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--library", required=True, type=Path)
    ap.add_argument("--starter-library", required=True, type=Path, help="starter.mclb (build/share/macrocon)")
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
    deps = bundled_dependencies(args.library)
    for soname, path in deps.items():
        files[f"macrocon/{soname}"] = library_bytes(path, args.strip)
    files["macrocon/THIRD_PARTY_NOTICES.txt"] = notices(deps)
    files["macrocon/starter.mclb"] = args.starter_library.read_bytes()
    licence = (ROOT / "LICENSE").read_bytes()
    files["macrocon/LICENSE"] = licence
    files[f"{dist}/LICENSE"] = licence
    files[f"{dist}/METADATA"] = (
        f"Metadata-Version: 2.1\nName: macrocon\nVersion: {ver}\nRequires-Python: >=3.8\nRequires-Dist: numpy\n"
        "Summary: Retrieval and re-embedding of macro constraints for quad meshing\n"
        "License: Apache-2.0\nLicense-File: LICENSE\n"
        "Classifier: License :: OSI Approved :: Apache Software License\n"
        "Classifier: Programming Language :: Python :: 3\nClassifier: Operating System :: POSIX :: Linux\n\n"
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
