#!/usr/bin/env bash
# Generates the hand-built test programs' projects (among them one whose names
# and IRIs are hostile to C++), builds each with
# `mospec build` (the project compiles with -Wall -Wextra -Werror), then runs
# the tests that dlopen the libraries: same log columns and bit-identical
# values as the interpreter, and no allocation in 10 000 ticks.
# The same for a scenario model (models/sc1.json) through `mospec generate`.
# Clang compiles the generated code warning-free too. Finally the installed
# package: `cmake --install` into a prefix, and that prefix's mospec builds a
# project against its installed headers and libraries.
# usage: build_test.sh MOSPEC WRITE_FIXTURE CONTROLLER_TEST ALLOC_TEST SCRATCH SOURCE_DIR
#                      BINARY_DIR CMAKE
set -euo pipefail
mospec=$1 write_fixture=$2 controller_test=$3 alloc_test=$4 scratch=$5 source=$6
binary_dir=$7 cmake=$8
rm -rf "$scratch"
mkdir -p "$scratch"

for program in small arm empty hostile operators; do
  "$write_fixture" "$program" "$scratch/$program"
  # Twice: the second generation of the same program changes no byte.
  cp -r "$scratch/$program" "$scratch/$program.first"
  "$write_fixture" "$program" "$scratch/$program"
  diff -r "$scratch/$program.first" "$scratch/$program"
  # A path with a space and a quote: passed as it is, never through a shell.
  odd="$scratch/odd dir 'x'/$program"
  mkdir -p "$(dirname "$odd")"
  mv "$scratch/$program" "$odd"
  if ! lib=$("$mospec" build "$odd" --jobs 2 2>"$scratch/$program.err"); then
    echo "build_test: mospec build failed for $program:" >&2
    cat "$scratch/$program.err" >&2
    exit 1
  fi
  test -f "$lib"
  if grep -i "warning" "$scratch/$program.err"; then
    echo "build_test: warnings building $program" >&2
    exit 1
  fi
  export "MOSPEC_$(echo "$program" | tr a-z A-Z)_CONTROLLER=$lib"
done

# A scenario, generated from the models (validated and lowered by mospec).
# Exit 1 means the models do not validate or lower: the ir tests report that.
cd "$source"
status=0
"$mospec" generate models/sc1.json -o "$scratch/sc1" 2>"$scratch/sc1.gen.err" || status=$?
if [ "$status" -eq 0 ]; then
  lib=$("$mospec" build "$scratch/sc1" --jobs 2) || { echo "build_test: sc1 does not build" >&2; exit 1; }
  export MOSPEC_SCENARIO_APP=models/sc1.json MOSPEC_SCENARIO_CONTROLLER=$lib
elif [ "$status" -eq 1 ]; then
  echo "build_test: skipped sc1 (it does not validate or lower):" >&2
  tail -3 "$scratch/sc1.gen.err" >&2
else
  cat "$scratch/sc1.gen.err" >&2
  exit 1
fi

MOSPEC_CACHE_TEST_DIR="$scratch/cache" "$controller_test"
"$alloc_test"

# A project that does not compile: exit 2 and the compiler's message.
broken="$scratch/broken"
cp -r "$scratch/small.first" "$broken"
echo "int broken = ;" >> "$broken/controller.cpp"
if "$mospec" build "$broken" >"$scratch/broken.out" 2>"$scratch/broken.err"; then
  echo "build_test: a broken project built" >&2
  exit 1
else
  status=$?
fi
test "$status" -eq 2
grep -q "error" "$scratch/broken.err"
grep -q "mospec: building '.*broken' failed" "$scratch/broken.err"
# A directory without a project: exit 2, located message.
if "$mospec" build "$scratch/nowhere" 2>"$scratch/nowhere.err"; then exit 1; else test $? -eq 2; fi
grep -q "holds no generated project" "$scratch/nowhere.err"

# Clang (the sanitizer builds' compiler) compiles the generated code warning-free too.
if command -v clang++ >/dev/null; then
  for program in small arm hostile operators; do
    "$cmake" -S "$scratch/$program.first" -B "$scratch/$program.clang" -DCMAKE_CXX_COMPILER=clang++ \
      "-Dmospec_DIR=$binary_dir/package" >"$scratch/$program.clang.log" 2>&1 &&
      "$cmake" --build "$scratch/$program.clang" >>"$scratch/$program.clang.log" 2>&1 ||
      { echo "build_test: clang cannot build $program:" >&2; cat "$scratch/$program.clang.log" >&2; exit 1; }
  done
fi

# The install tree.
"$cmake" --install "$binary_dir" --prefix "$scratch/prefix" >"$scratch/install.log"
test -f "$scratch/prefix/include/mospec/runtime/steps.hpp"
test -f "$scratch/prefix/include/mospec/robot/controller.hpp"
test ! -e "$scratch/prefix/include/mospec/description/chain_rdf.hpp"
"$write_fixture" small "$scratch/installed"
lib=$("$scratch/prefix/bin/mospec" build "$scratch/installed")
grep -q "mospec_DIR:.*=$scratch/prefix/lib/cmake/mospec" "$scratch/installed/build/CMakeCache.txt"
test -f "$lib"

rm -rf "$scratch"
echo "build_test: ok"
