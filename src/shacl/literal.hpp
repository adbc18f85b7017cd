// XSD lexical checks and SPARQL operator semantics for literals, as SHACL's
// sh:datatype, sh:minInclusive & co. and sh:lessThan need them.
#pragma once

#include <cstdint>
#include <string_view>

namespace mospec::shacl {

// The datatypes whose lexical space the validator knows. Everything else is
// Other: any lexical form is accepted and only RDF term equality applies.
enum class Xsd : uint8_t {
  Other,
  String,
  LangString,
  Boolean,
  Decimal,
  Integer,  // xsd:integer and every type derived from it (ranges checked separately)
  Float,
  Double,
  DateTime,
  DateTimeStamp,
  Date,
  Time,
};

struct DatatypeInfo {
  constexpr DatatypeInfo(Xsd k = Xsd::Other, std::string_view lo = {}, std::string_view hi = {})
      : kind(k), min(lo), max(hi) {}
  Xsd kind = Xsd::Other;
  // For integer-derived types: inclusive bounds as decimal digit strings
  // ("" = unbounded on that side).
  std::string_view min, max;
};

DatatypeInfo classify_datatype(std::string_view datatype_iri);

// Whether `lexical` is in the lexical space of the datatype (always true for
// Xsd::Other, and for xsd:string). rdf:langString is checked by the caller
// (it needs the language tag, not the lexical form).
bool well_formed(std::string_view lexical, const DatatypeInfo& type);

// The result of SPARQL's "<" family on two literals.
enum class Order : uint8_t { Less, Equal, Greater, Incomparable };

// A literal as the comparison sees it (language tags make a literal
// incomparable with anything except by term equality, as in SPARQL).
struct LiteralView {
  std::string_view lexical;
  std::string_view datatype;
  std::string_view language;
};

// SPARQL 1.1 operator mapping: numerics by value (exact for integer/decimal,
// IEEE for float/double), xsd:string by code point, xsd:boolean false < true,
// xsd:dateTime/xsd:date by instant with XSD's 14-hour rule for values without
// a time zone. Anything else (ill-typed forms, mixed kinds, language-tagged
// strings) is Incomparable.
Order compare_literals(const LiteralView& a, const LiteralView& b);

// Number of Unicode code points in UTF-8 text (SPARQL STRLEN).
size_t utf8_length(std::string_view text);

// SPARQL langMatches with a basic language range ("*" or a tag prefix), case-insensitive.
bool lang_matches(std::string_view tag, std::string_view range);

}  // namespace mospec::shacl
