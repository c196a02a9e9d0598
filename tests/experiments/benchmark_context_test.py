#!/usr/bin/env python3
"""Test of experiments/benchmark_context.py: Google Benchmark's absolute "executable" becomes
relative to the project root and no other byte of the file changes; a relative one is left
alone; a file that is not benchmark output is refused by name; and the committed perf_*.json
hold no absolute path. Exit status 0 pass, 1 fail."""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

SAMPLE = """{
  "context": {
    "date": "2026-12-06T20:44:42+00:00",
    "host_name": "vm",
    "executable": "%s",
    "num_cpus": 2,
    "load_avg": [0.942383,1.79346,2.47754],
    "library_build_type": "debug"
  },
  "benchmarks": [
    {
      "name": "BM_Ik",
      "real_time": 1.2345678901234567e+03,
      "time_unit": "ns"
    }
  ]
}
"""


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True,
                          check=False)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--script", required=True)
    parser.add_argument("--results", required=True)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as work:
        root = os.path.join(work, "clone")
        absolute = os.path.join(work, "perf_absolute.json")
        with open(absolute, "w", encoding="utf-8") as f:
            f.write(SAMPLE % (root + "/build/benchmarks/ik_benchmark"))
        done = run(args.script, "--root", root, absolute)
        if done.returncode != 0:
            fail("an absolute executable: exit %d: %s" % (done.returncode, done.stderr))
        with open(absolute, encoding="utf-8") as f:
            text = f.read()
        if text != SAMPLE % "build/benchmarks/ik_benchmark":
            fail("only the executable may change, to build/benchmarks/ik_benchmark:\n" + text)
        if os.listdir(work) != ["perf_absolute.json"]:
            fail("a temporary file was left: %s" % os.listdir(work))
        # again: already relative, the same bytes.
        if run(args.script, "--root", root, absolute).returncode != 0:
            fail("a relative executable is refused")
        with open(absolute, encoding="utf-8") as f:
            if f.read() != text:
                fail("a relative executable was changed")
        # outside the root: relative all the same, never absolute.
        with open(absolute, "w", encoding="utf-8") as f:
            f.write(SAMPLE % "/elsewhere/build/benchmarks/ik_benchmark")
        run(args.script, "--root", root, absolute)
        with open(absolute, encoding="utf-8") as f:
            executable = json.load(f)["context"]["executable"]
        if os.path.isabs(executable) or not executable.endswith("build/benchmarks/ik_benchmark"):
            fail("outside the root: " + executable)
        bad = os.path.join(work, "notes.json")
        with open(bad, "w", encoding="utf-8") as f:
            f.write('{"benchmarks": []}')
        done = run(args.script, bad)
        if done.returncode == 0 or "notes.json" not in done.stderr + done.stdout:
            fail("a file without context.executable is not refused by name: " + done.stderr)

    committed = sorted(glob.glob(os.path.join(args.results, "perf_*.json")))
    if not committed:
        fail("no perf_*.json in " + args.results)
    for path in committed:
        with open(path, encoding="utf-8") as f:
            executable = json.load(f)["context"]["executable"]
        if os.path.isabs(executable):
            fail("%s: the executable is absolute: %s" % (path, executable))
    print("PASS")


if __name__ == "__main__":
    main()
