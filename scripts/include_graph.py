#!/usr/bin/env python3
"""The include graph of bimloc by folder, checked against the declared layer order.

Every #include of every source and header under sim/ and localizer/ is resolved as the compiler
resolves it (quoted: the including file's folder first; then localizer/include, localizer/src
and the project root, the targets' include paths), and the file it lands on is mapped to its
folder:
  sim/<part>          the bench, one node per part (sim/world, sim/base, ...)
  localizer/<stage>   the method, one node per stage: include/bimloc/<stage>/ and src/<stage>/
                      together (bim, geometry, planes, pf, sgraph, peers)
  localizer           the entry point (localizer.hpp, localizer.cpp)
  localizer/<name>    any other file at the top (verbosity.hpp: localizer/verbosity)
Includes that land outside the project (the standard library, Eigen, PCL, ...) are not edges.

The check: each folder may include only folders on a LOWER layer of LAYERS below (its own files
are free); every folder found must be declared; and, whatever the layers say, the graph has no
cycle. Exit 0 when all holds, 1 with one line per offending #include (file:line) otherwise,
2 on bad usage.

  python3 scripts/include_graph.py              the graph, the layers, the check
  python3 scripts/include_graph.py --files      each edge with the includes that make it
  python3 scripts/include_graph.py --libraries  which folders include which heavy library
  python3 scripts/include_graph.py --root DIR   another tree (e.g. an old commit's `git archive`)
"""
import argparse
import collections
import os
import re
import sys

# Bottom first. A folder may include the folders of the layers below its own, never one on its
# own layer or above. Why this order: the method knows nothing of the bench; in the bench, the
# output plumbing (common) is below everything; the world and what needs no world come next;
# then what moves or senses in the world, what records or describes a run, the run itself, the
# in-the-loop runner, and the command line on top.
LAYERS = [
    ("method: planar poses, how much to print", ["localizer/geometry", "localizer/verbosity"]),
    ("method: the building model", ["localizer/bim"]),
    ("method: storeys and stairs: which floor the robot stands on", ["localizer/storeys"]),
    ("method: wall planes from a scan", ["localizer/planes"]),
    ("method: the localizers (paper's PF, S-Graph, peers), where to look next",
     ["localizer/pf", "localizer/sgraph", "localizer/peers", "localizer/guide"]),
    ("method: the entry point", ["localizer"]),
    ("bench: output plumbing", ["sim/common"]),
    ("bench: world, odometry, plan generation, pictures, ROS 2 bags",
     ["sim/world", "sim/odometry", "sim/worldgen", "sim/render", "sim/ros2"]),
    ("bench: in the world (base, lidar)", ["sim/base", "sim/lidar"]),
    ("bench: recordings and scenarios", ["sim/dataset", "sim/scenario"]),
    ("bench: map error, the information limit, simulation", ["sim/metrics", "sim/oracle", "sim/simulation"]),
    ("bench: in-the-loop runs", ["sim/runner"]),
    ("command line", ["sim/cli"]),
]

SOURCE_SUFFIXES = (".hpp", ".cpp", ".h", ".hh", ".cc")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)

# Heavy third-party headers, by the prefix of the include (for --libraries).
LIBRARIES = [
    ("PCL", ("pcl/",)), ("Ceres", ("ceres/",)), ("IFC++", ("ifcpp/",)),
    ("Embree", ("embree3/",)), ("Bullet", ("btBullet", "BulletCollision/", "LinearMath/")),
    ("assimp", ("assimp/",)), ("yaml-cpp", ("yaml-cpp/",)), ("CLI11", ("CLI/",)),
    ("gtest", ("gtest/", "gmock/")), ("nlohmann json", ("nlohmann/",)),
    ("Eigen", ("Eigen/", "unsupported/Eigen/")), ("ROS bag", ("rosbag/", "ros/", "sensor_msgs/")),
    ("OSMesa", ("GL/",)), ("libpng", ("png.h",)),
]


def folder_of(path, root):
    """The graph node of a project file, or None for a file outside sim/ and localizer/."""
    parts = os.path.relpath(path, root).split(os.sep)
    if parts[0] == "sim":
        return "sim/" + parts[1] if len(parts) > 2 else "sim"
    if parts[0] == "localizer" and len(parts) > 2:
        inner = parts[3:] if parts[1] == "include" else parts[2:]  # include/bimloc/X or src/X
        if len(inner) > 1:
            return "localizer/" + inner[0]
        stem = os.path.splitext(inner[0])[0]
        # The entry point's own files (localizer.cpp, localizer_impl.hpp, localizer_guide.cpp, ...).
        return "localizer" if stem == "localizer" or stem.startswith("localizer_") else "localizer/" + stem
    return None


def resolve(kind, name, including_dir, search_dirs):
    """The project file an include lands on, or None (a third-party or system header)."""
    candidates = ([including_dir] if kind == '"' else []) + search_dirs
    for base in candidates:
        path = os.path.normpath(os.path.join(base, name))
        if os.path.isfile(path):
            return path
    return None


def scan(root):
    """edges[(from, to)] = [(file, line, include)]; libraries[folder] = {library: [file]}."""
    search_dirs = [os.path.join(root, "localizer", "include"), os.path.join(root, "localizer", "src"),
                   root]
    edges = collections.defaultdict(list)
    libraries = collections.defaultdict(lambda: collections.defaultdict(set))
    folders = set()
    for top in ("localizer", "sim"):
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
            dirnames.sort()
            for filename in sorted(filenames):
                if not filename.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(dirpath, filename)
                source = folder_of(path, root)
                if source is None:
                    continue
                folders.add(source)
                with open(path, encoding="utf-8", errors="replace") as f:
                    text = f.read()
                for match in INCLUDE.finditer(text):
                    kind, name = match.group(1), match.group(2)
                    line = text.count("\n", 0, match.start()) + 1
                    target = resolve(kind, name, dirpath, search_dirs)
                    rel = os.path.relpath(path, root)
                    if target is None:
                        for library, prefixes in LIBRARIES:
                            if name.startswith(prefixes):
                                libraries[source][library].add(rel)
                        continue
                    destination = folder_of(target, root)
                    if destination is not None and destination != source:
                        edges[(source, destination)].append((rel, line, name))
    return edges, libraries, folders


def find_cycles(nodes, edges):
    """The strongly connected components of more than one folder (Tarjan)."""
    graph = collections.defaultdict(list)
    for a, b in edges:
        graph[a].append(b)
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
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
                cycles.append(sorted(component))

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return cycles


def check(edges, folders):
    """The problems found, one line each (empty: the layout holds)."""
    layer_of = {}
    problems = []
    for number, (_, members) in enumerate(LAYERS):
        for folder in members:
            layer_of[folder] = number
    for folder in sorted(folders - set(layer_of)):
        problems.append(f"{folder}: a folder not in the declared layers (add it to LAYERS in "
                        f"scripts/include_graph.py, on the layer it belongs to)")
    for (a, b), sites in sorted(edges.items()):
        if a in layer_of and b in layer_of and layer_of[b] >= layer_of[a]:
            where = "on its own layer" if layer_of[b] == layer_of[a] else "on a layer above it"
            for rel, line, name in sites:
                problems.append(f"{rel}:{line}: {a} includes {b} ({name}), {where}")
    for cycle in find_cycles(folders, edges):
        problems.append("cycle among " + ", ".join(cycle))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                        help="the project's top folder (default: this script's project)")
    parser.add_argument("--files", action="store_true", help="list the includes behind each edge")
    parser.add_argument("--libraries", action="store_true",
                        help="which folders include which heavy third-party library")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    if not os.path.isdir(os.path.join(root, "sim")) or not os.path.isdir(os.path.join(root, "localizer")):
        print(f"include_graph: {root} has no sim/ and localizer/ folders", file=sys.stderr)
        return 2
    edges, libraries, folders = scan(root)

    print("folder-level include graph (from -> to: number of #include lines)")
    by_source = collections.defaultdict(list)
    for (a, b), sites in sorted(edges.items()):
        by_source[a].append((b, sites))
    for a in sorted(folders):
        targets = by_source.get(a, [])
        print(f"  {a:20} -> " + (", ".join(f"{b} ({len(s)})" for b, s in targets) or "(nothing)"))
        if args.files:
            for b, sites in targets:
                for rel, line, name in sites:
                    print(f"      {rel}:{line} -> {name}")
    print("\nlayers, top first (a folder includes only folders of the layers below it)")
    for name, members in reversed(LAYERS):
        print(f"  {name:52} {' '.join(members)}")
    if args.libraries:
        print("\nheavy third-party headers included, by folder (files that include them)")
        for folder in sorted(libraries):
            used = libraries[folder]
            print(f"  {folder:20} " + ", ".join(f"{lib} ({len(used[lib])})" for lib in sorted(used)))
    problems = check(edges, folders)
    print()
    if problems:
        print(f"include graph: {len(problems)} problem(s)")
        for problem in problems:
            print("  " + problem)
        return 1
    print(f"include graph: {len(folders)} folders, {len(edges)} edges, no folder includes one on "
          f"its own layer or above, no cycle")
    return 0


if __name__ == "__main__":
    sys.exit(main())
