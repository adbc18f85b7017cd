// RFC 3986 IRI helpers used by JSON-LD and Turtle.
#pragma once

#include <string>
#include <string_view>

namespace mospec::rdf {

// True when `s` has a scheme (is an absolute IRI per RFC 3987's syntax check
// that JSON-LD uses: scheme ":" ...).
bool is_absolute_iri(std::string_view s);

// RFC 3987 well-formedness as far as it matters for RDF output: a scheme, no
// characters that IRIs exclude (space, controls, <>"{}|\^`), at most one '#',
// and percent signs that start an escape.
bool is_well_formed_iri(std::string_view s);

// Why `s` is not a well-formed IRI ("it contains a space (U+0020; write %20)"),
// or empty when it is. Quotes only printable ASCII.
std::string iri_problem(std::string_view s);

// RFC 3986 section 5.2 reference resolution (with remove_dot_segments).
// An empty base returns `reference` unchanged.
std::string resolve_iri(std::string_view base, std::string_view reference);
// resolve_iri() written over `out`, whose buffer the common case (a plain
// segment against a base) reuses: for callers resolving many references.
void resolve_iri_into(std::string& out, std::string_view base, std::string_view reference);

}  // namespace mospec::rdf
