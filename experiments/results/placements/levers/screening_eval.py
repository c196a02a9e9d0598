#!/usr/bin/env python3
"""Physics screening emulated offline (levers/README.md): per placement of screening_seed2.csv,
take the method whose seed-2 rows did better (nominal success, then successes; ties to
interp+refine) and score that choice on the seed-1 rows of ../inside.csv, which chose nothing."""
import csv
import statistics
from pathlib import Path

here = Path(__file__).resolve().parent
scored = {(r["x"], r["y"], r["theta_deg"], r["method"]): r
          for r in csv.DictReader(open(here.parent / "inside.csv"))}
screen = {(r["x"], r["y"], r["theta_deg"], r["method"]): r
          for r in csv.DictReader(open(here / "screening_seed2.csv"))}


def rank(row):
    return (int(row["nominal_success"]), int(row["successes"]))


placements = sorted({k[:3] for k in screen})
plain, chosen, picks = [], [], {"interp+refine": 0, "nearest": 0}
for p in placements:
    pick = ("interp+refine" if rank(screen[p + ("interp+refine",)]) >= rank(screen[p + ("nearest",)])
            else "nearest")
    picks[pick] += 1
    plain.append(float(scored[p + ("interp+refine",)]["robustness"]))
    chosen.append(float(scored[p + (pick,)]["robustness"]))
grid = [float(r["robustness"]) for k, r in scored.items() if k[3] == "interp+refine"]
after = (sum(grid) - sum(plain) + sum(chosen)) / len(grid)
print(f"{len(placements)} screened placements: interp+refine {statistics.mean(plain):.3f}, "
      f"screened {statistics.mean(chosen):.3f} (picked interp+refine {picks['interp+refine']}, "
      f"nearest {picks['nearest']})")
print(f"the inside grid's {len(grid)} rows: {statistics.mean(grid):.3f} -> {after:.3f}")
