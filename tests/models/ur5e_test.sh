#!/usr/bin/env bash
# models/ur5e.json (issue #16 item 5): a UR5e (robots/ur5e.jsonld) on the
# platform pressing the table with 15 N, its other five end-effector directions
# held. It validates, and lowers to one 6-joint arm mounted where
# pose-ur5e-platform-base says, with five acceleration constraints (angular
# x, y, z, linear y, z) and the contact force on the tip. Its numbers agree:
# at the world's initial configuration (models/ur5e.world.json) the tip is
# 0.6 m ahead of the platform centre with the flange facing +x_P, and the
# contact guards sit 5 cm either side of it.
# Usage: ur5e_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/ur5e.json
chain=https://mospec.example/robots/ur5e/chain

expect "loads" 0 "" -- "$mospec" rdf "$app" --strict
check "loads with no warning" test ! -s "$work/stderr.txt"
validates_clean "$app"

# The scenario's world file (models/ur5e.world.json) makes the UR5e the robot's
# right arm, which binds its chain; on mospec's default robot (two Gen3) the
# chain drives no arm.
echo '{}' > "$work/default.world.json"
expect "refuses the chain on the default robot" 1 \
  "no arm of the robot is bound to the chain '$chain' \(the robot's arms drive arm 0: .*kinova-gen3/chain" \
  -- "$mospec" ir "$app" --world "$work/default.world.json" -o "$work/unbound.json"
expect "lowers with the chain bound to the right arm" 0 "" -- \
  "$mospec" ir "$app" -o "$work/ir.json"
expect "... as --bind CHAIN=right says on the default robot" 0 "" -- \
  "$mospec" ir "$app" --world "$work/default.world.json" --bind "$chain=right" -o "$work/bound.json"

# Reads the IR and the world file; prints one line per failed expectation.
cat > "$work/check.py" <<'PY'
import json, math, sys
from ir_checks import want, single_arm, report
ir = json.load(open(sys.argv[1]))
world = json.load(open(sys.argv[2]))
arm = single_arm(ir)
segs = arm["segments"]
joints = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
          "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]
want([s["joint"] for s in segs] == joints, f"joints {[s['joint'] for s in segs]}")
want(all(s["type"] == "revolute" for s in segs), "every joint revolute")
want(arm["port"] == 0, "bound to the right arm (port 0)")
want(arm["mount"].endswith("/pose-ur5e-platform-base"), f"mount {arm['mount']}")
want(arm["X_RB"] == {"R": [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0], "p": [0.2, 0, 0]},
     f"mount pose {arm['X_RB']}")
want(arm["gravity"] == [0.0, 0.0, -9.81], "gravity")
want(arm["when-idle"]["kind"] == "brake-and-hold", "idle: brake and hold")
components = sorted(c["component"] for c in arm["acceleration-constraints"])
want(components == [0, 1, 2, 4, 5], f"acceleration constraints on {components}")
forces = arm["cartesian-forces"]
want(len(forces) == 1 and forces[0]["segment"] == 5, "one Cartesian force, on the tip")
data = {d["name"]: d for d in ir["data"]}
want(data["frc_ur5e_ee_contact_ref"]["value"] == [15.0], "contact force reference 15 N")
views = [st for st in ir["schedule"] if st["name"] == "assemble_wrench_ur5e_ee_contact"]
want(len(views) == 1, "the contact force assembles the tip's wrench")

# Forward kinematics over the lowered chain (the mount folded into the first
# joint's placement; R row-major) at the world's q.
def matmul(A, B): return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def rot(axis, q):
    x, y, z = axis; c, s = math.cos(q), math.sin(q); t = 1 - c
    return [[c + x*x*t, x*y*t - z*s, x*z*t + y*s],
            [y*x*t + z*s, c + y*y*t, y*z*t - x*s],
            [z*x*t - y*s, z*y*t + x*s, c + z*z*t]]
right = world["arms"]["right"]
q = right["q"]
want(len(q) == 6, "six initial joint positions")
# The arm's actuation is its description's: the URDF's <limit>s, which
# import-urdf kept (issue #33 item 7), one effort and position limit per joint.
want("actuation" not in right, "the world file leaves the actuation to the description")
robot = json.load(open("robots/ur5e.jsonld"))["@graph"]
kinds = [n["@type"][1] for n in robot if isinstance(n["@type"], list) and n["@type"][0] == "JointLimit"]
want(kinds.count("kc-stat:JointForce") == 6 and kinds.count("kc-stat:JointPosition") == 6,
     f"six effort and position limits (kc-ext:JointLimit) in robots/ur5e.jsonld, got {kinds}")
want(world["arms"]["left"] == {"present": False}, "no left arm")
R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]; p = [0.0, 0.0, 0.0]
for s, qi in zip(segs, q):
    Rj = [s["X_PJ"]["R"][0:3], s["X_PJ"]["R"][3:6], s["X_PJ"]["R"][6:9]]
    p = [p[i] + sum(R[i][k] * s["X_PJ"]["p"][k] for k in range(3)) for i in range(3)]
    R = matmul(matmul(R, Rj), rot(s["axis"], qi))
near = lambda a, b, tol: abs(a - b) <= tol
want(near(p[0], 0.6, 1e-4) and near(p[1], -0.1333, 1e-4) and near(p[2], 0.35, 1e-4),
     f"tip at (0.6, -0.1333, 0.35) in P, got {p}")
want(near(R[0][2], 1.0, 1e-4), f"flange z along +x_P, got {[R[i][2] for i in range(3)]}")
lost = data["pos_ur5e_ee_x_contact_lost"]["value"][0]
past = data["pos_ur5e_ee_x_past_table"]["value"][0]
want(near(lost, p[0] - 0.05, 1e-4), f"contact-lost threshold {lost} is 5 cm behind the tip's x {p[0]}")
want(near(past, p[0] + 0.05, 1e-4), f"past-table threshold {past} is 5 cm ahead of the tip's x {p[0]}")
report()
PY
check_program "$work/check.py" "$work/ir.json" models/ur5e.world.json

finish ur5e
