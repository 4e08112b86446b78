"""Marks the public headers' comments for Doxygen, once (kept for headers added later; idempotent):
a comment block right above a declaration becomes `/** ... */` (C) or `///` lines (C++), a
comment after a declaration on its line `/**< ... */` or `///< ...`. Section rulers (`/* ----`) and the file's opening comment stay as
they are. usage: doxygen_comments.py HEADER..."""
import re
import sys

TRAILING = re.compile(r"^(\s*[^/\s].*?[;,{]?\s*)/\*(?![*!<])\s?(.*\*/\s*)$")
TRAILING_LINE = re.compile(r"^(\s*[^/\s].*?[;,{)]\s*)//(?![/!<])\s?(.*)$")


def convert(lines):
    out = list(lines)
    i = 0
    while i < len(out):
        line = out[i]
        stripped = line.lstrip()
        if stripped.startswith("/*") and not stripped.startswith(("/**", "/*!", "/* ---")) and i > 0:
            end = i
            while "*/" not in out[end]:
                end += 1
            nxt = out[end + 1] if end + 1 < len(out) else ""
            if nxt.strip() and not nxt.lstrip().startswith(("/*", "#", "}")):
                out[i] = line.replace("/*", "/**", 1)
            i = end + 1
            continue
        if stripped.startswith("//") and not stripped.startswith(("///", "//!")) and i > 0 and \
                not out[i - 1].lstrip().startswith("//"):
            end = i
            while end + 1 < len(out) and out[end + 1].lstrip().startswith("//"):
                end += 1
            nxt = out[end + 1] if end + 1 < len(out) else ""
            if nxt.strip() and not nxt.lstrip().startswith(("#", "}")):
                for k in range(i, end + 1):
                    out[k] = out[k].replace("//", "///", 1)
            i = end + 1
            continue
        m = TRAILING.match(line)
        if m and not stripped.startswith(("/*", "*", "#")):
            out[i] = m.group(1) + "/**< " + m.group(2)
        m = TRAILING_LINE.match(out[i])
        if m and not stripped.startswith(("//", "#", "\"")) and '"' not in m.group(1)[-2:]:
            out[i] = m.group(1) + "///< " + m.group(2)
        i += 1
    return out


for path in sys.argv[1:]:
    with open(path) as f:
        lines = f.read().split("\n")
    with open(path, "w") as f:
        f.write("\n".join(convert(lines)))
