"""Where the LBR iiwa 14 R820 (models/iiwa14_allegro.urdf) stands so that it reaches the study's
table and the pan at theta = 20..100 deg.

    python3 docs/reference/checks/iiwa14_placement.py [--search]

The study's grasps are the hand poses X_WH of the shipped library (learning_data/library.json,
one demonstration per orientation; its waypoints from the pre-grasp to the grasp) and the lift
(the grasp raised 0.12 m). They were made with the Gifu hand, so they stand in for the
Allegro's grasps only as hand poses (frame H, the same convention). For a base pose X_WB (a
position and a yaw about z; the base plate on the floor level with the table top, z = 0 as
the PA-10's), each pose is turned into a flange pose X_BF = X_BW X_WH X_HF (X_FH = Tz(0.02) *
Rz(mount_yaw), the file's mount) and solved by the analytic arm-angle IK of reference/robot.md
1.5 on the PA-10's DH table with the iiwa's lengths and A4's sign turned (the mapping that
iiwa14_fk_check.py proves exact), over the arm angle psi on a 1 deg grid and the 8 branches.
A motion is reachable when one branch has an arm angle feasible (every joint within the
iiwa's limits) at every one of its poses; its "psi width" is the number of such grid degrees.
The joint margins (how far the worst joint stays inside its limit) are printed too.

--search scans base positions and mount yaws and prints the best; without it the proposed
placement is evaluated and printed. numpy only.
"""
import json
import math
import os
import sys

try:
    import numpy as np
except ImportError:  # the test suite skips the check (exit 77) where numpy is missing
    print("numpy is missing: check skipped")
    sys.exit(77)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
LIB = os.path.join(ROOT, "learning_data", "library.json")

D_BS, D_SE, D_EW, D_WT = 0.36, 0.42, 0.40, 0.126
MOUNT = 0.02
SIGNS = np.array([1, 1, 1, -1, 1, 1, 1])
LIMITS = np.radians([170, 120, 170, 120, 170, 120, 175])
ALPHA = [-math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2, 0.0]
PSI = np.radians(np.arange(-180, 180, 1.0))
LIFT = 0.12


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def rot_dh(th, al):
    ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(al), math.sin(al)
    return np.array([[ct, -st * ca, st * sa], [st, ct * ca, -ct * sa], [0, sa, ca]])


def quat_matrix(w, x, y, z):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def skew(u):
    return np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def ik_all_psi(R07, p07):
    """DH joint angles for every psi on the grid and each branch: dict (gc2, gc4, gc6) ->
    array (len(PSI), 7), or {} when the wrist is out of reach."""
    xsw = p07 - R07[:, 2] * D_WT - np.array([0, 0, D_BS])
    L = np.linalg.norm(xsw)
    c4 = (L * L - D_SE ** 2 - D_EW ** 2) / (2 * D_SE * D_EW)
    if abs(c4) > 1.0:
        return {}
    out = {}
    s, c = np.sin(PSI)[:, None, None], np.cos(PSI)[:, None, None]
    for gc4 in (1, -1):
        th4 = gc4 * math.acos(c4)
        r = math.hypot(xsw[0], xsw[1])
        th1r = math.atan2(xsw[1], xsw[0]) if r > 1e-9 else 0.0
        th2r = math.atan2(r, xsw[2]) - math.atan2(D_EW * math.sin(th4), D_SE + D_EW * math.cos(th4))
        R03r = rot_dh(th1r, ALPHA[0]) @ rot_dh(th2r, ALPHA[1]) @ rot_dh(0.0, ALPHA[2])
        U = skew(xsw / L)
        As, Bs = U @ R03r, -(U @ U) @ R03r
        Cs = (np.eye(3) + U @ U) @ R03r
        R34 = rot_dh(th4, ALPHA[3])
        Aw, Bw, Cw = (R34.T @ M.T @ R07 for M in (As, Bs, Cs))
        R03 = As * s + Bs * c + Cs
        R47 = Aw * s + Bw * c + Cw
        for gc2 in (1, -1):
            for gc6 in (1, -1):
                q = np.empty((len(PSI), 7))
                q[:, 0] = np.arctan2(-gc2 * R03[:, 1, 1], -gc2 * R03[:, 0, 1])
                q[:, 1] = gc2 * np.arccos(np.clip(-R03[:, 2, 1], -1, 1))
                q[:, 2] = np.arctan2(gc2 * R03[:, 2, 2], -gc2 * R03[:, 2, 0])
                q[:, 3] = th4
                q[:, 4] = np.arctan2(gc6 * R47[:, 1, 2], gc6 * R47[:, 0, 2])
                q[:, 5] = gc6 * np.arccos(np.clip(R47[:, 2, 2], -1, 1))
                q[:, 6] = np.arctan2(gc6 * R47[:, 2, 1], -gc6 * R47[:, 2, 0])
                out[(gc2, gc4, gc6)] = q
    return out


def margins(X_WH_list, base_xy, base_yaw, mount_yaw):
    """For one motion (a list of hand poses): per branch, the worst joint margin (rad) over the
    poses at each psi; the motion's best branch, psi width and the margin at its best psi."""
    X_BW_R = rz(base_yaw).T
    X_HF_R = rz(mount_yaw).T
    best = (-1, None, None, None)
    per_branch = {}
    stretch = 0.0
    for R_WH, p_WH in X_WH_list:
        R = X_BW_R @ R_WH @ X_HF_R
        p_H = X_BW_R @ (p_WH - np.array([base_xy[0], base_xy[1], 0.0]))
        p = p_H - R[:, 2] * MOUNT
        x_sw = p - R[:, 2] * D_WT - np.array([0, 0, D_BS])
        stretch = max(stretch, float(np.linalg.norm(x_sw)) / (D_SE + D_EW))
        sols = ik_all_psi(R, p)
        if not sols:
            return 0, None, -math.inf, None, stretch
        for br, q_dh in sols.items():
            q = q_dh * SIGNS
            m = (LIMITS - np.abs(q)).min(axis=1)  # worst joint margin at each psi
            per_branch[br] = np.minimum(per_branch.get(br, np.inf), m)
    for br, m in per_branch.items():
        width = int((m >= 0).sum())
        k = int(np.argmax(m))
        if (width, m[k]) > (best[0], -math.inf if best[2] is None else best[2]):
            best = (width, br, float(m[k]), float(np.degrees(PSI[k])))
    return best + (stretch,)


def motions():
    lib = json.load(open(LIB))
    out = []
    for e in lib["entries"]:
        w = e["motion"]["waypoints"]
        poses = [(quat_matrix(*p["quaternion"]), np.array(p["position"])) for p in w[::10]]
        poses.append((quat_matrix(*w[-1]["quaternion"]), np.array(w[-1]["position"])))
        R, p = poses[-1]
        poses.append((R, p + np.array([0, 0, LIFT])))
        out.append((e["theta_deg"], poses))
    return out


def evaluate(ms, base_xy, base_yaw, mount_yaw, show=False):
    worst_width, worst_margin, worst_stretch = 10 ** 9, math.inf, 0.0
    for theta, poses in ms:
        width, br, margin, psi, stretch = margins(poses, base_xy, base_yaw, mount_yaw)
        worst_width = min(worst_width, width)
        worst_margin = min(worst_margin, margin)
        worst_stretch = max(worst_stretch, stretch)
        if show:
            print("  theta %5.1f: psi width %3d deg, branch (gc2, gc4, gc6) %s, best psi %s deg, "
                  "worst joint %.1f deg inside its limit, shoulder-wrist %.2f of full stretch"
                  % (theta, width, br, "-" if psi is None else "%.0f" % psi,
                     math.degrees(margin) if margin > -math.inf else float("nan"), stretch))
    return worst_width, worst_margin, worst_stretch


# the proposal: the base where the PA-10's stands (the world origin), A1's zero toward +x as
# the PA-10's, the hand mounted without a turn
PROPOSED = {"base_xy": (0.2, -0.2), "base_yaw": 0.0, "mount_yaw": 0.0}


def main():
    ms = motions()
    if "--search" in sys.argv:
        rows = []
        for mount_deg in (0,):  # 180 and -90 give the same: A7 +- pi is the other gc6 branch
            for bx in np.arange(-0.2, 0.51, 0.05):
                for by in np.arange(-0.4, 0.21, 0.05):
                    w, m, st = evaluate(ms, (bx, by), 0.0, math.radians(mount_deg))
                    rows.append((w, m, st, bx, by, mount_deg))
        # a placement must leave the arm bent (at most 0.95 of full stretch, the lift included)
        rows = [r for r in rows if r[2] <= 0.95]
        rows.sort(key=lambda r: (-r[0], -r[1]))
        print("best placements with the arm at most 0.95 of full stretch (worst psi width over "
              "theta, worst joint margin, worst stretch, x, y, mount):")
        for w, m, st, bx, by, md in rows[:12]:
            print("  %3d deg  %6.1f deg  %.2f  (%.2f, %.2f) m  mount %d deg"
                  % (w, math.degrees(m), st, bx, by, md))
        return
    print("proposed base %s, base yaw %.0f deg, mount yaw %.0f deg:"
          % (PROPOSED["base_xy"], math.degrees(PROPOSED["base_yaw"]),
             math.degrees(PROPOSED["mount_yaw"])))
    w, m, st = evaluate(ms, PROPOSED["base_xy"], PROPOSED["base_yaw"], PROPOSED["mount_yaw"],
                        True)
    print("worst psi width %d deg, worst joint margin %.1f deg, worst stretch %.2f"
          % (w, math.degrees(m), st))
    if w <= 0:
        sys.exit(1)


if __name__ == "__main__":
    main()
