#!/usr/bin/env python3
"""The tables and the surface plot of experiments/placements.sh.

Reads OUT/analysis.json, OUT/inside.csv, OUT/inside_slide.csv, OUT/outside.csv and
OUT/check.csv (graspsynth generalize over placements) and the library; writes OUT/placements.md
(per method: synthesized, nominal success, passed the gate, mean robustness; the placements
where the methods separate, with the nearest demonstration's failure; the grip slide on the
placements it was checked on, per orientation; the line principle over placements) and
OUT/surface.svg (gnuplot: per method, the nominal success over the orientations at each
position on the table).

    experiments/placements_report.py OUT LIBRARY
"""
import collections
import csv
import json
import os
import subprocess
import sys
import tempfile

METHODS = ["nearest", "interp", "interp+refine", "line+refine", "interp+refine/slide"]


def read_rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def key(row):
    return (round(float(row["x"]), 4), round(float(row["y"]), 4), round(float(row["theta_deg"]), 3))


def demonstrated(library):
    with open(library) as f:
        lib = json.load(f)
    out = set()
    for e in lib["entries"]:
        p = e["placement"]
        out.add((round(p["x"], 4), round(p["y"], 4), round(p["theta_deg"], 3)))
    return out


def method_table(rows):
    """Per method: rows, synthesized, nominal successes, passed, robustness sum, out of range."""
    per = {m: collections.Counter() for m in METHODS}
    robustness = collections.defaultdict(float)
    for r in rows:
        m = r["method"]
        if m not in per:
            continue
        c = per[m]
        c["rows"] += 1
        c["synthesized"] += r["status"] == "ok"
        c["out_of_range"] += r["status"] == "out_of_range"
        c["nominal"] += int(r["nominal_success"])
        c["passed"] += int(r["passed"])
        c["fallback"] += int(r["fallback"])
        robustness[m] += float(r["robustness"])
    lines = ["| method | placements | synthesized | nominal success | passed the gate | "
             "mean robustness | fell back | out of the hull |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for m in METHODS:
        c = per[m]
        n = c["rows"]
        if n == 0:
            continue
        lines.append("| %s | %d | %d | %d (%.1f%%) | %d (%.1f%%) | %.3f | %d | %d |" % (
            m, n, c["synthesized"], c["nominal"], 100.0 * c["nominal"] / n, c["passed"],
            100.0 * c["passed"] / n, robustness[m] / n, c["fallback"], c["out_of_range"]))
    return "\n".join(lines) + "\n", per, robustness


def failure(row):
    """Why a row did not give a nominal success, in words."""
    if row["status"] != "ok":
        return {"unreachable": "out of reach (no IK solution or a jump)",
                "out_of_range": "outside the hull"}.get(row["status"], row["status"])
    return "nominal trial: " + (row["nominal_outcome"] or "failed")


def separations(rows):
    """Placements where nearest fails and a blend succeeds, and the reverse."""
    by = collections.defaultdict(dict)
    for r in rows:
        by[key(r)][r["method"]] = r
    blend_wins, nearest_wins = collections.Counter(), collections.Counter()
    examples = []
    for k in sorted(by):
        m = by[k]
        if "nearest" not in m:
            continue
        near_ok = m["nearest"]["nominal_success"] == "1"
        blends = [b for b in ("interp", "interp+refine") if b in m]
        blend_ok = any(m[b]["nominal_success"] == "1" for b in blends)
        if not near_ok and blend_ok:
            why = failure(m["nearest"])
            blend_wins[why] += 1
            if len(examples) < 12:
                winners = ", ".join(b for b in blends if m[b]["nominal_success"] == "1")
                examples.append("- (%g, %g) m, %g deg: nearest %s; %s succeeded" % (
                    k[0], k[1], k[2], why, winners))
        if near_ok and blends and not blend_ok:
            nearest_wins[failure(m["interp+refine"] if "interp+refine" in m else m[blends[0]])] += 1
    return blend_wins, nearest_wins, examples


def slide_check_section(rows):
    """The grip slide against interp+refine on the check placements, per orientation."""
    if not rows:
        return ""
    mean = collections.defaultdict(lambda: collections.defaultdict(list))
    for r in rows:
        mean[r["method"]][float(r["theta_deg"])].append(float(r["robustness"]))
    plain, slid = mean["interp+refine"], mean["interp+refine/slide"]
    table, _, _ = method_table(rows)
    lines = ["## The grip slide on placements it was not designed on (%d placements)\n" %
             len({key(r) for r in rows}),
             "The grip slide's rule (a grip within 4 cm of the handle's end slides in) was "
             "written from the inside grid's failures; these placements (between the inside "
             "grid's positions, at orientations it does not have) check it. Each method draws "
             "its own perturbed replays, so rows whose grasp the slide leaves as it is differ by "
             "replay noise alone.\n", table,
             "\n| orientation (deg) | interp+refine | interp+refine/slide |", "|---:|---:|---:|"]
    for theta in sorted(plain):
        a, b = plain[theta], slid.get(theta, [])
        lines.append("| %g | %.3f | %s |" % (theta, sum(a) / len(a),
                                             "%.3f" % (sum(b) / len(b)) if b else "-"))
    return "\n".join(lines) + "\n"


def line_section(analysis_path):
    if not os.path.exists(analysis_path):
        return ""
    with open(analysis_path) as f:
        a = json.load(f)
    fit = a.get("placement_line")
    if not fit:
        return ""
    if not fit["valid"]:
        return "## The line principle over placements\n\nNot fitted: %s\n" % fit["message"]

    def v(x):
        return "(%.3f, %.3f, %.3f)" % tuple(x)
    r, t = fit["residuals"], fit["theta_only"]
    return (
        "## The line principle over placements\n\n"
        "The grasp wrist relative to the object centre (world axes) as an affine function of "
        "the placement, `r = b + A_x (x - x_ref) + A_y (y - y_ref) + A_theta theta`, fitted by "
        "Ceres over %d placement means of the successful demonstrations at %d positions "
        "(reference (%.3f, %.3f) m):\n\n"
        "| term | value |\n|---|---|\n"
        "| b (m) | %s |\n| A_theta (m/rad) | %s: the wrist line at %s deg |\n"
        "| A_x (m/m) | %s |\n| A_y (m/m) | %s |\n\n"
        "| model | rms on the table (mm) | max (mm) | rms in height (mm) |\n|---|---:|---:|---:|\n"
        "| affine in (x, y, theta) | %.1f | %.1f | %.1f |\n"
        "| one line for every position (A_x = A_y = 0) | %.1f | %.1f | %.1f |\n" % (
            fit["samples"], fit["positions"], fit["reference_m"][0], fit["reference_m"][1],
            v(fit["b_m"]), v(fit["a_theta_m_per_rad"]),
            "-" if fit["line_angle_deg"] is None else "%.1f" % fit["line_angle_deg"],
            v(fit["a_x"]), v(fit["a_y"]), 1e3 * r["rms_xy_m"], 1e3 * r["max_xy_m"],
            1e3 * r["rms_z_m"], 1e3 * t["rms_xy_m"], 1e3 * t["max_xy_m"], 1e3 * t["rms_z_m"]))


def surface_plot(out, rows, library_placements):
    """surface.svg: per method, the share of orientations with a nominal success per position."""
    share = collections.defaultdict(lambda: [0, 0])
    for r in rows:
        s = share[(r["method"], round(float(r["x"]), 4), round(float(r["y"]), 4))]
        s[0] += int(r["nominal_success"])
        s[1] += 1
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for m in METHODS:
            path = os.path.join(tmp, m.replace("+", "_").replace("/", "_") + ".dat")
            with open(path, "w") as f:
                for (method, x, y), (ok, n) in sorted(share.items()):
                    if method == m:
                        f.write("%g %g %g\n" % (x, y, ok / n))
            files.append((m, path))
        demos = os.path.join(tmp, "demos.dat")
        with open(demos, "w") as f:
            for x, y in sorted({(p[0], p[1]) for p in library_placements}):
                f.write("%g %g\n" % (x, y))
        script = ["set terminal svg size 1500,900 font 'sans,11'",
                  "set output '%s'" % os.path.join(out, "surface.svg"),
                  "set multiplot layout 2,3 title 'Nominal success over the orientations, per "
                  "object position (crosses: demonstrated positions)'",
                  "set xrange [-0.37:-0.13]", "set yrange [0.73:0.97]", "set size ratio -1",
                  "set cbrange [0:1]", "set palette defined (0 'red', 0.5 'yellow', 1 'green')",
                  "set xlabel 'object x (m)'", "set ylabel 'object y (m)'", "set grid"]
        for m, path in files:
            script.append("set title '%s'" % m)
            script.append("plot '%s' using 1:2:3 with points pt 7 ps 2.5 palette notitle, "
                          "'%s' using 1:2 with points pt 2 ps 1.5 lc rgb 'black' notitle" % (
                              path, demos))
        script.append("unset multiplot")
        subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)


def main():
    out, library = sys.argv[1], sys.argv[2]
    placements = demonstrated(library)
    # rows at a demonstrated placement (the grid's centre in the outside run) are not held out.
    inside = [r for r in read_rows(os.path.join(out, "inside.csv")) +
              read_rows(os.path.join(out, "inside_slide.csv")) if key(r) not in placements]
    check = [r for r in read_rows(os.path.join(out, "check.csv")) if key(r) not in placements]
    outside = [r for r in read_rows(os.path.join(out, "outside.csv")) if key(r) not in placements]
    md = ["# Placements: the pan anywhere on the table\n",
          "Written by experiments/placements.sh from %s (%d demonstrated placements at %d "
          "positions). Per method: synthesized, nominal trial succeeded, passed the physics gate "
          "(nominal success and robustness >= 0.8 over 10 perturbed replays, the physics "
          "perturbed), mean robustness over all placements (a grasp not synthesized counts 0), "
          "interp rows that fell back to a vertex or the plain blend, rows outside the hull.\n"
          % (library, len(placements), len({(p[0], p[1]) for p in placements}))]
    for name, rows, what in (
            ("inside", inside, "Held-out placements between the demonstrated ones"),
            ("outside", outside, "Held-out placements outside the demonstrated grid")):
        if not rows:
            continue
        n = len({key(r) for r in rows})
        table, _, _ = method_table(rows)
        md.append("## %s (%d placements)\n\n%s" % (what, n, table))
        wins, losses, examples = separations(rows)
        md.append("\nWhere the methods separate: nearest failed and interp or interp+refine "
                  "succeeded at %d placements, by the nearest grasp's failure: %s. The reverse "
                  "(nearest succeeded, both blends failed): %d placements%s.\n" % (
                      sum(wins.values()),
                      ", ".join("%s %d" % (k, v) for k, v in wins.most_common()) or "none",
                      sum(losses.values()),
                      (" (" + ", ".join("%s %d" % (k, v) for k, v in losses.most_common()) + ")")
                      if losses else ""))
        if examples:
            md.append("\n" + "\n".join(examples) + "\n")
    md.append("\n" + slide_check_section(check))
    md.append("\n" + line_section(os.path.join(out, "analysis.json")))
    surface_plot(out, inside + outside, placements)
    md.append("\n![success over the table](surface.svg)\n")
    tmp = os.path.join(out, "placements.md.tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(md))
    os.replace(tmp, os.path.join(out, "placements.md"))
    print("wrote %s and %s" % (os.path.join(out, "placements.md"),
                               os.path.join(out, "surface.svg")))


if __name__ == "__main__":
    main()
