#!/usr/bin/env python3
"""Makes Google Benchmark's JSON output (--benchmark_out) hold no absolute path of the machine
that wrote it: the context's "executable" (argv[0] of the benchmark binary) becomes relative to
the project root, "build/benchmarks/ik_benchmark". Only that string changes: every other byte of
the file (the measurements, their formatting) stays as the benchmark wrote it, and a file whose
executable is already relative is left alone. experiments/performance.sh runs it on the
perf_*.json it writes.

    experiments/benchmark_context.py [--root DIR] FILE...     (default DIR: the project root)
"""
import argparse
import json
import os
import sys


def relative_executable(path, root):
    """`path` relative to `root` (with '/' separators) when absolute, else `path` unchanged."""
    if not os.path.isabs(path):
        return path
    return os.path.relpath(path, root).replace(os.sep, "/")


def rewrite(file, root):
    """Rewrites FILE in place (through a temporary file and a rename); False when unchanged."""
    with open(file, encoding="utf-8") as f:
        text = f.read()
    try:
        executable = json.loads(text)["context"]["executable"]
    except (ValueError, KeyError, TypeError) as e:
        raise SystemExit(f"{file}: not a Google Benchmark JSON file with context.executable ({e})")
    relative = relative_executable(executable, root)
    if relative == executable:
        return False
    old = '"executable": ' + json.dumps(executable)
    if text.count(old) != 1:
        raise SystemExit(f"{file}: expected one line {old}, found {text.count(old)}")
    text = text.replace(old, '"executable": ' + json.dumps(relative))
    tmp = os.path.join(os.path.dirname(os.path.abspath(file)), "." + os.path.basename(file) + ".tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, file)
    return True


def main():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=here, help="project root (default: %(default)s)")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    for file in args.files:
        if rewrite(file, args.root):
            print(f"{file}: executable made relative to {args.root}", file=sys.stderr)


if __name__ == "__main__":
    main()
