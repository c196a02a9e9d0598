"""Writes models/iiwa14_allegro.urdf: a KUKA LBR iiwa 14 R820 carrying an Allegro Hand (right).

    python3 models/make_iiwa14_allegro.py        # rewrites the URDF byte for byte

Every number below is a published figure (its source is in models/README.md, section
"iiwa14_allegro.urdf", and in the comment beside it) or an estimate marked [E]. The file is ours:
the frames follow models/pa10_gifu3.urdf (each arm joint turns about its own z axis, its origin
a roll of +-90 deg and an offset along the previous link), not the frames of any published file.
Where a published inertial is given in another frame (Drake's iiwa14 link frames differ from ours
by a turn of pi about the joint axis on some links), it is carried over into ours by that turn;
docs/reference/checks/iiwa14_fk_check.py checks the centre of mass of the whole arm against the
published frames.

Plain Python with numpy (which /usr/bin/python3 has).
"""
import math
import os

import numpy as np

PI = math.pi
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "iiwa14_allegro.urdf")


# --------------------------------------------------------------------------- rotations
def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rpy_matrix(rpy):
    """URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    return rz(rpy[2]) @ ry(rpy[1]) @ rx(rpy[0])


def matrix_rpy(R):
    """Inverse of rpy_matrix (pitch within +-pi/2); exact zeros and +-pi/2 come back clean."""
    pitch = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    if abs(math.cos(pitch)) < 1e-12:
        roll, yaw = math.atan2(-R[1, 2], R[1, 1]), 0.0
    else:
        roll = math.atan2(R[2, 1], R[2, 2])
        yaw = math.atan2(R[1, 0], R[0, 0])
    return [clean(roll), clean(pitch), clean(yaw)]


def clean(x):
    """Rounds away roundoff next to 0, +-pi/2 and +-pi so that the file shows exact values."""
    for v in (0.0, PI / 2, -PI / 2, PI, -PI):
        if abs(x - v) < 1e-12:
            return v
    return x


def pose(xyz=(0, 0, 0), rpy=(0, 0, 0)):
    X = np.eye(4)
    X[:3, :3] = rpy_matrix(rpy)
    X[:3, 3] = xyz
    return X


# --------------------------------------------------------------------------- inertias
def box_inertia(m, size):
    a, b, c = size
    return np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])


def cylinder_inertia(m, r, h):
    ixx = m * (3 * r * r + h * h) / 12
    return np.diag([ixx, ixx, m * r * r / 2])


def sphere_inertia(m, r):
    return np.eye(3) * (2.0 / 5.0) * m * r * r


def shape_volume(s):
    if s["kind"] == "box":
        return s["size"][0] * s["size"][1] * s["size"][2]
    if s["kind"] == "cylinder":
        return PI * s["r"] ** 2 * s["h"]
    if s["kind"] == "sphere":
        return 4.0 / 3.0 * PI * s["r"] ** 3
    raise ValueError(s["kind"])


def shape_inertia_about_centre(s, m):
    if s["kind"] == "box":
        I = box_inertia(m, s["size"])
    elif s["kind"] == "cylinder":
        I = cylinder_inertia(m, s["r"], s["h"])
    else:
        I = sphere_inertia(m, s["r"])
    R = s["X"][:3, :3]
    return R @ I @ R.T


def inertial_from_shapes(mass, shapes):
    """The link's mass spread with uniform density over its shapes (as pa10_gifu3.urdf):
    centre of mass and inertia about it, in link axes."""
    vols = [shape_volume(s) for s in shapes]
    total = sum(vols)
    com = sum(v / total * s["X"][:3, 3] for v, s in zip(vols, shapes))
    I = np.zeros((3, 3))
    for v, s in zip(vols, shapes):
        m = mass * v / total
        d = s["X"][:3, 3] - com
        I += shape_inertia_about_centre(s, m) + m * (d @ d * np.eye(3) - np.outer(d, d))
    return com, I


def box(size, xyz=(0, 0, 0), rpy=(0, 0, 0)):
    return {"kind": "box", "size": size, "X": pose(xyz, rpy)}


def cyl(r, h, xyz=(0, 0, 0), rpy=(0, 0, 0)):
    return {"kind": "cylinder", "r": r, "h": h, "X": pose(xyz, rpy)}


def sphere(r, xyz=(0, 0, 0)):
    return {"kind": "sphere", "r": r, "X": pose(xyz)}


# --------------------------------------------------------------------------- arm data
DEG = PI / 180.0
# KUKA, "LBR iiwa 7 R800, LBR iiwa 14 R820 Specification" (Spez LBR iiwa V5, 2015), LBR iiwa
# 14 R820 axis data: range, speed and torque per axis; the same values are in Drake's and
# ROS-Industrial's iiwa14 descriptions (85 deg/s = 1.4835 rad/s, 320 N m, ...).
ARM_RANGE_DEG = [170, 120, 170, 120, 170, 120, 175]
ARM_SPEED_DEG_S = [85, 85, 100, 75, 130, 135, 135]
ARM_TORQUE_NM = [320, 320, 176, 176, 110, 40, 40]

# Published joint positions (Drake manipulation/models/iiwa_description/urdf/iiwa14_*.urdf,
# ROS-Industrial kuka_lbr_iiwa_support lbr_iiwa_14_r820): the offset of each joint from the
# previous one along the arm, m. 0.1575 + 0.2025 = 0.36 (base to shoulder), 0.2045 + 0.2155 =
# 0.42 (shoulder to elbow), 0.1845 + 0.2155 = 0.40 (elbow to wrist), 0.081 + 0.045 = 0.126
# (wrist to flange) are KUKA's dimensions of the LBR iiwa 14 R820.
ARM_OFFSETS = [0.1575, 0.2025, 0.2045, 0.2155, 0.1845, 0.2155, 0.081]
FLANGE_OFFSET = 0.045

# Our joint origins (xyz, rpy): joint i turns about its own z; a roll of +-pi/2 and the offset
# along the previous link's axis. The roll signs give the published axis directions at q = 0:
# A1 +z, A2 +y, A3 +z, A4 -y, A5 +z, A6 +y, A7 +z (world, arm straight up).
H = PI / 2
ARM_JOINTS = [
    ("A1", (0, 0, ARM_OFFSETS[0]), (0, 0, 0)),
    ("A2", (0, 0, ARM_OFFSETS[1]), (-H, 0, 0)),
    ("A3", (0, -ARM_OFFSETS[2], 0), (H, 0, 0)),
    ("A4", (0, 0, ARM_OFFSETS[3]), (H, 0, 0)),
    ("A5", (0, ARM_OFFSETS[4], 0), (-H, 0, 0)),
    ("A6", (0, 0, ARM_OFFSETS[5]), (-H, 0, 0)),
    ("A7", (0, -ARM_OFFSETS[6], 0), (H, 0, 0)),
]

# Drake's published chain (iiwa14_*.urdf joint origins, xyz and rpy; every axis 0 0 1), only to
# carry its link inertials into our frames.
DRAKE_JOINTS = [
    ((0, 0, 0.1575), (0, 0, 0)),
    ((0, 0, 0.2025), (H, 0, PI)),
    ((0, 0.2045, 0), (H, 0, PI)),
    ((0, 0, 0.2155), (H, 0, 0)),
    ((0, 0.1845, 0), (-H, PI, 0)),
    ((0, 0, 0.2155), (H, 0, 0)),
    ((0, 0.081, 0), (-H, PI, 0)),
]
# Drake's iiwa14 inertials (iiwa_link_0 .. iiwa_link_7): mass kg, centre of mass m and the
# principal moments kg m^2 about it, in Drake's link frames.
DRAKE_INERTIALS = [
    (5.0, (-0.1, 0, 0.07), (0.05, 0.06, 0.03)),
    (5.76, (0, -0.03, 0.12), (0.033, 0.0333, 0.0123)),
    (6.35, (0.0003, 0.059, 0.042), (0.0305, 0.0304, 0.011)),
    (3.5, (0, 0.03, 0.13), (0.025, 0.0238, 0.0076)),
    (3.5, (0, 0.067, 0.034), (0.017, 0.0164, 0.006)),
    (3.5, (0.0001, 0.021, 0.076), (0.01, 0.0087, 0.00449)),
    (1.8, (0, 0.0006, 0.0004), (0.0049, 0.0047, 0.0036)),
    (1.2, (0, 0, 0.02), (0.001, 0.001, 0.001)),
]
# Collision primitives in Drake's link frames (iiwa14_primitive_collision.urdf: cylinders for
# links 0-5); links 6 and 7 and the flange are ours [E] (Drake uses meshes there).
DRAKE_SHAPES = [
    [cyl(0.139, 0.17, (-0.015, 0, 0.07))],
    [cyl(0.101, 0.29, (0, -0.014, 0.14))],
    [cyl(0.101, 0.29, (0, 0.056, 0.035), (H, 0, 0))],
    [cyl(0.092, 0.29, (0, 0.025, 0.137))],
    [cyl(0.092, 0.25, (0, 0.056, 0.025), (H, 0, 0))],
    [cyl(0.07, 0.29, (0, 0.03, 0.13), (-0.3, 0, 0))],
    None,
    None,
]
# ours [E], in our link frames: the A6 housing (a cylinder along the A6 axis, about the wrist
# centre, r 0.07 like link 5's) and the A7 drive up to the flange (r 0.05, 0.081 + 0.045 long
# less the housing's half length).
OWN_SHAPES = {
    6: [cyl(0.07, 0.14, (0, 0, 0))],
    7: [cyl(0.05, 0.045, (0, 0, 0.0225))],
}


def chain_frames(joints):
    X = np.eye(4)
    out = [X.copy()]
    for xyz, rpy in joints:
        X = X @ pose(xyz, rpy)
        out.append(X.copy())
    return out


def arm_links():
    ours = chain_frames([(xyz, rpy) for _, xyz, rpy in ARM_JOINTS])
    drake = chain_frames(DRAKE_JOINTS)
    links = []
    for i in range(8):
        X_rel = np.linalg.inv(ours[i]) @ drake[i]  # Drake's link frame in ours (q = 0)
        # the two frames differ by a signed permutation (a turn of 0 or pi about z) and no shift
        assert np.allclose(X_rel, np.round(X_rel), atol=1e-12), X_rel
        X_rel = np.round(X_rel) + 0.0
        R = X_rel[:3, :3]
        m, com, moments = DRAKE_INERTIALS[i]
        inertial = (m, R @ np.array(com) + X_rel[:3, 3], R @ np.diag(moments) @ R.T)
        if DRAKE_SHAPES[i] is not None:
            shapes = []
            for s in DRAKE_SHAPES[i]:
                t = dict(s)
                t["X"] = X_rel @ s["X"]
                shapes.append(t)
        else:
            shapes = OWN_SHAPES[i]
        links.append((inertial, shapes))
    return links


# --------------------------------------------------------------------------- hand data
# Wonik Robotics / SimLab, allegro_hand_description_right (allegro_hand_ros and
# allegro_hand_ros_v4): the palm's base_link has its origin where the fingers start, the palm
# box below it (z -0.095..0); the wrist (mounting face) is 0.095 below base_link. Our palm frame
# P = H is at the wrist plane, so every Allegro base_link position is shifted by +0.095 in z.
PALM_Z = 0.095
PALM_BOX = (0.0408, 0.1130, 0.095)
PALM_BOX_CENTRE = (-0.0093, 0.0, -0.0475 + PALM_Z)
PALM_MASS = 0.4154
LINK_X, LINK_Y = 0.0196, 0.0275                         # finger link boxes, m
FINGER_LEN = [0.0164, 0.054, 0.0384, 0.0267]            # joint 0 -> 1 -> 2 -> 3 -> tip centre
THUMB_LEN = [None, 0.0177, 0.0514, 0.0423]               # joint 13 -> 14 -> 15 -> tip centre
TIP_R = 0.012                                            # fingertip sphere radius
FINGER_MASS = [0.0119, 0.065, 0.0355, 0.0096 + 0.0168]   # link_0..3 (+ the tip's 0.0168)
THUMB_MASS = [0.0176, 0.0119, 0.038, 0.0388 + 0.0168]    # link_12..15 (+ the tip's 0.0168)
# limits, rad (v4 xacro: limit -+ its 0.1 rad safety margin; the same numbers as the
# earlier allegro_hand_description_right.urdf)
FINGER_LIMITS = [(-0.47, 0.47), (-0.196, 1.61), (-0.174, 1.709), (-0.227, 1.618)]
THUMB_LIMITS = [(0.263, 1.396), (-0.105, 1.163), (-0.189, 1.644), (-0.162, 1.719)]
HAND_VELOCITY = 7.0     # rad/s: the description's <limit velocity="7">
HAND_EFFORT = 0.7       # N m: the hand's maximum joint torque (Allegro Hand user's manual v4)
# finger bases in Allegro's base_link: y, z and the roll that fans the finger out
FINGER_BASES = [
    ("index", (0, 0.0435, -0.001542), -5 * DEG),
    ("middle", (0, 0, 0.0007), 0.0),
    ("ring", (0, -0.0435, -0.001542), 5 * DEG),
]
THUMB_BASE = ((-0.0182, 0.019333, -0.045987), (0, -95 * DEG, -90 * DEG))
THUMB_J2_ORIGIN = (-0.027, 0.005, 0.0399)
THUMB_BASE_BOX = ((0.0358, 0.034, 0.0455), (-0.0179, 0.009, 0.0145))
# the mount [E]: an adapter plate between the iiwa's media flange and the Allegro's wrist
MOUNT_LEN, MOUNT_R, MOUNT_MASS = 0.02, 0.045, 0.1
MOUNT_YAW = 0.0   # X_FH = Tz(0.02) * Rz(MOUNT_YAW): docs/reference/checks/iiwa14_placement.py


# --------------------------------------------------------------------------- writing
def num(x):
    if x == 0:
        return "0"
    s = repr(float(x))
    return s[:-2] if s.endswith(".0") else s


def vec(v):
    return " ".join(num(clean(float(x))) for x in v)


def inertia_attrs(I):
    return ('ixx="%.10e" ixy="%.10e" ixz="%.10e" iyy="%.10e" iyz="%.10e" izz="%.10e"'
            % (I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2])).replace("-0.0000000000e+00",
                                                                               "0.0000000000e+00")


def shape_lines(s, tag):
    xyz = [clean(float(x)) for x in s["X"][:3, 3]]
    xyz = [0.0 if abs(x) < 1e-15 else x for x in xyz]
    rpy = matrix_rpy(s["X"][:3, :3])
    if s["kind"] == "box":
        g = '<box size="%s"/>' % vec(s["size"])
    elif s["kind"] == "cylinder":
        g = '<cylinder radius="%s" length="%s"/>' % (num(s["r"]), num(s["h"]))
    else:
        g = '<sphere radius="%s"/>' % num(s["r"])
    return ["    <%s>" % tag,
            '      <origin xyz="%s" rpy="%s"/>' % (vec(xyz), vec(rpy)),
            "      <geometry>%s</geometry>" % g,
            "    </%s>" % tag]


def link_lines(name, mass, com, I, shapes, comment=None):
    out = []
    if comment:
        out.append("  <!-- %s -->" % comment)
    out.append('  <link name="%s">' % name)
    out += ["    <inertial>",
            '      <origin xyz="%s" rpy="0 0 0"/>' % vec([round(float(c), 12) for c in com]),
            '      <mass value="%s"/>' % num(mass),
            "      <inertia %s/>" % inertia_attrs(I),
            "    </inertial>"]
    for tag in ("collision", "visual"):
        for s in shapes:
            out += shape_lines(s, tag)
    out.append("  </link>")
    return out


def joint_lines(name, kind, parent, child, xyz, rpy, axis=None, limit=None, comment=None):
    out = []
    if comment:
        out.append("  <!-- %s -->" % comment)
    out += ['  <joint name="%s" type="%s">' % (name, kind),
            '    <parent link="%s"/>' % parent,
            '    <child link="%s"/>' % child,
            '    <origin xyz="%s" rpy="%s"/>' % (vec(xyz), vec(rpy))]
    if axis is not None:
        out.append('    <axis xyz="%s"/>' % vec(axis))
    if limit is not None:
        lo, hi, effort, vel = limit
        out.append('    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>'
                   % (num(lo), num(hi), num(effort), num(vel)))
    out.append("  </joint>")
    return out


HEADER = """<?xml version="1.0"?>
<!--
  graspsynth robot description: KUKA LBR iiwa 14 R820 carrying an Allegro Hand (right, v4).
  Written by models/make_iiwa14_allegro.py (python3 models/make_iiwa14_allegro.py rewrites it);
  every number's source: models/README.md, section "iiwa14_allegro.urdf". Numbers carry over
  from the published descriptions; the file and its frames are ours.

  Conventions used in this file (those of pa10_gifu3.urdf unless said)
  - SI units, angles in radians.
  - Arm joints A1..A7 (KUKA's axis names). Joint i's origin is a roll of +-pi/2 and the
    published offset along the previous link; it turns about its own z axis. The roll signs give
    the published axis directions: at q = 0 (arm straight up) A1 +z, A2 +y, A3 +z, A4 -y, A5 +z,
    A6 +y, A7 +z in the base frame. Joint origins sit at the published joint positions (A1 at
    0.1575 m, A2 at the shoulder centre 0.36 m, A3 at 0.5645 m, A4 at the elbow 0.78 m, A5 at
    0.9645 m, A6 at the wrist centre 1.18 m, A7 at 1.261 m); the flange F (flange_link, fixed) is
    0.045 m beyond A7: 1.306 m at q = 0, with F parallel to the base frame.
    Unlike the PA-10, the iiwa's A4 turns about -y at q = 0, so the PA-10's DH table fits it only
    with A4's sign turned (docs/reference/checks/iiwa14_fk_check.py).
  - Arm inertials are the published ones (mass, centre of mass, moments), turned into our link
    frames; they are NOT computed from the collision shapes (pa10_gifu3.urdf's rule), so a check
    that recomputes inertias from shapes must skip the arm links of this file.
  - Hand inertias ARE computed from the shapes (uniform density over them, the link's published
    mass; the fingertip sphere's mass joins the distal link, since tip frames are frames only).
  - Collision shapes are primitives (cylinders, boxes, spheres; no capsules). Visual geometry
    equals collision geometry.
  - Frame H (hand_mount_link) and the palm P = H are the Gifu hand's convention: z toward the
    fingertips, x the palm normal (the side the fingers flex toward), y toward the thumb and
    index; the palm box starts at the wrist plane z = 0. Allegro's base_link is P + 0.095 m in z.
  - Fingers thumb, index, middle, ring (no little finger), four joints each, all actuated: 16.
    Finger j1 turns the finger about its own long axis (Allegro's joint 0: axis 0 0 1, which
    turns the plane the finger flexes in); j2..j4 flex it about y toward +x. No joint is coupled.
-->
<robot name="iiwa14_allegro">
"""


def arm_section():
    out = ["", "  <!-- ============================ LBR iiwa 14 R820 arm ============================ -->", ""]
    links = arm_links()
    names = ["base_link"] + ["%s_link" % j[0] for j in ARM_JOINTS]
    for i in range(8):
        (m, com, I), shapes = links[i]
        out += link_lines(names[i], m, com, I, shapes)
        out.append("")
        if i < 7:
            jn, xyz, rpy = ARM_JOINTS[i]
            rng = ARM_RANGE_DEG[i] * DEG
            out += joint_lines(jn, "revolute", names[i], names[i + 1], xyz, rpy, (0, 0, 1),
                               (-rng, rng, ARM_TORQUE_NM[i], ARM_SPEED_DEG_S[i] * DEG),
                               "%s: +-%d deg, %d deg/s, %d N m" % (jn, ARM_RANGE_DEG[i],
                                                                 ARM_SPEED_DEG_S[i],
                                                                 ARM_TORQUE_NM[i]))
            out.append("")
    out += joint_lines("flange", "fixed", "A7_link", "flange_link", (0, 0, FLANGE_OFFSET),
                       (0, 0, 0), comment="the flange F: 0.045 m beyond A7 (the media flange)")
    out += ["", '  <link name="flange_link"/>', ""]
    return out


def finger_links(lengths, masses, base_shape=None):
    """Shapes and inertials of one finger's four links (link k is the child of joint k)."""
    links = []
    for k in range(4):
        if k == 0 and base_shape is not None:
            shapes = [base_shape]
        elif k == 3:
            L = lengths[3]
            shapes = [box((LINK_X, LINK_Y, L), (0, 0, L / 2)), sphere(TIP_R, (0, 0, L))]
        else:
            L = lengths[k]
            shapes = [box((LINK_X, LINK_Y, L), (0, 0, L / 2))]
        com, I = inertial_from_shapes(masses[k], shapes)
        links.append((masses[k], com, I, shapes))
    return links


def hand_section():
    out = ["  <!-- ============================= Allegro Hand (right) ============================= -->", ""]
    out += joint_lines("hand_mount", "fixed", "flange_link", "hand_mount_link",
                       (0, 0, MOUNT_LEN), (0, 0, MOUNT_YAW),
                       comment="hand mount: X_FH = Tz(%s) * Rz(%s) [E]" % (num(MOUNT_LEN),
                                                                        num(MOUNT_YAW)))
    out.append("")
    shapes = [cyl(MOUNT_R, MOUNT_LEN, (0, 0, -MOUNT_LEN / 2))]
    com, I = inertial_from_shapes(MOUNT_MASS, shapes)
    out += link_lines("hand_mount_link", MOUNT_MASS, com, I, shapes,
                      "frame H: adapter plate between the flange and the palm [E]")
    out += ["", *joint_lines("palm_joint", "fixed", "hand_mount_link", "palm", (0, 0, 0),
                             (0, 0, 0), comment="the palm frame P coincides with H"), ""]
    shapes = [box(PALM_BOX, PALM_BOX_CENTRE)]
    com, I = inertial_from_shapes(PALM_MASS, shapes)
    out += link_lines("palm", PALM_MASS, com, I, shapes,
                      "palm: Allegro's palm box, z 0..0.095 from the wrist plane")
    out.append("")

    # thumb (Allegro joints 12..15)
    xyz, rpy = THUMB_BASE
    thumb = finger_links(THUMB_LEN, THUMB_MASS,
                         box(THUMB_BASE_BOX[0], THUMB_BASE_BOX[1]))
    origins = [((xyz[0], xyz[1], xyz[2] + PALM_Z), rpy), (THUMB_J2_ORIGIN, (0, 0, 0)),
               ((0, 0, THUMB_LEN[1]), (0, 0, 0)), ((0, 0, THUMB_LEN[2]), (0, 0, 0))]
    axes = [(-1, 0, 0), (0, 0, 1), (0, 1, 0), (0, 1, 0)]
    roles = ["thumb rotation toward the palm (Allegro joint 12)",
             "thumb rotation about its own axis (Allegro joint 13)",
             "thumb flexion (Allegro joint 14)", "thumb tip flexion (Allegro joint 15)"]
    out += finger_section("thumb", origins, axes, THUMB_LIMITS, thumb, roles, THUMB_LEN[3])

    for n, (name, (bx, by, bz), roll) in enumerate(FINGER_BASES):
        links = finger_links(FINGER_LEN, FINGER_MASS)
        origins = [((bx, by, bz + PALM_Z), (roll, 0, 0)), ((0, 0, FINGER_LEN[0]), (0, 0, 0)),
                   ((0, 0, FINGER_LEN[1]), (0, 0, 0)), ((0, 0, FINGER_LEN[2]), (0, 0, 0))]
        axes = [(0, 0, 1), (0, 1, 0), (0, 1, 0), (0, 1, 0)]
        a = 4 * n
        roles = ["finger rotation about its own axis (Allegro joint %d)" % a,
                 "MCP flexion (Allegro joint %d)" % (a + 1),
                 "PIP flexion (Allegro joint %d)" % (a + 2),
                 "DIP flexion (Allegro joint %d)" % (a + 3)]
        out += finger_section(name, origins, axes, FINGER_LIMITS, links, roles, FINGER_LEN[3])
    return out


def finger_section(name, origins, axes, limits, links, roles, tip_len):
    out = []
    parent = "palm"
    for k in range(4):
        child = "%s_link%d" % (name, k + 1)
        lo, hi = limits[k]
        out += joint_lines("%s_j%d" % (name, k + 1), "revolute", parent, child, origins[k][0],
                           origins[k][1], axes[k], (lo, hi, HAND_EFFORT, HAND_VELOCITY),
                           "%s J%d, %s" % (name, k + 1, roles[k]))
        out.append("")
        m, com, I, shapes = links[k]
        out += link_lines(child, m, com, I, shapes)
        out.append("")
        parent = child
    out += joint_lines("%s_tip" % name, "fixed", parent, "%s_tip_link" % name,
                       (0, 0, tip_len), (0, 0, 0),
                       comment="%s tip frame: centre of the fingertip sphere (r 0.012)" % name)
    out += ["", '  <link name="%s_tip_link"/>' % name, ""]
    return out


def main():
    lines = HEADER.rstrip("\n").split("\n") + arm_section() + hand_section() + ["</robot>"]
    with open(OUT, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", OUT)


if __name__ == "__main__":
    main()
