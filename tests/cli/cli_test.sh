#!/usr/bin/env bash
# Black-box tests of the mospec CLI: exit codes, located one-line errors, and no
# partial outputs. Usage: cli_test.sh MOSPEC_BINARY
source "$(dirname "$0")/../support/cli_lib.sh"
cd "$work"

mkdir -p ctx
cat > good.json <<'J'
{ "@context": { "ex": "https://ex.org/", "name": "ex:name" },
  "@id": "https://ex.org/a", "name": "A" }
J
cat > bad.json <<'J'
{ "@context": { "ex": "https://ex.org/" },
  "@id": "https://ex.org/a",
  "ex:name" "A" }
J
cat > dropped.json <<'J'
{ "@context": { "ex": "https://ex.org/" },
  "@id": "https://ex.org/a",
  "ex:name": "A",
  "nickname": "B" }
J
cat > unmapped.json <<'J'
{ "@context": "https://nowhere.example/context.jsonld",
  "@id": "https://ex.org/a" }
J
cat > cycle.json <<'J'
{ "@context": "https://ctx.example/a.jsonld", "@id": "https://ex.org/a" }
J
echo '{ "@context": "https://ctx.example/b.jsonld" }' > ctx/a.jsonld
echo '{ "@context": "https://ctx.example/a.jsonld" }' > ctx/b.jsonld
cat > import-cycle.json <<'J'
{ "@context": "https://ctx.example/i1.jsonld", "@id": "https://ex.org/a" }
J
echo '{ "@context": { "@version": 1.1, "@import": "https://ctx.example/i2.jsonld" } }' > ctx/i1.jsonld
echo '{ "@context": { "@version": 1.1, "@import": "https://ctx.example/i1.jsonld" } }' > ctx/i2.jsonld
cat > bad-context.json <<'J'
{ "@context": { "ex": { "@id": 42 } }, "@id": "https://ex.org/a" }
J

expect help 0 '' -- "$mospec" --help
expect rdf-help 0 '' -- "$mospec" rdf --help
expect version 0 '' -- "$mospec" --version
stdout_has version '^mospec [0-9]+\.[0-9]+\.[0-9]+$'
expect command-typo 2 "^mospec: error: no command 'valdate'; did you mean 'validate'\?" -- "$mospec" valdate x.json
# A world file given where a model goes: said so, with the app beside it.
echo '{ "base": "fixed" }' > task.world.json
cp good.json task.json
expect world-file-as-model 2 "^mospec: error: 'task.world.json' is a world file \(the robot and the simulated world, docs/simulation.md\), not a model: give the app it goes with, 'task.json'" -- "$mospec" validate task.world.json
expect world-file-as-model-ir 2 "is a world file" -- "$mospec" ir task.world.json
expect command-unknown 2 "^mospec: error: no command 'frobnicate' \(run 'mospec --help' for the commands\)" -- "$mospec" frobnicate
expect no-command 2 'mospec:' -- "$mospec"
expect no-input 2 'mospec:' -- "$mospec" rdf
expect bad-format 2 'mospec:' -- "$mospec" rdf --format turtle good.json
expect bad-map 2 'mospec: .*--map expects IRI=DIR' -- "$mospec" rdf --map nodir good.json
expect good 0 '' -- "$mospec" rdf good.json
grep -q '<https://ex.org/a> <https://ex.org/name> "A"' stdout.txt || { echo "FAIL good: output"; failures=$((failures+1)); }
expect malformed-json 2 '^bad\.json:3:[0-9]+: error: ' -- "$mospec" rdf bad.json -o out1.nt
[ ! -e out1.nt ] || { echo "FAIL malformed-json: partial output left"; failures=$((failures+1)); }
expect missing-file 2 'nonexistent\.json' -- "$mospec" rdf nonexistent.json
expect directory-input 2 'ctx' -- "$mospec" rdf ctx
expect unmapped-iri 2 'unmapped\.json:1:[0-9]+: error: .*https://nowhere\.example/context\.jsonld' -- "$mospec" rdf unmapped.json
expect context-cycle 2 'ctx/b\.jsonld:1:[0-9]+: error: .*(includes itself|recursive|cycle)' -- "$mospec" rdf --map https://ctx.example/=ctx cycle.json
expect import-cycle 2 'ctx/i1\.jsonld:1:[0-9]+: error: .*@import' -- "$mospec" rdf --map https://ctx.example/=ctx import-cycle.json
expect invalid-context 2 'bad-context\.json:1:[0-9]+: error: ' -- "$mospec" rdf bad-context.json
expect dropped-warns 0 'dropped\.json:4:[0-9]+: warning: .*nickname' -- "$mospec" rdf dropped.json
expect dropped-strict 1 'dropped\.json:4:[0-9]+: warning: .*nickname' -- "$mospec" rdf --strict dropped.json -o out2.nt
[ ! -e out2.nt ] || { echo "FAIL dropped-strict: output written despite findings"; failures=$((failures+1)); }
if [ -w /dev/full ]; then
  expect dev-full 2 "cannot write '/dev/full'" -- "$mospec" rdf good.json -o /dev/full
fi
expect output-file 0 '' -- "$mospec" rdf good.json --format ntriples -o out3.nt
grep -q 'https://ex.org/name' out3.nt || { echo "FAIL output-file: content"; failures=$((failures+1)); }
ls | grep -q '\.tmp\.' && { echo "FAIL: temporary file left behind"; failures=$((failures+1)); }

# Determinism: the same input gives byte-identical output (blank nodes included).
cat > blanks.json <<'J'
{ "@context": { "ex": "https://ex.org/" },
  "@graph": [ { "ex:p": { "ex:q": [ { "@list": [1, 2.5, "x"] } ] } },
              { "@id": "ex:a", "ex:r": { "ex:s": true } } ] }
J
expect determinism-1 0 '' -- "$mospec" rdf blanks.json -o det1.nq
expect determinism-2 0 '' -- "$mospec" rdf blanks.json -o det2.nq
check determinism-identical cmp -s det1.nq det2.nq
check determinism-has-blank-nodes grep -q '^_:' det1.nq

# import-urdf: a URDF chain as a kinematic-chain JSON-LD model.
cat > arm.urdf <<'U'
<robot name="arm">
  <link name="base"/>
  <link name="upper"><inertial><mass value="1.5"/><origin xyz="0 0 0.1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.002"/></inertial></link>
  <link name="tool"/>
  <link name="camera"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit effort="10" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="flange" type="fixed"><parent link="upper"/><child link="tool"/><origin xyz="0 0 0.3"/></joint>
  <joint name="cam" type="fixed"><parent link="base"/><child link="camera"/></joint>
</robot>
U
expect urdf-two-leaves 2 "^arm\\.urdf:1:1: error: robot 'arm' has 2 leaf links \\(camera, tool\\)" -- "$mospec" import-urdf arm.urdf
expect urdf-bad-tip 2 "has no link 'hand'" -- "$mospec" import-urdf arm.urdf --tip hand
expect urdf-ok 0 '' -- "$mospec" import-urdf arm.urdf --tip tool --base https://ex.org/arm/ -o arm.jsonld
grep -q '"https://ex.org/arm/"' arm.jsonld && grep -q 'RevoluteJoint' arm.jsonld ||
  { echo "FAIL urdf-ok: content"; failures=$((failures+1)); }
# The default base is named after the robot (issue #33 item 7), the URDF's
# <limit> is kept as model quantities, and a tip link fixed to the last moving
# link (a tool0/flange) is written as the chain's tip, a link of its own, with
# a note that says how a task makes it the controlled frame.
expect urdf-fixed-tool-note 0 \
  "^mospec: note: the tip link 'tool' is fixed to the last moving link 'upper' \(fixed joint flange\): the model states it as the link <https://mospec.example/robots/arm/link-tool> with the frame <https://mospec.example/robots/arm/frame-tool>, posed by <https://mospec.example/robots/arm/pose-tool> in <https://mospec.example/robots/arm/frame-upper>\. It can be an arm solver's controlled frame: attach its motion drivers to <https://mospec.example/robots/arm/link-tool> \(they act at <https://mospec.example/robots/arm/point-tool-origin>\)" -- \
  "$mospec" import-urdf arm.urdf --tip tool -o arm-default.jsonld
check urdf-tool-link grep -Fq '"simplices": [ "frame-tool", "point-tool-origin" ]' arm-default.jsonld
check urdf-base-after-robot grep -q '"@base": "https://mospec.example/robots/arm/"' arm-default.jsonld
check urdf-effort-limit grep -Fq '"@id": "effort-limit-shoulder"' arm-default.jsonld
check urdf-position-limits grep -Fq '"@id": "position-limit-shoulder"' arm-default.jsonld
check urdf-velocity-limit grep -Fq '"@id": "velocity-limit-shoulder"' arm-default.jsonld
expect urdf-no-limits 0 '' -- "$mospec" import-urdf arm.urdf --tip tool --no-limits -o arm-plain.jsonld
check urdf-no-limits-published-vocabulary-only bash -c "! grep -q 'limit\|mospec/joints' arm-plain.jsonld"
sed 's/robot name="arm"/robot name="my arm"/' arm.urdf > my-arm.urdf
expect urdf-base-of-a-spaced-name 0 '' -- "$mospec" import-urdf my-arm.urdf --tip tool -o my-arm.jsonld
check urdf-base-iri-safe grep -q '"@base": "https://mospec.example/robots/my-arm/"' my-arm.jsonld
# An untrusted URDF: refused at the element concerned, exit 2, nothing written.
# A hundred thousand levels overflowed urdfdom's recursive XML parser.
{ echo '<robot name="deep">'; awk 'BEGIN { for (i = 0; i < 100000; i++) printf "<a>"
  for (i = 0; i < 100000; i++) printf "</a>" }'; echo '</robot>'; } > deep.urdf
expect urdf-deep 2 '^deep\.urdf:2:190: error: element <a> is nested 65 levels deep' -- \
  "$mospec" import-urdf deep.urdf -o deep.jsonld
check urdf-deep-writes-nothing test ! -e deep.jsonld
# Two finite masses folded into one infinite one were written as "mass": inf.
cat > heavy.urdf <<'U'
<robot name="heavy">
  <link name="base"/>
  <link name="upper"><inertial><mass value="1e308"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="tool"><inertial><mass value="1e308"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit effort="10" velocity="1" lower="-1" upper="1"/></joint>
  <joint name="flange" type="fixed"><parent link="upper"/><child link="tool"/></joint>
</robot>
U
expect urdf-folded-inf 2 "^heavy\.urdf:9:3: error: fixed joint 'flange' folds link 'tool' into link 'upper': .*got inf kg" -- \
  "$mospec" import-urdf heavy.urdf -o heavy.jsonld
check urdf-folded-inf-writes-nothing test ! -e heavy.jsonld

finish cli
