// RFC 3986 IRI helpers used by JSON-LD and Turtle.
#pragma once

#include <optional>
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

// A base IRI prepared for resolving many references against it: what a plain
// segment ("g", the common case: JSON-LD documents resolve thousands of "@id"
// values against a handful of bases) resolves onto is computed once, when the
// base is made, so such a reference costs one copy. Immutable; results equal
// resolve_iri()'s.
class IriBase {
 public:
  IriBase() = default;  // the empty base
  explicit IriBase(std::string iri);

  const std::string& iri() const { return iri_; }
  // resolve_iri(iri(), reference) written over `out`, whose buffer the common
  // case reuses.
  void resolve_into(std::string& out, std::string_view reference) const;
  std::string resolve(std::string_view reference) const;

 private:
  std::string iri_;
  // What a plain segment is appended to; none when the base has dot segments
  // (resolution then removes them) or is empty.
  std::optional<std::string> plain_prefix_;
};

}  // namespace mospec::rdf
