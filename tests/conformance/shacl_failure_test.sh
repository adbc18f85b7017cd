#!/usr/bin/env bash
# The SHACL conformance runner checks, not skips, manifest entries whose
# mf:result is sht:Failure: such a test passes only if mospec refuses the
# shapes graph (or the validation) with an error, and fails when mospec
# accepts it. The W3C core suite has no such entries, so this test writes its
# own small manifests. Usage: shacl_failure_test.sh SHACL_CONFORMANCE_BINARY
. "$(dirname "$0")/../support/cli_lib.sh"

prefixes='@prefix mf: <http://www.w3.org/2001/sw/DataAccess/tests/test-manifest#> .
@prefix sht: <http://www.w3.org/ns/shacl-test#> .
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .'

# An ill-formed shapes graph (sh:minLength needs an integer), a well-formed
# one, and an entry that is not an sht:Validate test (skipped, with reason).
cat > "$work/ill-formed.ttl" <<TTL
$prefixes
ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:minLength "three" .
TTL
cat > "$work/well-formed.ttl" <<TTL
$prefixes
ex:S a sh:NodeShape ; sh:targetNode ex:a ; sh:minLength 3 .
TTL
entry() { # NAME FILE
  echo "<$1> a sht:Validate ; mf:action [ sht:dataGraph <$2> ; sht:shapesGraph <$2> ] ;
  mf:result sht:Failure ."
}
cat > "$work/refused.ttl" <<TTL
$prefixes
<> a mf:Manifest ; mf:entries ( <ill> <other> ) .
$(entry ill ill-formed.ttl)
<other> a sht:SomethingElse .
TTL
cat > "$work/accepted.ttl" <<TTL
$prefixes
<> a mf:Manifest ; mf:entries ( <well> ) .
$(entry well well-formed.ttl)
TTL

expect refused-passes 0 '' -- "$mospec" "$work/refused.ttl"
stdout_has refused-summary '^shacl: 1 passed, 0 failed, 1 skipped$'
stdout_has skip-listed-with-reason '^SKIP other: not an sht:Validate test$'

expect accepted-fails 1 '' -- "$mospec" "$work/accepted.ttl"
stdout_has accepted-summary '^shacl: 0 passed, 1 failed, 0 skipped$'
stdout_has accepted-named '^FAIL well: expects a failure \(sht:Failure\), but validation succeeded'

finish shacl-failure
