#!/usr/bin/env bash
# vocab_home.sh SRC_DIR: vocabulary IRIs have one home, SRC_DIR/vocab/ (w3c.hpp,
# metamodels.hpp). Fails (exit 1), printing file:line, when a namespace IRI of
# the comp-rob2b or secorolab metamodels (anywhere, comments included) or of RDF, RDFS, XSD,
# OWL, SHACL, i18n or QUDT (outside comments) is spelled in another file under
# SRC_DIR; the fix is to name the constant from vocab/ instead.
# `vocab_home.sh --selftest SRC_DIR` checks that a planted spelling is caught.
set -u
if [ "${1:-}" = "--selftest" ]; then
  src=${2:?usage: vocab_home.sh --selftest SRC_DIR}
  tmp=$(mktemp -d) || exit 2
  trap 'rm -rf "$tmp"' EXIT
  cp -r "$src" "$tmp/src"
  "$0" "$tmp/src" > /dev/null || { echo "vocab_home selftest: the tree itself fails"; exit 1; }
  status=0
  for plant in 'const char* k = "https://comp-rob2b.github.io/metamodels/geometry/coordinates#x";' \
               '// see https://comp-rob2b.github.io/metamodels/ for the terms' \
               'auto k = "https://secorolab.github.io/metamodels/task/constraint#tolerance";' \
               'auto t = "http://www.w3.org/1999/02/22-rdf-syntax-ns#type";' \
               'auto u = "http://qudt.org/schema/qudt/unit";'; do
    printf '%s\n' "$plant" > "$tmp/src/support/planted.cpp"
    if out=$("$0" "$tmp/src"); then
      echo "vocab_home selftest: not caught: $plant"; status=1
    elif ! grep -q 'support/planted.cpp:1:' <<< "$out"; then
      echo "vocab_home selftest: caught but not located: $out"; status=1
    fi
  done
  # A W3C IRI in a comment is allowed (the metamodel base is not).
  printf '%s\n' '// "http://www.w3.org/ns/shacl#ClassConstraintComponent"' > "$tmp/src/support/planted.cpp"
  "$0" "$tmp/src" > /dev/null || { echo "vocab_home selftest: a W3C IRI in a comment was refused"; status=1; }
  [ $status = 0 ] && echo "vocab_home selftest: ok"
  exit $status
fi

src=${1:?usage: vocab_home.sh SRC_DIR}
[ -d "$src/vocab" ] || { echo "vocab_home: $src/vocab: not a directory" >&2; exit 2; }
cd "$src" || exit 2
status=0
files=$(find . -path ./vocab -prune -o -type f -print | sed 's|^\./||' | sort)
[ -n "$files" ] || exit 0

# The metamodel base: nowhere outside vocab/, not even in comments (a comment
# that spells it is how a copy starts).
if hits=$(grep -nF 'https://comp-rob2b.github.io/metamodels/' $files); then
  printf '%s\n' "$hits" | sed 's/$/  <- the comp-rob2b metamodel base: use vocab::kMetamodels or a vocab::<metamodel>::ns (src\/vocab\/metamodels.hpp)/'
  status=1
fi
if hits=$(grep -nF 'https://secorolab.github.io/metamodels/' $files); then
  printf '%s\n' "$hits" | sed 's/$/  <- the secorolab metamodel base: use vocab::kSecorolab or a vocab::<metamodel>::ns (src\/vocab\/metamodels.hpp)/'
  status=1
fi
# Other vocabularies: outside comments.
if hits=$(grep -nE 'http://www\.w3\.org/1999/02/22-rdf-syntax-ns#|http://www\.w3\.org/2000/01/rdf-schema#|http://www\.w3\.org/2001/XMLSchema#|http://www\.w3\.org/2002/07/owl#|http://www\.w3\.org/ns/shacl#|https://www\.w3\.org/ns/i18n#|http://qudt\.org/' $files |
            grep -vE '^[^:]+:[0-9]+:[[:space:]]*(//|#[^i]|\*)'); then
  printf '%s\n' "$hits" | sed 's/$/  <- a vocabulary IRI: use the constant from src\/vocab\/w3c.hpp or metamodels.hpp/'
  status=1
fi
exit $status
