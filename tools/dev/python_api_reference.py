"""The Python binding's API reference (docs/python_api.md) from its docstrings.

    MACROCON_LIBRARY=build/lib/libmacrocon.so PYTHONPATH=bindings/python \
        /usr/bin/python3 tools/dev/python_api_reference.py --out docs/python_api.md [--check]

Walks `macrocon.__all__` in its order: classes with their signature, docstring and public members
(methods, class methods, properties: those the package defines, not numpy's or enum's), functions
and constants. --check compares with the file instead of writing it and fails when it is stale
(the docs.python_api_reference test), naming the command that regenerates it.
"""
import argparse
import dataclasses
import enum
import inspect
import sys

import macrocon


def signature(obj):
    try:
        return str(inspect.signature(obj))
    except (TypeError, ValueError):
        return "(...)"


def doc(obj):
    text = inspect.getdoc(obj) or ""
    return text.strip()


def members(cls):
    seen, out = set(), []
    for base in cls.__mro__:
        if not base.__module__.startswith("macrocon"):
            continue
        for name, raw in vars(base).items():
            if name.startswith("_") or name in seen:
                continue
            seen.add(name)
            kind = ("property" if isinstance(raw, property) else "classmethod" if isinstance(raw, classmethod)
                    else "staticmethod" if isinstance(raw, staticmethod) else "method" if inspect.isfunction(raw)
                    else None)
            if kind:
                out.append((name, kind, raw.__func__ if kind in ("classmethod", "staticmethod") else raw))
    return sorted(out)


def class_section(name, cls):
    lines = []
    if issubclass(cls, enum.Enum):
        lines += [f"### `{name}` (enum)", "", doc(cls), ""]
        lines += [f"- `{m.name}` = {m.value}" for m in cls]
        return lines + [""]
    if dataclasses.is_dataclass(cls):
        fields = ", ".join(f.name for f in dataclasses.fields(cls))
        lines += [f"### `{name}` (dataclass: {fields})", "", doc(cls), ""]
    else:
        bases = [b.__name__ for b in cls.__bases__ if b is not object and not b.__name__.startswith("_")]
        lines += [f"### `{name}{signature(cls)}`" + (f" ({', '.join(bases)})" if bases else ""), "", doc(cls), ""]
    for member, kind, raw in members(cls):
        if dataclasses.is_dataclass(cls) and member in {f.name for f in dataclasses.fields(cls)}:
            continue
        head = f"`{name}.{member}`" if kind == "property" else f"`{name}.{member}{signature(raw)}`"
        label = "" if kind == "method" else f" ({kind})"
        lines += [f"- {head}{label}: " + doc(raw).replace("\n", "\n  "), ""]
    return lines


def reference():
    lines = ["# Python API reference", "",
             "Generated from the binding's docstrings by `tools/dev/python_api_reference.py`; do not edit by hand",
             "(the `docs.python_api_reference` test fails when it is stale). The C ABI's reference is built",
             "by Doxygen from the headers (`cmake --build build --target api_reference`).", "",
             "```python", "import macrocon", "```", "", doc(macrocon), ""]
    classes, functions, constants = [], [], []
    for name in macrocon.__all__:
        value = getattr(macrocon, name)
        (classes if inspect.isclass(value) else functions if callable(value) else constants).append((name, value))
    lines += ["## Functions", ""]
    for name, fn in functions:
        lines += [f"- `macrocon.{name}{signature(fn)}`: " + doc(fn).replace("\n", "\n  "), ""]
    lines += ["## Constants", ""]
    lines += [f"- `macrocon.{name}` = `{value!r}`" for name, value in constants] + [""]
    errors = [(n, c) for n, c in classes if issubclass(c, Exception)]
    lines += ["## Classes", ""]
    for name, cls in classes:
        if not issubclass(cls, Exception):
            lines += class_section(name, cls)
    lines += ["## Errors", ""]
    for name, cls in errors:
        bases = ", ".join(b.__name__ for b in cls.__bases__)
        lines += [f"- `{name}` ({bases}): " + doc(cls).replace("\n", "\n  "), ""]
    return "\n".join(lines).rstrip() + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", required=True)
    p.add_argument("--check", action="store_true")
    args = p.parse_args()
    text = reference()
    if args.check:
        with open(args.out) as f:
            if f.read() != text:
                sys.exit(f"{args.out} is stale: regenerate it with\n  MACROCON_LIBRARY=build/lib/libmacrocon.so "
                         f"PYTHONPATH=bindings/python /usr/bin/python3 tools/dev/python_api_reference.py --out {args.out}")
        print(f"{args.out} is up to date ({len(text.splitlines())} lines)")
        return
    with open(args.out, "w") as f:
        f.write(text)
    print(f"wrote {args.out} ({len(text.splitlines())} lines)")


main()
