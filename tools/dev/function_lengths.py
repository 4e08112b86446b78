#!/usr/bin/env python3
"""Lengths of the C++ function bodies in the given folders, longest first.

    function_lengths.py [--top N] [--max LINES] DIR...

A definition starts at column 0 (namespace bodies are not indented here), its signature ends
with an opening brace and it is not a namespace, class, struct, enum or union; its length runs
from the signature's first line to the closing brace at column 0. Lambdas count toward the function that holds them. With --max, exits 1 and
names every function longer than LINES (the project's limit is in CONTRIBUTING.md).
"""
import argparse
import os
import re
import sys

NOT_A_FUNCTION = re.compile(r'^(namespace|class|struct|enum|union|extern|template\s*<[^>]*>\s*(class|struct))\b')


def functions(path):
    with open(path, encoding='utf-8') as f:
        lines = f.read().split('\n')
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line or line[0].isspace() or line.startswith(('#', '//', '}', '/*', ' *')):
            i += 1
            continue
        # the signature runs from here to the first line ending in '{' (a body) or ';' (a declaration)
        j = i
        while j < len(lines) and j < i + 12 and not lines[j].rstrip().endswith(('{', ';')) and lines[j].strip():
            j += 1
        if j >= len(lines) or not lines[j].rstrip().endswith('{'):
            i = j + 1
            continue
        head = ' '.join(l.strip() for l in lines[i:j + 1])
        end = j + 1
        while end < len(lines) and not lines[end].startswith('}'):
            end += 1
        if not NOT_A_FUNCTION.match(head) and '(' in head and '=' not in head.split('(')[0]:
            name = re.sub(r'\s*\(.*', '', head).split()[-1]
            yield name, i + 1, end - i + 1
            i = end + 1
        else:
            i = j + 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--top', type=int, default=10)
    parser.add_argument('--max', type=int, default=0)
    parser.add_argument('dirs', nargs='+')
    args = parser.parse_args()
    found = []
    for root in args.dirs:
        for folder, _, files in os.walk(root):
            for name in files:
                if name.endswith(('.cpp', '.h', '.hpp')):
                    path = os.path.join(folder, name)
                    found += [(length, f'{path}:{line}', fn) for fn, line, length in functions(path)]
    found.sort(key=lambda x: (-x[0], x[1]))
    for length, where, fn in found[:args.top]:
        print(f'{length:5d}  {fn}  {where}')
    if args.max:
        over = [f for f in found if f[0] > args.max]
        if over:
            print(f'{len(over)} function(s) over {args.max} lines:', file=sys.stderr)
            for length, where, fn in over:
                print(f'  {fn} ({length} lines) at {where}', file=sys.stderr)
            return 1
        print(f'every function is at most {args.max} lines ({len(found)} functions)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
