#!/usr/bin/env python3
"""Measures candidate grips of the synthetic operator in ODE and in MuJoCo (issue 45).

For each grip (a JSON object of GraspStyle fields in the operator file's units, applied over
the strategy's own grip) and each orientation, the operator's noise-free trial is generated
(`demos generate`, one trial, the first strategy of the orientation's plan or --strategy), its
demonstration is scored by `select --perturb 20 --all-replays` (20 ODE replays under the motion
and physics perturbations: the `sel` column) and becomes a grasp file (`synthesize --method
nearest --no-refine --perturb 0 --force`: the demonstration's grasping motion after a planned
reach), and that grasp is played in ODE (nominal, and --perturb N perturbed replays) and in
MuJoCo (stiff and soft finger servos). One line per (grip, orientation): the demonstration's
simulated outcome, the selection score, and per engine the outcome, lift, slip (mm, deg) and
load bearers; --out keeps them all as JSON (load shares included). Runs are deterministic: the
operator's noise is off and every seed fixed. About 40 s of wall time per (grip, orientation)
on 2 busy cores; the grips measured for issue 45 are experiments/grips/pan_candidates.json.

    experiments/grip_sweep.py --grips experiments/grips/pan_candidates.json \
        --thetas 20,40,70,100 --out results.json [--operator learning_data/demos/operator.json]
        [--object NAME] [--perturb 10] [--jobs 2] [--work DIR]

grips.json: {"name": {grip fields...}, ...}; {} (an empty grip) is the operator's own grip.
Besides GraspStyle fields a grip may hold "@open" / "@closed" ({joint index: deg}, edits of the
strategy's hand shapes, f0..f15 = thumb j1-j4, then abduction, MCP, PIP of index, middle, ring,
little), "@keep_open" ([joint index, ...]: joints that stay as opened), "@THETA" (fields for that orientation only), "@d" and "@eta" (the wrist's place) and
"@top" (top-level operator fields, e.g. close_duration).
A theta without a plan in the operator file takes the nearest plan's strategy, its polar angles
turned with the object (the wrist where the nearest plan's is, relative to the handle).
"""

import argparse
import concurrent.futures
import json
import os
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
NOISE = ("timing_spread", "position_noise", "height_noise", "yaw_noise_deg", "path_noise",
         "finger_noise_deg", "sloppy_fraction")


def reduced_config(config, theta, grip, strategy_index):
    """The operator file for one noise-free trial at theta with the grip over the strategy's."""
    c = json.loads(json.dumps(config))
    for key in NOISE:
        c[key] = 0.0
    plans = sorted(config["plans"], key=lambda p: abs(p["theta_deg"] - theta))
    plan = json.loads(json.dumps(plans[0]))
    turn = theta - plan["theta_deg"]
    plan["theta_deg"] = float(theta)
    plan["trials"] = 1
    plan["pregrasp_eta_deg"] += turn
    s = plan["strategies"][min(strategy_index, len(plan["strategies"]) - 1)]
    s["eta_deg"] += turn
    own = s.get("grasp", {})
    own.update({key: v for key, v in grip.items() if not key.startswith("@")})
    per_theta = grip.get("@%d" % theta, {})
    own.update(per_theta)
    # "@open" / "@closed": {joint index: deg} edits of the strategy's own hand shapes.
    for key, field in (("@open", "open_hand_deg"), ("@closed", "closed_hand_deg")):
        if key in grip:
            hand = list(own.get(field) or config[field])
            for j, v in grip[key].items():
                hand[int(j)] = v
            own[field] = hand
    # "@keep_open": [joint index, ...]: those joints do not move when the hand closes.
    if "@keep_open" in grip:
        opened = own.get("open_hand_deg") or config["open_hand_deg"]
        closed = list(own.get("closed_hand_deg") or config["closed_hand_deg"])
        for j in grip["@keep_open"]:
            closed[j] = opened[j]
        own["closed_hand_deg"] = closed
    if own:
        s["grasp"] = own
    if "@d" in grip:
        s["d"] = grip["@d"]
    if "@eta" in grip:
        s["eta_deg"] = grip["@eta"]
    plan["strategies"] = [s]
    c["plans"] = [plan]
    c.update(grip.get("@top", {}))
    return c


def run(args, cwd=None):
    return subprocess.run(args, capture_output=True, text=True, cwd=cwd)


def essentials(report_path):
    if not os.path.exists(report_path):
        return None
    with open(report_path) as f:
        r = json.load(f)
    n = r["nominal"]
    h = n.get("hold") or {}
    out = {"outcome": n["outcome"], "lift_mm": round(1000 * n.get("lift_m", 0.0), 1),
           "slip_mm": round(1000 * h.get("slip_m", 0.0), 1),
           "slip_deg": round(h.get("slip_deg", 0.0), 1),
           "tilt_deg": round(h.get("end_tilt_deg", 0.0), 1),
           "bearers": h.get("load_bearers", ""),
           "share": {k: round(v, 2) for k, v in (h.get("load_share") or {}).items()}}
    rob = r.get("robustness") or {}
    if rob.get("trials"):
        out["perturbed"] = "%d/%d" % (rob["successes"], rob["trials"])
        out["perturbed_outcomes"] = {}
        for t in r.get("trials", []):
            out["perturbed_outcomes"][t["outcome"]] = out["perturbed_outcomes"].get(
                t["outcome"], 0) + 1
    return out


def evaluate(g, config, name, grip, theta, work, perturb, strategy, obj):
    d = os.path.join(work, "%s_t%03d" % (name, theta))
    os.makedirs(d, exist_ok=True)
    cfg = os.path.join(d, "operator.json")
    with open(cfg, "w") as f:
        json.dump(reduced_config(config, theta, grip, strategy), f, indent=1)
    demos = os.path.join(d, "demos")
    objflag = ["--object", obj] if obj else []
    run([g, "demos", "generate", "--operator", cfg, "--out", demos, "--quiet"] + objflag)
    row = {"grip": name, "theta": theta}
    logs = [x for x in os.listdir(demos)] if os.path.isdir(demos) else []
    demo_outcome = "none"
    for x in logs:
        with open(os.path.join(demos, x)) as f:
            for line in f:
                if "simulated_outcome" in line:
                    demo_outcome = line.strip().split(",")[-1].split(":")[-1].strip()
    row["demo"] = demo_outcome
    lib = os.path.join(d, "library.json")
    run([g, "select", demos, "--out", lib, "--perturb", "20", "--all-replays"] + objflag)
    grasp = os.path.join(d, "grasp.json")
    if os.path.exists(lib):
        with open(lib) as f:
            scores = json.load(f)["scores"]
        if scores:
            row["select"] = "%d/%d" % (scores[0]["successes"], scores[0]["trials"])
        run([g, "synthesize", "--library", lib, "--theta", str(theta), "--method", "nearest",
             "--no-refine", "--perturb", "0", "--force", "--out", grasp] + objflag)
    if not os.path.exists(grasp):
        row["error"] = "no grasp (demonstration not lifted?)"
        return row
    for eng, extra in (("ode", ["--perturb", str(perturb)] if perturb else []),
                       ("mj_stiff", ["--engine", "mujoco", "--mujoco-servo", "stiff"]),
                       ("mj_soft", ["--engine", "mujoco", "--mujoco-servo", "soft"])):
        rep = os.path.join(d, eng + ".json")
        run([g, "simulate", grasp, "--out", rep] + extra + objflag)
        row[eng] = essentials(rep)
    return row


def line(row):
    def cell(e):
        if not e:
            return "-"
        s = "%s lift %.0f slip %.0fmm/%.0fdeg %s" % (e["outcome"], e["lift_mm"], e["slip_mm"],
                                                   e["slip_deg"], e["bearers"])
        if "perturbed" in e:
            s += " pert %s" % e["perturbed"]
        return s
    return "%-14s %4d demo=%-12s sel=%-5s | ODE %s | MJs %s | MJsoft %s %s" % (
        row["grip"], row["theta"], row["demo"], row.get("select", "-"), cell(row.get("ode")), cell(row.get("mj_stiff")),
        cell(row.get("mj_soft")), row.get("error", ""))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--grips", required=True)
    p.add_argument("--thetas", default="20,40,70,100")
    p.add_argument("--operator", default=os.path.join(HERE, "..", "learning_data", "demos",
                                                      "operator.json"))
    p.add_argument("--object", default="")
    p.add_argument("--strategy", type=int, default=0)
    p.add_argument("--perturb", type=int, default=0)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--work", default=os.path.join(tempfile.gettempdir(), "grips-sweep"),
                   help="scratch folder of the trials (default: grips-sweep in the temp folder)")
    p.add_argument("--out", required=True)
    p.add_argument("--graspsynth", default=os.path.join(HERE, "..", "build", "apps",
                                                        "graspsynth"))
    a = p.parse_args()
    with open(a.operator) as f:
        config = json.load(f)
    with open(a.grips) as f:
        grips = json.load(f)
    thetas = [int(t) for t in a.thetas.split(",")]
    jobs = [(n, grips[n], t) for n in grips for t in thetas]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
        futs = [ex.submit(evaluate, a.graspsynth, config, n, gr, t, a.work, a.perturb,
                          a.strategy, a.object) for n, gr, t in jobs]
        for fu in futs:
            row = fu.result()
            rows.append(row)
            print(line(row), flush=True)
    with open(a.out, "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
