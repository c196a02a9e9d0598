#!/usr/bin/env bash
# The shipped objects side by side. For every object that has demonstrations and a grasp
# library (the pan in learning_data/, the others in learning_data/objects/NAME/): the analysis
# of its demonstrations (Table I, the wrist-line fit against the radial strategy) and a grasp
# for every integer orientation from 20 to 100 deg by the four methods (the nearest
# demonstration turned with the object, the paper's interpolation, interpolation + refinement,
# the line principle with refinement), each validated in physics (nominal + 10 perturbed
# replays, the physics perturbed). Writes experiments/results/objects/NAME/ (analysis.json,
# generalization.csv and .md) and the comparison table experiments/results/objects.md (and
# objects.csv) of every object with results there (this run's and earlier ones'): per object, the line and radial RMS, and per method the nominal success and
# the mean robustness. Deterministic from --seed 1. 20-30 minutes per object on 2 cores.
#
#   experiments/objects.sh [BUILD_DIR] [OBJECT ...]     (default: build, every object with a library)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
graspsynth="${root}/${1:-build}/apps/graspsynth"
shift || true
out="${root}/experiments/results"
cd "${root}"

# the objects with a library: the pan's, then the others' in name order.
objects=("$@")
if [ ${#objects[@]} -eq 0 ]; then
  objects=(pan)
  for lib in learning_data/objects/*/library.json; do
    [ -e "${lib}" ] && objects+=("$(basename "$(dirname "${lib}")")")
  done
fi

for name in "${objects[@]}"; do
  if [ "${name}" = pan ]; then
    demos=learning_data/demos
    library=learning_data/library.json
  else
    demos="learning_data/objects/${name}/demos"
    library="learning_data/objects/${name}/library.json"
  fi
  dir="${out}/objects/${name}"
  mkdir -p "${dir}"
  echo "== ${name}"
  "${graspsynth}" analyze "${demos}" --object "${name}" --out "${dir}/analysis.json" > /dev/null
  "${graspsynth}" generalize --object "${name}" --library "${library}" --orientations 20:100:1 \
    --methods nearest,interp,interp+refine,line+refine --perturb 10 --seed 1 \
    --name generalization --out "${dir}"
done

# the table: every object with results (this run's and earlier runs'), the pan first.
python3 - "${out}" <<'EOF'
import csv, json, os, sys
out = sys.argv[1]
names = sorted((n for n in os.listdir(os.path.join(out, "objects"))
                if os.path.exists(os.path.join(out, "objects", n, "generalization.csv"))),
               key=lambda n: (n != "pan", n))
methods = ["nearest", "interp", "interp+refine", "line+refine"]
rows = []
for name in names:
    d = os.path.join(out, "objects", name)
    a = json.load(open(os.path.join(d, "analysis.json")))
    line = a["wrist_line"].get("rms_m")
    radial = a["radial_model"]["rms_m"] if a["radial_model"]["valid"] else None
    per = {m: [0, 0, 0.0] for m in methods}  # rows, nominal successes, robustness sum
    for r in csv.DictReader(open(os.path.join(d, "generalization.csv"))):
        if r["method"] not in per:
            continue
        p = per[r["method"]]
        p[0] += 1
        p[1] += int(r["nominal_success"])
        p[2] += float(r["robustness"])
    rows.append((name, a["counts"]["used"], line, radial, per))

def mm(x):
    return "-" if x is None else "%.1f" % (x * 1e3)

tmp = os.path.join(out, "objects.md.tmp")
with open(tmp, "w") as f:
    f.write("# Objects\n\nWritten by experiments/objects.sh: per shipped object, the wrist-line "
            "fit of its successful demonstrations against the radial strategy (RMS, mm), and "
            "per method over 20-100 deg at 1 deg steps the nominal success (%) and the mean "
            "robustness (10 perturbed replays, the physics perturbed; a row not synthesized "
            "counts 0).\n\n")
    f.write("| object | demos used | line RMS (mm) | radial RMS (mm) | " +
            " | ".join("%s nominal | %s robustness" % (m, m) for m in methods) + " |\n")
    f.write("|---|---:|---:|---:|" + "---:|---:|" * len(methods) + "\n")
    for name, used, line, radial, per in rows:
        cells = []
        for m in methods:
            n, ok, rob = per[m]
            cells += ["%.1f" % (100.0 * ok / n) if n else "-", "%.2f" % (rob / n) if n else "-"]
        f.write("| %s | %d | %s | %s | %s |\n" % (name, used, mm(line), mm(radial),
                                                 " | ".join(cells)))
os.replace(tmp, os.path.join(out, "objects.md"))
tmp = os.path.join(out, "objects.csv.tmp")
with open(tmp, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["object", "demos_used", "line_rms_m", "radial_rms_m", "method", "orientations",
                "nominal_successes", "mean_robustness"])
    for name, used, line, radial, per in rows:
        for m in methods:
            n, ok, rob = per[m]
            w.writerow([name, used, line, radial, m, n, ok, rob / n if n else ""])
os.replace(tmp, os.path.join(out, "objects.csv"))
print("wrote", os.path.join(out, "objects.md"), "and objects.csv")
EOF
