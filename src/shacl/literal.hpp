// SPARQL operator semantics for literals, as SHACL's sh:minInclusive & co. and
// sh:lessThan need them. The XSD lexical forms themselves (sh:datatype) are
// read by rdf/xsd.hpp.
#pragma once

#include <cstdint>
#include <string_view>

namespace mospec::shacl {

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
