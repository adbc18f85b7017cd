// RFC 3986 IRI helpers used by JSON-LD and Turtle.
#pragma once

#include <string>
#include <string_view>

namespace mospec::rdf {

// True when `s` has a scheme (is an absolute IRI per RFC 3987's syntax check
// that JSON-LD uses: scheme ":" ...).
bool is_absolute_iri(std::string_view s);

// RFC 3986 section 5.2 reference resolution (with remove_dot_segments).
// An empty base returns `reference` unchanged.
std::string resolve_iri(std::string_view base, std::string_view reference);

}  // namespace mospec::rdf
