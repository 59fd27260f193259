#!/usr/bin/env python3
"""The include graph of graftal's layers, read from the sources as they are.

Every file of src/<layer>/ and include/graftal/<layer>/ belongs to that layer; an
`#include "graftal/<other>/..."` is an edge layer -> other. The layers and what each may
use are listed below (the same order as CMakeLists.txt links them).

  include_graph.py           prints the graph (Markdown) and the edges
  include_graph.py --write   writes it into docs/architecture.md between its markers
  include_graph.py --check   fails (exit 1) on an upward edge, or when the graph in
                             docs/architecture.md is not the one the sources give
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Each layer and the layers it may include, bottom up.
MAY_USE = {
    'core': [],
    'lang': ['core'],
    'rewrite': ['lang', 'core'],
    'geometry': ['core'],
    'maps': ['lang', 'geometry', 'core'],
    'turtle': ['rewrite', 'lang', 'geometry', 'core'],
    'output': ['turtle', 'rewrite', 'lang', 'geometry', 'core'],
    'music': ['turtle', 'rewrite', 'lang', 'geometry', 'core'],
    'pipeline': ['music', 'maps', 'output', 'turtle', 'rewrite', 'lang', 'geometry', 'core'],
    'studio': ['pipeline', 'music', 'maps', 'output', 'turtle', 'rewrite', 'lang', 'geometry',
               'core'],
    'python': ['pipeline', 'music', 'maps', 'output', 'turtle', 'rewrite', 'lang', 'geometry',
               'core'],
    'cli': ['studio', 'pipeline', 'music', 'maps', 'output', 'turtle', 'rewrite', 'lang',
            'geometry', 'core'],
    'web': ['studio', 'pipeline', 'music', 'maps', 'output', 'turtle', 'rewrite', 'lang',
            'geometry', 'core'],
}
BEGIN = '<!-- include graph: made by scripts/include_graph.py --write -->'
END = '<!-- end of the include graph -->'
INCLUDE = re.compile(r'^\s*#\s*include\s+"graftal/([a-z]+)/[^"]+"', re.M)


def edges():
    found = {}
    for layer in MAY_USE:
        for folder in (os.path.join(ROOT, 'src', layer),
                       os.path.join(ROOT, 'include', 'graftal', layer)):
            if not os.path.isdir(folder):
                continue
            for name in sorted(os.listdir(folder)):
                if not name.endswith(('.hpp', '.cpp', '.h')):
                    continue
                path = os.path.join(folder, name)
                with open(path, encoding='utf-8') as f:
                    text = f.read()
                for other in INCLUDE.findall(text):
                    if other != layer:
                        found.setdefault((layer, other), []).append(
                            os.path.relpath(path, ROOT))
    return found


def markdown(found):
    lines = [BEGIN, '', '| layer | includes the public headers of |', '| --- | --- |']
    for layer in MAY_USE:
        used = [o for o in MAY_USE if (layer, o) in found]
        lines.append(f'| {layer} | {", ".join(used) if used else "(none)"} |')
    lines += ['', END]
    return '\n'.join(lines)


def main():
    found = edges()
    upward = [(a, b, files) for (a, b), files in sorted(found.items())
              if b not in MAY_USE.get(a, [])]
    graph = markdown(found)
    mode = sys.argv[1] if len(sys.argv) > 1 else ''
    doc_path = os.path.join(ROOT, 'docs', 'architecture.md')
    with open(doc_path, encoding='utf-8') as f:
        doc = f.read()
    if mode == '--write':
        start, end = doc.find(BEGIN), doc.find(END)
        if start < 0 or end < 0:
            sys.exit('docs/architecture.md has no include graph markers')
        doc = doc[:start] + graph + doc[end + len(END):]
        with open(doc_path, 'w', encoding='utf-8') as f:
            f.write(doc)
    failed = False
    for a, b, files in upward:
        failed = True
        print(f'upward include: {a} -> {b} in {", ".join(files)}', file=sys.stderr)
    if mode == '--check':
        if graph not in doc:
            failed = True
            print('docs/architecture.md: the include graph is not the one the sources give; '
                  'run scripts/include_graph.py --write', file=sys.stderr)
        if not failed:
            print(f'include graph: {len(found)} edges between {len(MAY_USE)} layers, none upward')
    elif mode != '--write':
        print(graph)
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
