#!/usr/bin/env python3
"""The README's table of headline results, made from the committed results.

    scripts/readme_results.py            print the table
    scripts/readme_results.py --write    put it into README.md between the results markers
    scripts/readme_results.py --check    exit 1 when README.md's table differs from the files

Every figure is read from experiments/results/ (the study's summary, the generalization,
objects and placements reports), so the README cannot state a figure the files do not hold.
"""

import argparse
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
RESULTS = ROOT / "experiments" / "results"
BEGIN = "<!-- results:begin (scripts/readme_results.py writes this table) -->"
END = "<!-- results:end -->"


class ResultsError(Exception):
    pass


def read(relative):
    path = RESULTS / relative
    try:
        return path.read_text()
    except OSError as e:
        raise ResultsError(f"{path}: {e.strerror}") from e


def find(pattern, text, name):
    match = re.search(pattern, text, re.MULTILINE)
    if not match:
        raise ResultsError(f"experiments/results/{name}: no line matches {pattern!r}")
    return match


def table_rows(text, name, header_start):
    """The rows of the first markdown table whose header starts with header_start, as dicts."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.startswith(header_start):
            header = [c.strip() for c in line.strip("|").split("|")]
            rows = []
            for row in lines[i + 2:]:
                if not row.startswith("|"):
                    break
                rows.append(dict(zip(header, (c.strip() for c in row.strip("|").split("|")))))
            return rows
    raise ResultsError(f"experiments/results/{name}: no table starting {header_start!r}")


def link(name):
    return f"[{pathlib.PurePath(name).name}](experiments/results/{name})"


def rows():
    out = []
    summary = read("study_summary.txt")
    table1 = find(r"Table I (\d+ of \d+ orientations within 5 mm / 2 deg)", summary,
                  "study_summary.txt")
    n = table1.group(1).split()[2]
    out.append((f"the paper's Table I ({n} orientations)",
                table1.group(1).replace(" orientations", ""), link("study_summary.txt")))
    objects = table_rows(read("objects.md"), "objects.md", "| object |")
    pan = next((r for r in objects if r["object"] == "pan"), None)
    if pan is None:
        raise ResultsError("experiments/results/objects.md: no row for the pan")
    out.append(("the operator's wrist line (pan)",
                f"rms {pan['line RMS (mm)']} mm (the radial strategy: {pan['radial RMS (mm)']} mm)",
                link("objects.md")))
    for method in ("interp+refine", "line+refine"):
        m = find(rf"^  {re.escape(method)}: (\d+)/(\d+) (nominal successes, \d+/\d+ passed the "
                 r"gate, mean robustness [0-9.]+)", summary, "study_summary.txt")
        out.append((f"the study: {method} at {m.group(2)} orientations",
                    f"{m.group(1)}/{m.group(2)} {m.group(3)}", link("study_summary.txt")))
    for r in table_rows(read("generalization.md"), "generalization.md", "| method |"):
        out.append((f"every degree 20-100: {r['method']}",
                    f"{r['nominal successes']} nominal successes, {r['passed the gate']} passed, "
                    f"mean robustness {r['mean robustness (all rows)']}",
                    link("generalization.md")))
    for r in objects:
        if r["object"] == "pan":
            continue
        out.append((f"other objects, interp+refine: {r['object']}",
                    f"{r['interp+refine nominal']}% nominal successes, mean robustness "
                    f"{r['interp+refine robustness']}", link("objects.md")))
    placements = table_rows(read("placements/placements.md"), "placements/placements.md",
                            "| method |")
    for r in placements:
        if r["method"] == "interp+refine/slide":
            out.append((f"{r['placements']} held-out placements: {r['method']}",
                        f"{r['nominal success']} nominal successes, {r['passed the gate']} "
                        f"passed, mean robustness {r['mean robustness']}",
                        link("placements/placements.md")))
    return out


def table():
    lines = ["| result | measured | from |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows()]
    return "\n".join(lines) + "\n"


def readme_block(text):
    begin, end = text.find(BEGIN), text.find(END)
    if begin < 0 or end < begin:
        raise ResultsError(f"README.md: the markers {BEGIN!r} ... {END!r} are missing")
    return begin + len(BEGIN) + 1, end


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--write", action="store_true", help="rewrite README.md's table")
    mode.add_argument("--check", action="store_true", help="compare README.md's table")
    parser.add_argument("--readme", type=pathlib.Path, default=ROOT / "README.md")
    args = parser.parse_args()
    try:
        fresh = table()
        if not (args.write or args.check):
            sys.stdout.write(fresh)
            return 0
        text = args.readme.read_text()
        start, stop = readme_block(text)
        if args.write:
            args.readme.write_text(text[:start] + fresh + text[stop:])
            return 0
        if text[start:stop] != fresh:
            sys.stderr.write(f"{args.readme}: the results table differs from experiments/results/"
                             f" (run scripts/readme_results.py --write); expected:\n{fresh}")
            return 1
        return 0
    except ResultsError as e:
        sys.stderr.write(f"readme_results: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
