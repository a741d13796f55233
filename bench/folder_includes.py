#!/usr/bin/env python3
"""Folder-level include edges of lib/eqhb and the cycles among them.

Each folder below lib/eqhb (laws/joints counts as laws) is a node; an edge
A -> B means a file of A includes "eqhb/B/...". Prints the edges with the
files behind them and every cycle (strongly connected set of two or more
folders); exits 1 if there is a cycle, so it can serve as a check.

  python3 bench/folder_includes.py [lib/eqhb] [--edges]
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"eqhb/([^"]+)"', re.M)


def folder_of(relative):
    parts = relative.split("/")
    return parts[0] if len(parts) > 1 else "."  # files at the top of eqhb/


def edges(root):
    found = {}
    for directory, _, files in os.walk(root):
        for name in files:
            if not name.endswith((".h", ".cpp", ".hpp", ".cc")):
                continue
            path = os.path.join(directory, name)
            source = folder_of(os.path.relpath(path, root))
            with open(path, encoding="utf-8", errors="replace") as f:
                for target in INCLUDE.findall(f.read()):
                    target_folder = folder_of(target)
                    if target_folder not in (source, "."):
                        found.setdefault((source, target_folder), []).append(os.path.relpath(path, root))
    return found


def cycles(found):
    graph = {}
    for a, b in found:
        graph.setdefault(a, set()).add(b)
        graph.setdefault(b, set())
    # Tarjan's strongly connected components.
    index, low, stack, on_stack, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main(argv):
    root = next((a for a in argv if not a.startswith("--")), "lib/eqhb")
    found = edges(root)
    if "--edges" in argv:
        for (a, b), files in sorted(found.items()):
            print(f"{a} -> {b}  ({len(files)}: {', '.join(sorted(set(files))[:3])}{' ...' if len(set(files)) > 3 else ''})")
    found_cycles = cycles(found)
    for component in found_cycles:
        members = set(component)
        print("cycle: " + ", ".join(component))
        for (a, b), files in sorted(found.items()):
            if a in members and b in members:
                print(f"  {a} -> {b}: {', '.join(sorted(set(files)))}")
    if not found_cycles:
        print(f"no cycles among {len({f for e in found for f in e})} folders ({len(found)} edges)")
    return 1 if found_cycles else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
