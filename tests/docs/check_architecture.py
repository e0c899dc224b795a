#!/usr/bin/env python3
"""Checks docs/architecture.md's module diagram against the real CMake link lines.

The diagram is the ```mermaid block of docs/architecture.md: one edge
`A --> B` per target A (library or app) that links target B (PUBLIC, PRIVATE
or INTERFACE). This configures the source tree into a scratch folder with
`cmake --graphviz` (tests and benchmarks off), reads the edges between the
project's own targets and fails, naming each edge, when the diagram has one
that the build does not or lacks one that it has.

usage: check_architecture.py SOURCE_DIR [SCRATCH_DIR]
       check_architecture.py --print SOURCE_DIR   (the edges as mermaid lines, to paste)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The project's own targets: the libraries and apps named p3at_*, and the two
# apps that are not (external libraries such as yaml-cpp or Eigen3::Eigen are
# left out of the diagram).
TARGET = r"p3at_\w+|vipars|mission_exec"


def diagram_edges(doc_path):
    text = open(doc_path, encoding="utf-8").read()
    blocks = re.findall(r"```mermaid\n(.*?)```", text, re.S)
    if len(blocks) != 1:
        sys.exit(f"{doc_path}: expected exactly one ```mermaid block, found {len(blocks)}")
    edges = set()
    for number, line in enumerate(blocks[0].splitlines(), 1):
        line = line.strip()
        if not line or line.startswith("%%") or line.startswith("graph") or line.startswith("flowchart"):
            continue
        m = re.fullmatch(rf"({TARGET})\s*-->\s*({TARGET})", line)
        if not m:
            sys.exit(f"{doc_path}: mermaid line {number}: expected 'target --> target', got {line!r}")
        edges.add((m.group(1), m.group(2)))
    return edges


def build_edges(source_dir, scratch):
    dot = os.path.join(scratch, "graph.dot")
    cmd = ["cmake", "-S", source_dir, "-B", os.path.join(scratch, "build"), "-G", "Ninja",
           "-DP3AT_BUILD_TESTS=OFF", "-DP3AT_BUILD_BENCH=OFF", f"--graphviz={dot}"]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("cmake failed:\n" + run.stdout + run.stderr)
    names, edges = {}, set()
    for line in open(dot, encoding="utf-8"):
        m = re.match(r'\s*"(node\d+)"\s*\[\s*label\s*=\s*"([^"]+)"', line)
        if m:
            names[m.group(1)] = m.group(2)
            continue
        m = re.match(r'\s*"(node\d+)"\s*->\s*"(node\d+)"', line)
        if m:
            edges.add((m.group(1), m.group(2)))
    named = {(names[a], names[b]) for a, b in edges}
    return {(a, b) for a, b in named if re.fullmatch(TARGET, a) and re.fullmatch(TARGET, b)}


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--print":
        scratch = tempfile.mkdtemp(prefix="p3at-graphviz-")
        try:
            for a, b in sorted(build_edges(os.path.abspath(sys.argv[2]), scratch)):
                print(f"{a} --> {b}")
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        return 0
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    source_dir = os.path.abspath(sys.argv[1])
    scratch = sys.argv[2] if len(sys.argv) == 3 else tempfile.mkdtemp(prefix="p3at-graphviz-")
    try:
        documented = diagram_edges(os.path.join(source_dir, "docs", "architecture.md"))
        real = build_edges(source_dir, scratch)
    finally:
        if len(sys.argv) == 2:
            shutil.rmtree(scratch, ignore_errors=True)
    missing = sorted(real - documented)
    extra = sorted(documented - real)
    for a, b in missing:
        print(f"docs/architecture.md lacks {a} --> {b} (the build links it)")
    for a, b in extra:
        print(f"docs/architecture.md draws {a} --> {b} (the build does not link it)")
    if missing or extra:
        return 1
    print(f"docs/architecture.md's diagram matches the build: {len(real)} links between "
          f"{len({t for e in real for t in e})} targets")
    return 0


if __name__ == "__main__":
    sys.exit(main())
