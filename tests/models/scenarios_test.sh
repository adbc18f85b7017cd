#!/usr/bin/env bash
# The project's scenario models (models/sc*.json) load and validate with zero
# findings under --strict against mospec's own metamodels, and the shapes are
# really applied (a changed copy fails). Needs nothing from ../shared.
# Usage: scenarios_test.sh MOSPEC_BINARY SOURCE_DIR
set -u
mospec=$(realpath "$1")
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $1"; sed 's/^/  /' "$work/out" | head -20; failures=$((failures+1)); }

cd "$src"  # the apps' iri-map paths are relative to the repository root
apps=$(ls models/sc*.json | grep -v '\.world\.json$')  # not the worlds (models/APP.world.json)
[ -n "$apps" ] || { echo "FAIL no scenario apps in models/"; exit 1; }
for app in $apps; do
  if "$mospec" rdf "$app" --strict > /dev/null 2> "$work/out"; then echo "ok   $app loads with no warning"
  else fail "$app: loader warnings"; fi
  if "$mospec" validate "$app" --strict > "$work/out" 2>&1 && grep -q '^shacl: 0 violations, 0 warnings, 0 infos' "$work/out"
  then echo "ok   $app validates with zero findings (--strict)"
  else fail "$app: findings"; fi
done

# The shapes are applied: a copy whose gravity is in newtons fails.
cp -r models metamodels robots "$work/"
sed -i 's/"M-PER-SEC2"/"N"/' "$work/models/platform/01-world-model.json"
(cd "$work" && "$mospec" validate models/sc0a.json --strict > out 2>&1)
if [ $? -eq 1 ] && grep -q 'gravity is an acceleration' "$work/out"; then echo "ok   changed copy is rejected"
else fail "a copy with gravity in N was not rejected"; fi

# SC1's distance tube upside down ([0.68, 0.60] m) is rejected, the message
# quoting both thresholds.
if [ -f models/sc1.json ]; then
  rm -rf "$work/models" && cp -r models "$work/"
  sed -i 's/"0.72"/"0.60"/' "$work/models/sc1/00-misc.json"
  (cd "$work" && "$mospec" validate models/sc1.json --strict > out 2>&1)
  if [ $? -eq 1 ] && [ "$(grep -c 'lower threshold must be less than the upper threshold (lower 0.68, upper 0.60)' "$work/out")" -eq 2 ]; then
    echo "ok   sc1 with an empty distance tube is rejected"
  else fail "sc1 with lower > upper was not rejected twice"; fi
  # ... with a note where each threshold is written.
  if grep -q '^models/sc1/00-misc.json:12:[0-9]*: note: the value <[^>]*dist-rightarm-shoulder-ee-lower> is here$' "$work/out" &&
     grep -q '^models/sc1/00-misc.json:22:[0-9]*: note: upper <[^>]*dist-rightarm-shoulder-ee-upper> is here$' "$work/out"; then
    echo "ok   the empty tube's finding names where each threshold is written"
  else fail "lower > upper: no note at each threshold"; fi
fi

# SC1's distance and direction operators are checked (the spatial-operators
# family files sc1 lists): an operator with two poses is rejected.
if [ -f models/sc1.json ]; then
  rm -rf "$work/models" && cp -r models "$work/"
  sed -i 's/"pose": "pose-rightarm-shoulder-ee",/"pose": ["pose-rightarm-shoulder-ee", "pose-leftarm-shoulder-ee"],/' \
    "$work/models/sc1/02-map.json"
  (cd "$work" && "$mospec" validate models/sc1.json --strict > out 2>&1)
  if [ $? -eq 1 ] && grep -q 'error: <[^>]*pose-to-dist-rightarm>' "$work/out" \
     && grep -q 'error: <[^>]*pose-to-dir-rightarm>' "$work/out"; then
    echo "ok   sc1 with a two-pose distance and direction operator is rejected"
  else fail "sc1's distance/direction operators with two poses were not rejected"; fi
fi

# SC1's wrench transforms to the platform are checked: platform wrenches that act
# at the shoulder's origin instead of the platform's are rejected (one per arm).
if [ -f models/sc1.json ]; then
  rm -rf "$work/models" && cp -r models "$work/"
  sed -i 's|"reference-point": "point-platform-origin"|"reference-point": "https://mospec.example/robots/kinova-gen3/point-base_link-origin"|' \
    "$work/models/sc1/01-world-model.json"
  (cd "$work" && "$mospec" validate models/sc1.json --strict > out 2>&1)
  if [ $? -eq 1 ] && [ "$(grep -c "the transformed wrench must come out acting at the origin of the pose's proximal frame" "$work/out")" -eq 2 ]; then
    echo "ok   sc1 with platform wrenches at the wrong point is rejected"
  else fail "sc1's wrench transforms to a wrong reference point were not rejected twice"; fi
fi

# sc0a's contact-lost guard is checked: its threshold in millimetres (the position
# is in metres) is rejected by the unilateral-constraint and the monitor shapes.
rm -rf "$work/models" && cp -r models "$work/"
sed -i '/"@id": "pos-rightarm-ee-x-contact-lost"/,/}/ s/"unit": "M"/"unit": "MilliM"/' "$work/models/sc0a/00-misc.json"
(cd "$work" && "$mospec" validate models/sc0a.json --strict > out 2>&1)
if [ $? -eq 1 ] && grep -q 'error: <[^>]*cstr-pos-rightarm-contact-lost>: the threshold has a unit the constrained quantity does not have' "$work/out" \
   && grep -q "error: <[^>]*mon-rightarm-contact-lost>: a threshold of the watched constraint has a unit the monitor's error signal does not have" "$work/out"; then
  echo "ok   sc0a with a contact-lost threshold in mm is rejected"
else fail "sc0a's contact-lost threshold in mm was not rejected"; fi

# The shared clock is checked: a time in minutes is rejected.
rm -rf "$work/models" && cp -r models "$work/"
sed -i 's/"unit": "SEC"/"unit": "MIN"/' "$work/models/common/clock.json"
(cd "$work" && "$mospec" validate models/sc0a.json --strict > out 2>&1)
if [ $? -eq 1 ] && grep -q "error: <[^>]*clock-controller>: a clock's time is in seconds" "$work/out"; then
  echo "ok   a clock whose time is in minutes is rejected"
else fail "a clock whose time is in minutes was not rejected"; fi

# A post-condition is satisfied when its error is 0: SC1's motion ending on the
# contact force (an assignment, no error) is rejected.
if [ -f models/sc1.json ]; then
  rm -rf "$work/models" && cp -r models "$work/"
  sed -i 's/"cstr-time-sc1-rightarm-timeout"/"cstr-frc-rightarm-ee-contact"/' "$work/models/sc1/04-motion-specification.json"
  (cd "$work" && "$mospec" validate models/sc1.json --strict > out 2>&1)
  if [ $? -eq 1 ] && grep -q 'error: <[^>]*cstr-hdl-sc1-rightarm>: a pre- or post-condition (when, until) must be evaluated by an error evaluator.*cstr-frc-rightarm-ee-contact' "$work/out"; then
    echo "ok   sc1 ending on a constraint without an error evaluator is rejected"
  else fail "sc1 with an until constraint evaluated by no error evaluator was not rejected"; fi
fi

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
