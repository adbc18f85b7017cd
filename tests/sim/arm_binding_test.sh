#!/usr/bin/env bash
# Arms are bound to chains by what the world file and the models say, never by
# a built-in IRI (issue #33 item 2): a copy of a shipped scenario whose chain is
# renamed consistently (robot description, solvers, world file) lowers and
# runs; two arms bound to one chain are refused at the world file.
# Usage: arm_binding_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
tree="$work/tree"
mkdir -p "$tree"
cp -r "$src/models" "$src/robots" "$src/metamodels" "$tree/"
cd "$tree" || exit 1

# The right arm's chain (robots/kinova-gen3.jsonld) and the left twin's
# (models/left-arm/robot.jsonld) renamed, in the descriptions, every solver and
# every world file.
sed -i 's/"@id": "chain"/"@id": "my-arm-chain"/' robots/kinova-gen3.jsonld models/left-arm/robot.jsonld
grep -rl 'kinova-gen3\(-left\)\?/chain' models | xargs sed -i \
  -e 's#kinova-gen3/chain#kinova-gen3/my-arm-chain#g' -e 's#kinova-gen3-left/chain#kinova-gen3-left/my-arm-chain#g'
check "no model names the old chains" bash -c "! grep -rq 'kinova-gen3\(-left\)\?/chain\"' models robots"

expect "sc0a with its chain renamed lowers" 0 "" -- "$mospec" ir models/sc0a.json -o "$work/sc0a.ir.json"
check "the renamed chain drives arm 0 (the right arm)" \
  grep -q '"chain": "https://mospec.example/robots/kinova-gen3/my-arm-chain"' "$work/sc0a.ir.json"
expect "sc0a with its chain renamed runs" 0 "" -- "$mospec" run models/sc0a.json --interpret --duration 0.01

# sc1 drives both arms: the left twin is bound by the world file's arms.left.chain.
expect "sc1 renamed, the left twin unbound: refused naming the arms' chains" 1 \
  "no arm of the robot is bound to the chain 'https://mospec.example/robots/kinova-gen3-left/my-arm-chain' \(the robot's arms drive arm 0: https://mospec.example/robots/kinova-gen3/my-arm-chain, arm 1: https://mospec.example/robots/kinova-gen3-left/chain\)" -- \
  "$mospec" ir models/sc1.json
python3 - <<'PY'
import json
w = json.load(open("models/sc1.world.json"))
w["arms"] = {"left": {"chain": "https://mospec.example/robots/kinova-gen3-left/my-arm-chain"}}
json.dump(w, open("models/sc1.world.json", "w"), indent=1)
PY
expect "sc1 renamed, arms.left.chain binding the left twin, lowers" 0 "" -- "$mospec" ir models/sc1.json
expect "sc1 renamed runs" 0 "" -- "$mospec" run models/sc1.json --interpret --duration 0.01

# Two arms bound to one chain: which one a solver drives would be arbitrary.
cat > "$work/twice.world.json" <<'JSON'
{
  "robot": { "model": "../robots/kinova-gen3.jsonld",
             "chain": "https://mospec.example/robots/kinova-gen3/my-arm-chain" },
  "arms": { "left": { "chain": "https://mospec.example/robots/kinova-gen3/my-arm-chain" } }
}
JSON
cp "$work/twice.world.json" models/twice.world.json
expect "two arms bound to one chain: refused at the second arm's entry" 2 \
  "^models/twice.world.json:4:[0-9]+: error: arms right and left are both bound to the chain 'https://mospec.example/robots/kinova-gen3/my-arm-chain' \(by the world's \`robot.chain\` and arms.left\)" -- \
  "$mospec" ir models/sc0a.json --world models/twice.world.json
echo '{"arms": {"right": {"robot": {"model": "../robots/kinova-gen3.jsonld", "chain": "x"}, "chain": "y"}}}' \
  > models/both.world.json
expect "an arm with its own robot names its chain there, once" 2 \
  "^models/both.world.json:1:96: error: arms.right.chain: an arm with its own \`robot\` is bound by \`robot.chain\`; state the chain IRI once, there" -- \
  "$mospec" ir models/sc0a.json --world models/both.world.json

finish arm_binding
