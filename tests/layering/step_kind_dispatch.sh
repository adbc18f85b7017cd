#!/usr/bin/env bash
# step_kind_dispatch.sh SRC_DIR: only the step-kind registry dispatches on a
# step's kind. Each kind's behaviour is its entry in kStepKinds (src/ir/ir.cpp)
# and its hooks (src/ir/kinds/*.cpp); code elsewhere reads a kind's role or
# calls its hooks, so adding a kind touches no pass, back-end, verdict or
# report. Fails (exit 1), printing file:line and the fix, for every `case
# StepKind::X` and every comparison with a StepKind outside those files.
# Making a step of a kind (lowering's `step_for(StepKind::X, ...)`) is fine.
# `step_kind_dispatch.sh --selftest SRC_DIR` checks that planted cases are caught.
set -u
registry='^[^:]*/ir/(ir\.cpp|kinds/[^/:]*):'
pattern='case +(ir::)?StepKind::|[=!]= *(ir::)?StepKind::|(ir::)?StepKind::[A-Za-z]+ *[=!]='
if [ "${1:-}" = "--selftest" ]; then
  src=${2:?usage: step_kind_dispatch.sh --selftest SRC_DIR}
  tmp=$(mktemp -d) || exit 2
  trap 'rm -rf "$tmp"' EXIT
  cp -r "$src" "$tmp/src"
  "$0" "$tmp/src" > /dev/null || { echo "step_kind_dispatch selftest: the tree itself fails"; exit 1; }
  status=0
  for plant in '    case StepKind::Evaluate:' \
               '    case ir::StepKind::GuardedMotion: {' \
               '  if (s.kind == ir::StepKind::Controller) return;' \
               '  if (s.kind!=StepKind::ArmSolve) return;' \
               '  if (StepKind::ReadClock == s.kind) return;'; do
    printf 'namespace x {\n%s\n}\n' "$plant" > "$tmp/src/verdict/planted.cpp"
    if out=$("$0" "$tmp/src"); then
      echo "step_kind_dispatch selftest: not caught: $plant"; status=1
    elif ! grep -q "verdict/planted.cpp:2:" <<< "$out"; then
      echo "step_kind_dispatch selftest: caught but not located: $out"; status=1
    fi
  done
  # Making a step of a kind is not dispatching on one; the registry may.
  printf '%s\n' '  Step s = st.step_for(StepKind::Evaluate, e);' > "$tmp/src/verdict/planted.cpp"
  "$0" "$tmp/src" > /dev/null || { echo "step_kind_dispatch selftest: step_for was refused"; status=1; }
  printf '%s\n' '    case StepKind::Evaluate:' > "$tmp/src/ir/kinds/planted.cpp"
  "$0" "$tmp/src" > /dev/null || { echo "step_kind_dispatch selftest: the registry was refused"; status=1; }
  [ $status = 0 ] && echo "step_kind_dispatch selftest: ok"
  exit $status
fi

src=${1:?usage: step_kind_dispatch.sh SRC_DIR}
[ -d "$src" ] || { echo "step_kind_dispatch: no directory $src"; exit 2; }
hits=$(find "$src" \( -name '*.cpp' -o -name '*.hpp' \) -print0 | sort -z \
  | xargs -0 -r grep -nE "$pattern" | grep -vE "$registry")
if [ -n "$hits" ]; then
  while IFS= read -r hit; do
    file=${hit%%:*}; rest=${hit#*:}; line=${rest%%:*}
    echo "$file:$line: error: dispatches on a step's kind outside the registry (${rest#*:}); read its role (ir::role(step)) or give its kind a hook in kStepKinds (src/ir/ir.cpp, src/ir/kinds/; docs/extending.md)"
  done <<< "$hits"
  echo "step_kind_dispatch: FAILED"
  exit 1
fi
echo "step_kind_dispatch: ok"
