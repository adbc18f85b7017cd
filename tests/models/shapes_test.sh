#!/usr/bin/env bash
# mospec's own shapes (metamodels/**/*.ttl): each shape has a conforming and a
# violating data graph (tests/models/data/*-good.json / *-bad.json); the bad one
# must give exactly the expected findings, the good one none (under --strict).
# Then the authors' four apps (skipped when ../shared is absent): mospec's shapes
# add no violation of their own. Usage: shapes_test.sh MOSPEC_BINARY SOURCE_DIR SHARED_DIR
set -u
mospec=$(realpath "$1")
src=$(realpath "$2")
shared=$3
data="$src/tests/models/data"
mm="$src/metamodels"
failures=0
out=$(mktemp)
trap 'rm -f "$out"' EXIT

fail() { echo "FAIL $1"; sed 's/^/  /' "$out"; failures=$((failures+1)); }

# shape_args "A.ttl B.ttl": --shapes options for mospec's shape files.
shape_args() { for f in $1; do printf -- '--shapes\n%s\n' "$mm/$f"; done; }
# good NAME SHAPES: no result at all (no violation, warning or info).
good() {
  mapfile -t args < <(shape_args "$2")
  "$mospec" validate --listed-shapes-only "$data/$1-good.json" "${args[@]}" > "$out" 2>&1
  if [ $? -eq 0 ] && grep -q '^shacl: 0 violations, 0 warnings, 0 infos' "$out"; then
    echo "ok   $1 conforms"; else fail "$1-good does not conform"; fi
}
# bad NAME SHAPES COUNT PATTERN...: exactly COUNT violations, and each PATTERN
# (focus node + message) is among them.
bad() {
  local name=$1 shapes=$2 count=$3; shift 3
  mapfile -t args < <(shape_args "$shapes")
  "$mospec" validate --listed-shapes-only "$data/$name-bad.json" "${args[@]}" > "$out" 2>&1
  local rc=$?
  if [ $rc -ne 1 ]; then fail "$name-bad: exit $rc, expected 1"; return; fi
  if ! grep -q "^shacl: $count violations" "$out"; then fail "$name-bad: expected $count violations"; return; fi
  for p in "$@"; do
    if ! grep -Eq -- "$p" "$out"; then fail "$name-bad: no finding matches /$p/"; return; fi
  done
  echo "ok   $name violations ($count)"
}

good direction-cosine geometry/coordinates.ttl
bad direction-cosine geometry/coordinates.ttl 4 \
  '<https://ex.org/b1>: value does not conform to .*ThreeDoubles.*direction-cosine-x' \
  '<https://ex.org/b2>: direction cosines must form a rotation matrix' \
  '<https://ex.org/b3>: value conforms to none of the shapes of sh:or' \
  '<https://ex.org/b4>: value does not conform to .*ThreeDoubles.*direction-cosine-z'

good units geometry/coordinates.ttl
# A unit that fits none of its quantity's kinds is reported once per kind,
# each naming the units that kind takes.
bad units geometry/coordinates.ttl 6 \
  "<https://ex.org/d>: unit fits none of the quantity's kinds \\(<http://qudt.org/vocab/quantitykind/Distance> takes M\\)" \
  '<https://ex.org/d>: quantity kind has no unit that fits it \(it takes M\)' \
  "<https://ex.org/w>: unit fits none of the quantity's kinds \\(<http://qudt.org/vocab/quantitykind/Force> takes N\\)" \
  "<https://ex.org/w>: unit fits none of the quantity's kinds \\(<http://qudt.org/vocab/quantitykind/Torque> takes N-M\\)" \
  '<https://ex.org/w>: quantity kind has no unit that fits it' \
  '<https://ex.org/v>: quantity kind has no unit that fits it'

good bilateral task/constraint.ttl
bad bilateral task/constraint.ttl 8 \
  '<https://ex.org/c5>: reference value or threshold has a unit the constrained quantity does not have' \
  '<https://ex.org/c5>: reference value or threshold has a quantity kind the constrained quantity does not have' \
  '<https://ex.org/c6>: the constrained quantity has no unit' \
  '<https://ex.org/b1>: lower threshold must be less than the upper threshold \(lower 7\.2E-1, upper 6\.8E-1\)' \
  '<https://ex.org/b2>: a bilateral constraint has exactly one lower threshold' \
  '<https://ex.org/b2>: a bilateral constraint has exactly one upper threshold' \
  '<https://ex.org/b3>: lower and upper threshold must have the same unit' \
  '<https://ex.org/b4>: lower and upper threshold must have the same quantity kind'

good solver "task/solver-specification.ttl task/platform-solvers.ttl"
bad solver "task/solver-specification.ttl task/platform-solvers.ttl" 17 \
  '<https://ex.org/velocity-bad>: a velocity-composition solver has exactly one platform configuration' \
  '<https://ex.org/velocity-bad>: a velocity-composition solver composes exactly one velocity twist' \
  '<https://ex.org/drv-bad>: the motion driver has no level in the prioritisation hierarchy.*ex.org/spec-frc1' \
  '<https://ex.org/drv-bad>: the motion driver has no level in the prioritisation hierarchy.*ex.org/spec-frc2' \
  '<https://ex.org/drv-bad>: a Cartesian-force driver must be a Cartesian force specification' \
  '<https://ex.org/drv-bad>: the prioritisation hierarchy lists prioritisation levels' \
  '<https://ex.org/base-bad>: a force-distribution solver has exactly one platform configuration' \
  '<https://ex.org/base-bad>: a force-distribution solver distributes exactly one wrench' \
  "<https://ex.org/acc-bad>: the acceleration energy is no controller's control signal" \
  '<https://ex.org/spec-acc-bad>: an acceleration-constraint specification has acceleration constraints' \
  '<https://ex.org/spec-frc-bad>: nothing produces the applied wrench' \
  '<https://ex.org/spec-frc3-bad>: nothing produces the applied wrench' \
  '<https://ex.org/s4>: gravity is an acceleration: its unit must be M-PER-SEC2' \
  "<https://ex.org/s1>: gravity must be expressed in the solver's root frame.*g-world" \
  "<https://ex.org/s2>: gravity must be expressed in the solver's root frame.*g-nowhere" \
  '<https://ex.org/s3>: a solver has exactly one root frame'

good handler "task/constraint-handler.ttl task/decaying-integral-term.ttl task/motion-specification.ttl"
bad handler "task/constraint-handler.ttl task/decaying-integral-term.ttl task/motion-specification.ttl" 11 \
  '<https://ex.org/m1>: a post-condition \(until\) must be a constraint' \
  '<https://ex.org/m2>: value conforms to none of the shapes of sh:or' \
  '<https://ex.org/e4>: an evaluator evaluates exactly one constraint' \
  '<https://ex.org/e4>: an error evaluator produces exactly one error signal' \
  "<https://ex.org/k1>: the controller's error signal is produced by no error evaluator" \
  '<https://ex.org/k1>: a decaying integral term has exactly one decay rate in \[0, 1\]' \
  '<https://ex.org/k2>: a PID controller has exactly one proportional gain' \
  '<https://ex.org/k2>: a PID controller has exactly one integral gain' \
  '<https://ex.org/k2>: a PID controller has exactly one derivative gain' \
  '<https://ex.org/h>: every constraint of the handled motion must be evaluated.*not-a-constraint' \
  'warning: <https://ex.org/h>: the handler evaluates a constraint that is not part of its motion.*ex.org/c3' \
  '<https://ex.org/h3>: a pre- or post-condition \(when, until\) must be evaluated by an error evaluator of the handler.*ex.org/c4>'

# The damping and impedance controllers (src/ir/controllers.cpp; the registry
# test ir_controllers_test checks each controller kind has a case here).
ctrl="task/constraint-handler.ttl task/damping-controller.ttl task/impedance-controller.ttl task/motion-specification.ttl"
good controllers "$ctrl"
bad controllers "$ctrl" 12 \
  "<https://ex.org/damp-bad>: a damping controller pairs a linear velocity \\(M-PER-SEC\\) with a force \\(N\\).*ex.org/f-max-nm" \
  '<https://ex.org/damp-bad>: a damping controller.s maximum velocity is one number > 0' \
  '<https://ex.org/damp-none>: a damping controller measures exactly one velocity' \
  '<https://ex.org/damp-none>: a damping controller has exactly one maximum force' \
  '<https://ex.org/damp-none>: a damping controller.s maximum force is in N or N-M' \
  '<https://ex.org/damp-none>: a damping controller.s maximum force is one number > 0' \
  "<https://ex.org/imp-bad>: an impedance controller's control signal, stiffness and damping have the units.*ex.org/k-bad" \
  '<https://ex.org/imp-bad>: mospec.s impedance controller has no apparent inertia' \
  '<https://ex.org/imp-bad>: an impedance controller.s damping is a number >= 0' \
  '<https://ex.org/imp-none>: an impedance controller is a controller' \
  '<https://ex.org/imp-none>: an impedance controller states a stiffness or a damping' \
  "<https://ex.org/h>: a handler's controllers are controllers \\(or damping controllers.*ex.org/x-err"

good unilateral task/unilateral-constraint.ttl
bad unilateral task/unilateral-constraint.ttl 8 \
  '<https://ex.org/u1>: a unilateral constraint has exactly one threshold' \
  '<https://ex.org/u2>: a unilateral constraint has exactly one threshold' \
  '<https://ex.org/u3>: the threshold has a unit the constrained quantity does not have.*ex.org/z-mm>' \
  '<https://ex.org/u4>: the threshold has a quantity kind the constrained quantity does not have.*ex.org/z-len>' \
  '<https://ex.org/u5>: the constrained quantity has no unit' \
  '<https://ex.org/u6>: a unilateral constraint is exactly one of a greater-than and a less-than constraint' \
  '<https://ex.org/u7>: a unilateral constraint is exactly one of a greater-than and a less-than constraint' \
  '<https://ex.org/u8>: a threshold is a quantity with exactly one value and one unit'

good mobile-base mospec/mobile-base.ttl
bad mobile-base mospec/mobile-base.ttl 8 \
  '<https://ex.org/b1>: a castor-drive base lists at least two drives \(CastorDrive\)' \
  '<https://ex.org/b1>: a castor-drive base has exactly one castor offset' \
  "<https://ex.org/b2>: a castor-drive base's lengths are in metres: exactly one unit, M" \
  "<https://ex.org/b2>: a castor-drive base's wheel radius, wheel distance and castor offset are numbers > 0" \
  '<https://ex.org/b2>: a castor-drive base lists at least two drives \(CastorDrive\)' \
  "<https://ex.org/d1>: a castor drive's pivot position is in metres: exactly one unit, M" \
  '<https://ex.org/d1>: a castor drive has exactly one drive weight, a number >= 0' \
  '<https://ex.org/d2>: a castor drive has exactly one moment-alignment weight, a number >= 0'

good quantities mospec/quantities.ttl
bad quantities mospec/quantities.ttl 5 \
  "<https://ex.org/thirty>: the value 'thirty' is not a finite number" \
  "<https://ex.org/nan>: the value 'NaN' is not a finite number" \
  "<https://ex.org/inf>: the value 'INF' is not a finite number" \
  "<https://ex.org/empty>: the value '' is not a finite number" \
  "<https://ex.org/node>: a quantity's value is a literal number, not a node"

good time mospec/time.ttl
bad time mospec/time.ttl 9 \
  '<https://ex.org/timeout-negative>: a timeout \(a threshold on a clock.s time\) must be a number of seconds > 0' \
  '<https://ex.org/timeout-zero>: a timeout \(a threshold on a clock.s time\) must be a number of seconds > 0' \
  '<https://ex.org/timeout-nan>: a timeout \(a threshold on a clock.s time\) must be a number of seconds > 0' \
  '<https://ex.org/c1>: a clock gives exactly one time' \
  "<https://ex.org/c1>: a clock's time is in seconds: exactly one unit, SEC" \
  '<https://ex.org/c2>: a clock gives exactly one time' \
  "<https://ex.org/c3>: a clock's time is in seconds: exactly one unit, SEC" \
  "<https://ex.org/c4>: a clock's time is a quantity \\(qudt:Quantity\\)" \
  "<https://ex.org/c5>: a clock's time is in seconds: exactly one unit, SEC"

good arm-behaviour mospec/solver.ttl
bad arm-behaviour mospec/solver.ttl 11 \
  '<https://ex.org/not-a-solver>: GravityCompensated is a kind of arm solver' \
  '<https://ex.org/two-idles>: an arm solver has one idle behaviour' \
  '<https://ex.org/limp>: an idle behaviour \(when-idle\) is a BrakeAndHold or a Float' \
  '<https://ex.org/brake-ms>: a BrakeAndHold.s time-constant is in seconds' \
  '<https://ex.org/brake-zero>: a BrakeAndHold.s time-constant is a number of seconds > 0' \
  '<https://ex.org/brake-none>: a BrakeAndHold has exactly one time-constant' \
  '<https://ex.org/float>: a Float does not brake'

good joints mospec/joints.ttl
bad joints mospec/joints.ttl 11 \
  '<https://ex.org/q-deg>: a joint position has exactly one unit: RAD \(revolute joint\) or M' \
  '<https://ex.org/q-link>: <https://ex.org/[^>]*> is no joint: no loaded file defines it as a kc-ent:Joint' \
  '<https://ex.org/q-orphan>: a joint position is the output of exactly one solver' \
  '<https://ex.org/qd-rad>: a joint velocity is of exactly one joint' \
  '<https://ex.org/qd-rad>: a joint velocity has exactly one unit: RAD-PER-SEC \(revolute joint\) or M-PER-SEC' \
  '<https://ex.org/tau-n>: the unit of a measured joint torque follows its joint: N-M on a revolute joint.*unit/N>' \
  '<https://ex.org/not-a-quantity>: a measured joint torque is a quantity' \
  '<https://ex.org/q-lift-rad>: the unit of a joint position follows its joint: RAD on a revolute joint, M on a prismatic joint.*unit/RAD>' \
  '<https://ex.org/qd-lift-rad>: the unit of a joint velocity follows its joint.*unit/RAD-PER-SEC>' \
  '<https://ex.org/f-lift-nm>: the unit of a measured joint torque follows its joint.*unit/N-M>' \
  '<https://ex.org/q-j4-m>: the unit of a joint position follows its joint.*unit/M>'

# Joint limits: the published kc-ext:JointLimit (issue #33 item 7), and the
# retired mospec classes pointing to it.
good joint-limits mospec/joint-limits.ttl
bad joint-limits "mospec/joint-limits.ttl mospec/retired-terms.ttl" 12 \
  '<https://ex.org/pos-swapped>: the lower bound \(2.41E0\) exceeds the upper bound \(-2.41E0\)' \
  '<https://ex.org/pos-swapped>: <https://ex.org/pos-j1-again> limits the same quantity of the same joint' \
  '<https://ex.org/pos-deg>: the unit <http://qudt.org/vocab/unit/DEG> does not fit the limit and its joint' \
  '<https://ex.org/vel-lopsided>: mospec bounds a joint.s velocity and effort by one magnitude' \
  '<https://ex.org/eff-link>: a joint limit is of exactly one joint \(of-joint, a kc-ent:Joint\).*value <https://ex.org/link>' \
  '<https://ex.org/eff-no-joint>: a joint limit is of exactly one joint.*MinCount' \
  '<https://ex.org/eff-kind>: the quantity kind <http://qudt.org/vocab/quantitykind/Angle> does not fit the limit' \
  '<https://ex.org/acc-j1>: mospec enforces no joint acceleration limit' \
  '<https://ex.org/untyped>: a joint limit is typed also by exactly one kind of quantity it limits' \
  '<https://ex.org/no-upper>: a joint limit has exactly one upper bound' \
  '<https://ex.org/old-effort>: mos-jnt:JointPositionLimits, JointVelocityLimit and JointEffortLimit are retired: a joint limit is the published kc-ext:JointLimit'
good prismatic-joint mospec/prismatic-joint.ttl
bad prismatic-joint mospec/prismatic-joint.ttl 5 \
  '<https://ex.org/lift-no-axis>: a prismatic joint translates along exactly one common-axis.*MinCount' \
  '<https://ex.org/lift-two-axes>: a prismatic joint translates along exactly one common-axis.*MaxCount' \
  '<https://ex.org/lift-two-axes>: a prismatic joint translates along exactly one common-axis.*ex.org/point>' \
  '<https://ex.org/lift-not-a-joint>: a prismatic joint is a joint' \
  '<https://ex.org/lift-and-hinge>: a joint is prismatic or revolute, not both'

good estimated-wrench mospec/estimated-wrench.ttl
bad estimated-wrench mospec/estimated-wrench.ttl 2 \
  '<https://ex.org/F-quantity>: an estimated wrench is a wrench' \
  '<https://ex.org/F-quantity>: an estimated wrench is the output of exactly one solver'

good guards mospec/guards.ttl
bad guards "mospec/guards.ttl mospec/retired-terms.ttl" 13 \
  '<https://ex.org/retired>: mos-grd:tolerance is retired: a constraint.s tolerance is the published cstr-ext:tolerance; list the context https://secorolab.github.io/metamodels/task/constraint-extension.json' \
  '<https://ex.org/motion-while>: <https://ex.org/exact> is a per-condition on a quantity no controller or assignment of the motion acts on' \
  '<https://ex.org/band>: only an equality, a less-than or a greater-than constraint has a tolerance' \
  '<https://ex.org/negative>: a tolerance is a number >= 0' \
  "<https://ex.org/seconds>: a tolerance is in the constrained quantity's unit" \
  '<https://ex.org/twice>: a constraint has at most one tolerance' \
  '<https://ex.org/twice>: a tolerance has exactly one value' \
  '<https://ex.org/motion>: <https://ex.org/exact> is an equality constraint without a tolerance.*motion-specification#until' \
  '<https://ex.org/motion>: <https://ex.org/exact> is an equality constraint without a tolerance.*motion-specification#when' \
  '<https://ex.org/mon-exact>: only an edge-triggered monitor reports edges' \
  '<https://ex.org/mon-exact>: the monitor watches the error of <https://ex.org/exact>, an equality constraint without a tolerance' \
  '<https://ex.org/mon-sideways>: the monitor watches the error of <https://ex.org/exact>' \
  '<https://ex.org/mon-sideways>: an edge-triggered monitor reports one edge: rising, falling or both'

good monitors task/monitors.ttl
bad monitors task/monitors.ttl 9 \
  '<https://ex.org/b1>: a monitor watches exactly one error signal' \
  '<https://ex.org/b1>: a level-triggered monitor raises exactly one flag' \
  "<https://ex.org/b2>: the monitor's error signal is produced by no error evaluator.*err-nowhere" \
  "<https://ex.org/b2>: the monitor's error signal has no unit" \
  "<https://ex.org/b3>: a threshold of the watched constraint has a unit the monitor's error signal does not have.*ex.org/lo>" \
  "<https://ex.org/b3>: a threshold of the watched constraint has a unit the monitor's error signal does not have.*ex.org/hi>" \
  '<https://ex.org/b4>: an edge-triggered monitor emits on at most one event queue' \
  "<https://ex.org/b5>: a threshold of the watched constraint has a unit the monitor's error signal does not have.*ex.org/t-max>" \
  "<https://ex.org/h>: a handler's monitors are monitors.*not-a-monitor"

good joint-force task/joint-force-drivers.ttl
bad joint-force task/joint-force-drivers.ttl 7 \
  '<https://ex.org/jf-none>: a joint-force specification applies exactly one joint force' \
  '<https://ex.org/jf-none>: a joint-force driver is attached to exactly one joint' \
  "<https://ex.org/jf-link>: nothing produces the joint force.*tau-nowhere" \
  '<https://ex.org/jf-link>: <https://ex.org/link> is no joint: no loaded file defines it as a kc-ent:Joint' \
  '<https://ex.org/jf-unit>: a force on a revolute joint is a torque: its unit must be N-M' \
  '<https://ex.org/jf-slide-unit>: a force on a prismatic joint is a force: its unit must be N.*unit/N-M>' \
  '<https://ex.org/drv>: a joint-force driver must be a joint-force specification.*not-a-driver'

good wrench-transform newtonian-rigid-body-dynamics/operators.ttl
bad wrench-transform newtonian-rigid-body-dynamics/operators.ttl 4 \
  "<https://ex.org/t1>: the transformed wrench must be seen by the pose's distal frame" \
  "<https://ex.org/t2>: the transformed wrench must act at the origin of the pose's distal frame" \
  "<https://ex.org/t2>: the transformed wrench must come out acting at the origin of the pose's proximal frame" \
  "<https://ex.org/t3>: the transformed wrench must come out seen by the pose's proximal frame"

# The operators' shapes both as the four family files apps list and as
# geometry/spatial-operators.ttl (for apps naming the published file): same findings.
families="geometry/spatial-operators/distance.ttl geometry/spatial-operators/direction.ttl"
families="$families geometry/spatial-operators/angle.ttl geometry/spatial-operators/pose.ttl"
families="$families geometry/spatial-operators/axis-angle.ttl geometry/spatial-operators/twist.ttl"
for geom_ops in geometry/spatial-operators.ttl "$families"; do
ops="geometry/spatial-relations.ttl $geom_ops newtonian-rigid-body-dynamics/operators.ttl task/map.ttl"
good operators "$ops"
bad operators "$ops" 15 \
  '<https://ex.org/view2>: the view feeds a constrained quantity but nothing computes what it reads' \
  '<https://ex.org/d1>: a linear distance is between exactly two entities' \
  '<https://ex.org/d2>: a point-to-point distance is between points' \
  '<https://ex.org/p1>: a relative spatial relation is with respect to exactly one entity' \
  "<https://ex.org/rot>: the rotated input must be seen by the pose's distal frame" \
  "<https://ex.org/rot>: the rotated output must be seen by the pose's proximal frame" \
  "<https://ex.org/rotw>: the rotated wrench must come out seen by the pose's proximal frame" \
  '<https://ex.org/view>: a view yields exactly one 1D quantity' \
  '<https://ex.org/view>: a view selects exactly one of the axes x, y, z' \
  '<https://ex.org/compose>: a pose composition has exactly one second input pose \(in2\)' \
  '<https://ex.org/compose>: a pose composition has exactly one composite pose' \
  '<https://ex.org/angle>: a planar angle is between exactly two directions' \
  '<https://ex.org/angle>: a planar angle operator gives exactly one angle' \
  '<https://ex.org/invert>: an angle inversion has exactly one input angle' \
  '<https://ex.org/invert>: an angle inversion has exactly one output angle'
done

# One instance of every operator kind mospec lowers (src/ir/operators.cpp; the
# registry test ir_operators_test checks each has a case here or above).
kinds="geometry/spatial-relations.ttl geometry/spatial-operators.ttl newtonian-rigid-body-dynamics/operators.ttl"
good operator-kinds "$kinds"
bad operator-kinds "$kinds" 13 \
  '<https://ex.org/dist-bad>: value is not an instance of .*spatial-relations#Pose' \
  '<https://ex.org/dir-bad>: fewer than 1 value .*spatial-operators#direction' \
  '<https://ex.org/yaw-bad>: an angle around an axis names exactly one of the axes x, y, z' \
  "<https://ex.org/rotdir-bad>: the rotated input must be seen by the pose's distal frame" \
  '<https://ex.org/tftw-bad>: a twist transformation has exactly one input twist' \
  '<https://ex.org/addtw-bad>: a twist sum has exactly one second twist \(in2\)' \
  '<https://ex.org/rotw-bad>: a wrench rotation has exactly one output wrench' \
  '<https://ex.org/force-bad>: fewer than 1 value .*operators#direction' \
  '<https://ex.org/addw-bad>: value is not an instance of .*structural-entities#Wrench' \
  '<https://ex.org/inv-bad>: exactly one output wrench \(to\)' \
  '<https://ex.org/copy-bad>: exactly one output wrench \(to\)' \
  '<https://ex.org/acc-bad>: mospec accumulates single wrenches' \
  '<https://ex.org/inertial-bad>: an inertial wrench reads exactly one rigid-body inertia that states'

# geometry/spatial-operators.ttl is exactly the family files' shapes: its text
# after the prefixes is theirs, concatenated in the order above.
body() { sed -e '/^#/d' -e '/^@prefix/d' -e '/^$/d' "$@"; }
if diff <(body "$mm/geometry/spatial-operators.ttl") \
        <(for f in $families; do body "$mm/$f"; done) > "$out"; then
  echo "ok   spatial-operators.ttl = its family files"
else fail "geometry/spatial-operators.ttl differs from spatial-operators/*.ttl"; fi
for f in $families; do
  if grep -q '^@prefix mos:' "$mm/$f" && grep -q '^mos:' "$mm/$f"; then :; else fail "$f holds no shape"; fi
done

# newtonian-rigid-body-dynamics/operators.ttl is exactly its per-operator files'
# shapes (wrench, add, rotate, transform, and the operators no scenario uses:
# rotate-distal, assign, accumulate): sc1 lists wrench, add and transform,
# sc2 wrench and rotate, so that --strict finds no unused shape in either.
dyn_families="wrench add rotate transform rotate-distal assign accumulate inertia"
if diff <(body "$mm/newtonian-rigid-body-dynamics/operators.ttl") \
        <(for f in $dyn_families; do body "$mm/newtonian-rigid-body-dynamics/operators/$f.ttl"; done) > "$out"; then
  echo "ok   newtonian-rigid-body-dynamics/operators.ttl = its per-operator files"
else fail "newtonian-rigid-body-dynamics/operators.ttl differs from operators/*.ttl"; fi
for f in $dyn_families; do
  f="newtonian-rigid-body-dynamics/operators/$f.ttl"
  if grep -q '^@prefix mos:' "$mm/$f" && grep -q '^mos:' "$mm/$f"; then :; else fail "$f holds no shape"; fi
done
# The per-operator files check what the aggregate checks.
good wrench-transform newtonian-rigid-body-dynamics/operators/transform.ttl
bad wrench-transform newtonian-rigid-body-dynamics/operators/transform.ttl 4 \
  "<https://ex.org/t1>: the transformed wrench must be seen by the pose's distal frame" \
  "<https://ex.org/t2>: the transformed wrench must act at the origin of the pose's distal frame" \
  "<https://ex.org/t2>: the transformed wrench must come out acting at the origin of the pose's proximal frame" \
  "<https://ex.org/t3>: the transformed wrench must come out seen by the pose's proximal frame"

# The authors' apps with their own contexts and shapes plus three of mospec's
# shape files: the known upstream sh:xone findings on DirectionCosineXYZ (1/2/2/2)
# and, because the authors' contexts drop the arguments of the end-effector wrench
# rotations (docs/upstream-findings.md F3), one "nothing produces the applied
# wrench" per arm; nothing else.
upstream="$shared/upstream/motion-spec-ral"
if [ -d "$upstream/models" ]; then
  cd "$upstream"
  # (sc0b also constrains the angle quantities that only sc1 defines: F9.)
  for app in sc0a-right-arm:1:0 sc0b-dual-arm:2:2 sc1:2:0 sc2:2:0; do
    IFS=: read -r name n nu <<< "$app"
    "$mospec" validate "models/$name.json" --shapes "$mm/geometry/coordinates.ttl" \
      --shapes "$mm/task/constraint.ttl" --shapes "$mm/task/solver-specification.ttl" > "$out" 2>/dev/null
    total=$(grep -c ': error: ' "$out"); xone=$(grep -c 'error:.*XoneConstraintComponent' "$out")
    frc=$(grep -c 'error: <https://secorolab.github.io/models/demo/spec-frc-[a-z]*-ee-z>: nothing produces the applied wrench' "$out")
    nounit=$(grep -c 'error: .*cstr-ang-[a-z]*-shoulder-ee-vertical>: the constrained quantity has no unit' "$out")
    if [ "$xone" -eq "$n" ] && [ "$frc" -eq "$n" ] && [ "$nounit" -eq "$nu" ] && [ "$total" -eq $((2 * n + nu)) ]; then
      echo "ok   upstream $name: $n sh:xone, $n unproduced-wrench and $nu undefined-quantity finding(s), nothing else"
    else
      fail "upstream $name: $total violations ($xone sh:xone, $frc unproduced wrench), expected $n of each"
    fi
  done
  # Against mospec's metamodels only (contexts and shapes, through --map): the
  # findings docs/upstream-findings.md explains, and nothing else.
  # (sc0b constrains two angles and references only sc1 defines, F9: each is
  # named as defined by no loaded file, mospec/references.ttl; so is every
  # app's platform configuration, F10: hddc2b_example_vel, and in sc1 and sc2
  # also hddc2b_example_frc_sc1 or _sc2.)
  for app in sc0a-right-arm:4:0:1:0:1 sc0b-dual-arm:12:0:2:4:1 sc1:7:4:2:0:2 sc2:7:4:2:0:2; do
    IFS=: read -r name nv nw ng nu nb <<< "$app"
    "$mospec" validate "models/$name.json" --map "https://comp-rob2b.github.io/metamodels/=$mm" > "$out" 2>/dev/null
    rot=$(grep -c "error: <https://secorolab.github.io/models/demo/rot-platform-to-rightarm-ee>: the rotated" "$out")
    scope=$(grep -c 'warning: .*the handler evaluates a constraint that is not part of its motion' "$out")
    grav=$(grep -c 'error: .*gravity is an acceleration: its unit must be M-PER-SEC2' "$out")
    undefined=$(grep -c 'error: <[^>]*cstr-ang-[a-z]*-shoulder-ee-vertical>: names <[^>]*>, which no loaded file defines' "$out")
    base=$(grep -c 'error: <https://secorolab.github.io/models/demo/base-[fi][vf]k>: names <https://secorolab.github.io/models/demo/hddc2b_example_[a-z0-9_]*>, which no loaded file defines' "$out")
    if grep -q "^shacl: $nv violations, $nw warnings, 0 infos" "$out" && [ "$rot" -eq 2 ] && [ "$grav" -eq "$ng" ] \
       && [ "$scope" -eq "$nw" ] && [ "$undefined" -eq "$nu" ] && [ "$base" -eq "$nb" ]; then
      echo "ok   upstream $name with mospec's metamodels: $nv violation(s), $nw warning(s) as documented"
    else
      fail "upstream $name with mospec's metamodels: expected $nv violations and $nw warnings"
    fi
  done
else
  echo "skip upstream apps: $upstream is absent"
fi

# metamodels/mospec/shape-files.txt (the shapes validate adds for the
# vocabulary a model uses) lists every shape file but the aggregates (X.ttl
# beside a folder X/, which repeat their family's shapes).
expected_list=$(cd "$mm" && find . -name '*.ttl' | sed 's|^\./||' | sort |
  while read -r f; do [ -d "${f%.ttl}" ] || echo "$f"; done)
listed=$(grep -v '^#' "$mm/mospec/shape-files.txt" | grep -v '^$' | sort)
if [ "$expected_list" = "$listed" ]; then echo "ok   shape-files.txt lists every family shape file"
else
  diff <(echo "$expected_list") <(echo "$listed") > "$out"
  fail "metamodels/mospec/shape-files.txt differs from the family shape files (< missing, > extra)"
fi

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
