#!/usr/bin/env bash
# Plots of experiment 2 from its CSV files (gnuplot, SVG): nominal success and robustness
# against orientation, one line per method.
#
#   experiments/plot_generalization.sh RESULTS_DIR
set -euo pipefail
out="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "${tmp}"' EXIT
# one whitespace-separated file per method: theta nominal_success robustness
for csv in generalization extrapolation; do
  # a blank line where the orientations jump (0-19, then 101-120): gnuplot breaks the line.
  awk -F, -v dir="${tmp}" -v stem="${csv}" 'NR > 1 {
      gsub(/[+\/]/, "_", $2);
      f = dir "/" stem "_" $2 ".dat";
      if ((f in last) && $1 - last[f] > 1.5) print "" > f;
      last[f] = $1;
      print $1, $7, $11 > f }' "${out}/${csv}.csv"
done
plot_lines() {
  local column="$1" first=1
  for f in "${tmp}"/generalization_*.dat "${tmp}"/extrapolation_line_refine.dat; do
    local title
    title="$(basename "${f}" .dat | sed 's/^generalization_//; s/^extrapolation_/extrapolation: /; s/_refine/+refine/')"
    [[ ${first} == 1 ]] || printf ', '
    printf "'%s' using 1:%s with linespoints title '%s'" "${f}" "${column}" "${title}"
    first=0
  done
}
gnuplot <<GNUPLOT
set terminal svg size 900,700 font 'sans,11'
set output '${out}/generalization.svg'
set multiplot layout 2,1
set xrange [0:120]
set grid
set key outside right
set ylabel 'robustness (10 replays)'
set yrange [-0.05:1.05]
set title 'Robustness of the synthesized grasp against orientation'
plot $(plot_lines 3)
set title 'Nominal trial succeeded (1) or failed (0)'
set ylabel 'nominal success'
set xlabel 'object orientation theta (deg)'
plot $(plot_lines 2)
unset multiplot
GNUPLOT
echo "wrote ${out}/generalization.svg"
