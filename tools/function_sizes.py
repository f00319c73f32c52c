#!/usr/bin/env python3
"""Lists the functions of src/ longer than a screen.

A function is a definition whose body opens with '{' alone at the start of a line and closes
with '}' alone at the start of a line (the house format, .clang-format). Data tables are not
functions and are not counted. Exits 1 when a function is longer than LIMIT lines and not
listed in EXCEPTIONS below (with its reason), so a test can keep functions short.

usage: tools/function_sizes.py [SRC] [--limit N] [--top K]
"""
import os
import re
import sys

# Functions allowed beyond the limit, with the reason. (None at present.)
EXCEPTIONS = {}


def functions(root):
    for folder, _, files in sorted(os.walk(root)):
        for name in sorted(files):
            if not name.endswith(('.c', '.h')):
                continue
            path = os.path.join(folder, name)
            with open(path, encoding='utf-8') as f:
                lines = f.read().split('\n')
            i = 0
            while i < len(lines):
                if lines[i] == '{' and i > 0:
                    j = i - 1
                    while j > 0 and (lines[j].startswith(' ') or lines[j] == ''):
                        j -= 1
                    match = re.search(r'(\w+)\s*\(', lines[j])
                    k = i + 1
                    while k < len(lines) and lines[k] != '}':
                        k += 1
                    yield (k - j + 1, os.path.relpath(path, root), match.group(1) if match else '?')
                    i = k
                i += 1


def main():
    args = sys.argv[1:]
    root = 'src'
    limit, top = 80, 0
    while args:
        a = args.pop(0)
        if a == '--limit':
            limit = int(args.pop(0))
        elif a == '--top':
            top = int(args.pop(0))
        else:
            root = a
    found = sorted(functions(root), reverse=True)
    for n, path, name in found[:top]:
        print(f'{n:5d}  {path}  {name}')
    over = [(n, p, f) for n, p, f in found if n > limit and f not in EXCEPTIONS]
    for n, path, name in over:
        print(f'{path}: {name} is {n} lines, more than {limit}')
    print(f'{len(found)} functions, the longest {found[0][0]} lines; '
          f'{len(over)} over {limit} lines')
    return 1 if over else 0


if __name__ == '__main__':
    sys.exit(main())
