#!/usr/bin/env python3
"""Runs the examples of a markdown page as written: the documentation's doc-test.

    doc_examples.py --source ROOT --build BUILD PAGE.md [PAGE.md ...]
    doc_examples.py --source ROOT --list PAGE.md ...      count the examples, run nothing

Every fenced block of a page is an example when its language is `sh`, `console` or `python`:
- `sh`: the block runs in bash (-e, -o pipefail), then waits for what it started in the
  background;
- `console`: each `$ ` line runs in bash; the lines after it are its expected output, where
  `...` stands for any text;
- `python`: the block runs in /usr/bin/python3 with the build's package on PYTHONPATH.
Other blocks (text, json, a synopsis with [OPTIONS]) are not run. A comment on the line just
before a block changes how it runs:
- `<!-- doc-test: reduced: COMMAND -->`: the block is too long for the suite; COMMAND, the
  reduced form the page names beside it, runs instead;
- `<!-- doc-test: exit N -->`: the block is meant to end with exit status N;
- `<!-- doc-test: skip: REASON -->`: the block cannot run here (it installs packages, it is
  the test suite itself, it needs a second machine); the reason is printed.
The blocks of a page run in order in one scratch folder, so a later example can use an earlier
one's files. The scratch folder links every top-level entry of the checkout (build/ to the
build given), so the commands read the shipped data where the page says; an example that
writes into the checkout (a tracked file changed or a file added there) fails the test.
"""

import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^```(\w*)\s*$")
MARKER = re.compile(r"^<!--\s*doc-test:\s*(reduced|exit|skip)\s*:?\s*(.*?)\s*-->\s*$")
RUN_LANGUAGES = ("sh", "console", "python")
WATCHED = ("learning_data", "models", "examples", "experiments", "docs", "viewer", "scripts")


class Example:
    def __init__(self, page, line, language, text, marker):
        self.page, self.line, self.language, self.text = page, line, language, text
        self.kind, self.argument = marker if marker else (None, None)

    def where(self):
        return f"{self.page}:{self.line}"


def parse(page):
    """The runnable blocks of a page, with the marker before each."""
    lines = page.read_text().splitlines()
    examples, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        language, start = m.group(1), i
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        body = "\n".join(lines[start + 1:j]) + "\n"
        marker = None
        if start > 0:
            mm = MARKER.match(lines[start - 1])
            if mm:
                marker = (mm.group(1), mm.group(2))
        if language in RUN_LANGUAGES:
            examples.append(Example(page, start + 1, language, body, marker))
        elif marker:
            raise SystemExit(f"{page}:{start + 1}: a doc-test marker before a block that is not "
                             f"an example ({language or 'no language'})")
        i = j + 1
    return examples


def snapshot(source):
    """Every file under the watched folders of the checkout, with its size and mtime."""
    files = {}
    for top in WATCHED:
        for dirpath, dirnames, filenames in os.walk(source / top):
            dirnames[:] = [d for d in dirnames if d not in ("node_modules", "__pycache__")]
            for name in filenames:
                path = pathlib.Path(dirpath) / name
                try:
                    st = path.lstat()
                except OSError:
                    continue
                files[path] = (st.st_size, st.st_mtime_ns)
    return files


def scratch_folder(source, build):
    folder = pathlib.Path(tempfile.mkdtemp(prefix="graspsynth_doc_"))
    for entry in source.iterdir():
        if entry.name in (".git", "build"):
            continue
        (folder / entry.name).symlink_to(entry)
    (folder / "build").symlink_to(build)
    return folder


def console_script(text):
    """The commands of a console block and the expected output after each."""
    steps = []
    for line in text.splitlines():
        if line.startswith("$ "):
            steps.append([line[2:], []])
        elif steps:
            steps[-1][1].append(line)
    return steps


def expected_matches(expected, output):
    got = output.splitlines()
    if len(expected) > len(got):
        return False
    for want, line in zip(expected, got):
        pattern = ".*".join(re.escape(part) for part in want.split("..."))
        if not re.fullmatch(pattern, line):
            return False
    return True


def run(example, folder, env, timeout):
    """(ok, message) of one example."""
    if example.kind == "reduced":
        commands = [(example.argument, None)]
        language = "sh"
    elif example.language == "console":
        commands = console_script(example.text)
        language = "console"
    else:
        commands = [(example.text, None)]
        language = example.language
    want_exit = int(example.argument) if example.kind == "exit" else 0
    for command, expected in commands:
        if language == "python":
            argv = ["/usr/bin/python3", "-c", command]
        else:
            argv = ["bash", "-e", "-o", "pipefail", "-c", command + "\nwait\n"]
        try:
            r = subprocess.run(argv, cwd=folder, env=env, capture_output=True, text=True,
                               timeout=timeout)
        except subprocess.TimeoutExpired:
            return False, f"did not finish within {timeout} s:\n{command}"
        if r.returncode != want_exit:
            return False, (f"exit status {r.returncode}, expected {want_exit}:\n{command}\n"
                           f"--- stdout\n{r.stdout[-3000:]}--- stderr\n{r.stderr[-3000:]}")
        if expected and not expected_matches(expected, r.stdout):
            return False, (f"output differs from the page:\n{command}\n--- page\n"
                           + "\n".join(expected) + f"\n--- stdout\n{r.stdout[-3000:]}")
    return True, ""


def main():
    parser = argparse.ArgumentParser(description="Run a markdown page's examples as written.")
    parser.add_argument("--source", type=pathlib.Path, required=True, help="the checkout")
    parser.add_argument("--build", type=pathlib.Path, help="the build folder (build/ there)")
    parser.add_argument("--list", action="store_true", help="count the examples, run nothing")
    parser.add_argument("--timeout", type=float, default=900, help="seconds per example")
    parser.add_argument("pages", nargs="+", type=pathlib.Path)
    args = parser.parse_args()
    source = args.source.resolve()
    examples = []
    for page in args.pages:
        examples += parse(page if page.is_absolute() else source / page)
    if args.list:
        for e in examples:
            print(f"{e.where()}: {e.language}{' ' + e.kind if e.kind else ''}")
        print(f"{len(examples)} examples")
        return 0
    if args.build is None:
        parser.error("--build is required to run the examples")
    build = args.build.resolve()
    folder = scratch_folder(source, build)
    env = dict(os.environ, PYTHONPATH=str(build / "python"), MPLBACKEND="Agg")
    if os.geteuid() == 0:  # Open MPI refuses root unless told twice (CI machines run as root)
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    before = snapshot(source)
    failures, ran, skipped = [], 0, 0
    try:
        for e in examples:
            if e.kind == "skip":
                print(f"{e.where()}: skipped: {e.argument}")
                skipped += 1
                continue
            start = time.monotonic()
            ok, message = run(e, folder, env, args.timeout)
            ran += 1
            print(f"{e.where()}: {'ok' if ok else 'FAILED'} ({time.monotonic() - start:.1f} s)",
                  flush=True)
            if not ok:
                failures.append(f"{e.where()}: {message}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    after = snapshot(source)
    changed = sorted(str(p.relative_to(source)) for p in after if before.get(p) != after[p])
    if changed:
        failures.append("the examples wrote into the checkout: " + ", ".join(changed[:20]))
    print(f"{ran} examples run, {skipped} skipped, {len(failures)} failed")
    for f in failures:
        print(f"\n{f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
