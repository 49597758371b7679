#!/usr/bin/env python3
"""Checks the dependency rule of docs/architecture.md on the includes of src/:

    core <- io <- modules <- app <- cli        (plugin on top, through the command)

- core includes only core;
- io includes core and io, never a module, app or the command;
- a module (any other folder of src/urbanvec) includes core, itself and other modules, never io, app
  or the command, and the modules' include graph has no cycle;
- app includes anything of src/urbanvec; the command (src/cli) includes anything;
- GDAL/OGR/CPL/PROJ headers appear only in io, app and the command.

Usage: check_layering.py [--list] [<src folder>] (default: this repository's src/). Prints one line per
violation and exits 1 when there is any; `--list` prints the module graph.
"""
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
SRC = os.path.join(ROOT, 'src')
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')
GDAL_HEADER = re.compile(r'^(gdal|ogr|cpl_|proj|gnm)')


def layer_of(folder):
    if folder in ('core', 'io', 'app'):
        return folder
    return 'module'


def main():
    args = [a for a in sys.argv[1:] if a != '--list']
    src = os.path.abspath(args[0]) if args else SRC
    violations = []
    graph = {}
    for base, _, files in sorted(os.walk(src)):
        for name in sorted(files):
            if not name.endswith(('.cpp', '.hpp', '.h')):
                continue
            path = os.path.join(base, name)
            rel = os.path.relpath(path, src)
            parts = rel.split(os.sep)
            if parts[0] == 'cli':
                owner, layer = 'cli', 'cli'
            elif parts[0] == 'urbanvec' and len(parts) > 2:
                owner = parts[1]
                layer = layer_of(owner)
            else:
                continue
            with open(path, encoding='utf-8') as source:
                for number, line in enumerate(source, 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    header = m.group(1)
                    where = '{}:{}'.format(os.path.join('src', rel), number)
                    if GDAL_HEADER.match(header) and layer not in ('io', 'app', 'cli'):
                        violations.append('{}: {} includes the GDAL/PROJ header <{}>; only io, app and the '
                                          'command may'.format(where, layer if layer != 'module' else owner, header))
                    if not header.startswith('urbanvec/'):
                        continue
                    target = header.split('/')[1]
                    target_layer = 'cli' if target == 'cli' else layer_of(target)
                    allowed = {
                        'core': {'core'},
                        'io': {'core', 'io'},
                        'module': {'core', 'module'},
                        'app': {'core', 'io', 'module', 'app'},
                        'cli': {'core', 'io', 'module', 'app'},
                    }[layer]
                    if target_layer not in allowed:
                        violations.append('{}: {} includes {} ({}), against core <- io <- modules <- app <- cli'.format(
                            where, owner, header, target_layer))
                    if layer == 'module' and target_layer == 'module' and target != owner:
                        graph.setdefault(owner, set()).add(target)
    # The modules' graph must have no cycle.
    state = {}

    def visit(node, trail):
        state[node] = 'open'
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 'open':
                violations.append('modules include each other in a cycle: ' + ' -> '.join(trail + [node, nxt]))
            elif nxt not in state:
                visit(nxt, trail + [node])
        state[node] = 'done'

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
    if '--list' in sys.argv:
        for node in sorted(graph):
            print('{} -> {}'.format(node, ', '.join(sorted(graph[node]))))
    for v in violations:
        print(v)
    return 1 if violations else 0


if __name__ == '__main__':
    sys.exit(main())
