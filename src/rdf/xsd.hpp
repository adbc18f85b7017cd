// XSD 1.1 datatypes of RDF literals: which datatype an IRI names, whether a
// lexical form is in its lexical space, and the value it denotes. The one
// reader of XSD lexical forms: SHACL's sh:datatype and value-range checks
// (shacl/literal.hpp), SPARQL's expression values (sparql/value.hpp) and
// lowering's numbers (ir/lower.cpp) all go through it.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace mospec::rdf::xsd {

// The datatypes whose lexical space mospec knows. Everything else is Other:
// any lexical form is accepted and only RDF term equality applies.
enum class Kind : uint8_t {
  Other,
  String,
  LangString,  // rdf:langString (the language tag is the caller's to check)
  Boolean,
  Decimal,
  Integer,  // xsd:integer and every type derived from it (ranges in Datatype)
  Float,
  Double,
  DateTime,
  DateTimeStamp,
  Date,
  Time,
};

struct Datatype {
  constexpr Datatype(Kind k = Kind::Other, std::string_view lo = {}, std::string_view hi = {})
      : kind(k), min(lo), max(hi) {}
  Kind kind = Kind::Other;
  // For integer-derived types: inclusive bounds as decimal digit strings
  // ("" = unbounded on that side). Empty for xsd:integer itself.
  std::string_view min, max;
};

// The datatype a datatype IRI names (xsd:int -> Integer in [-2^31, 2^31 - 1]).
Datatype classify(std::string_view datatype_iri);

// Whether `lexical` is in the lexical space of the datatype, range of an
// integer-derived type included (always true for Other, String, LangString):
//   boolean   true, false, 1, 0
//   decimal   [+-]?(digits(.digits?)?|.digits)
//   integer   [+-]?digits
//   float, double   a decimal form with an optional [eE][+-]?digits, INF,
//             +INF, -INF, NaN
//   dateTime  -?YYYY-MM-DDThh:mm:ss(.s+)?(Z|[+-]hh:mm)? with real calendar days
//             and 24:00:00 only as itself; dateTimeStamp requires the zone;
//             date and time are the two halves.
bool well_formed(std::string_view lexical, const Datatype& type);

// An exact decimal (of a decimal or integer lexical form): sign, integer
// digits without leading zeros, fraction digits without trailing zeros; the
// views point into the lexical form. Zero is never negative.
struct Decimal {
  bool negative = false;
  std::string_view integer;
  std::string_view fraction;
};
// nullopt unless `lexical` is a decimal form (an integer form if !allow_point).
std::optional<Decimal> parse_decimal(std::string_view lexical, bool allow_point = true);
// -1, 0 or 1, exactly.
int compare(const Decimal& a, const Decimal& b);

// The value of a float/double (or decimal/integer) lexical form, with
// INF/-INF/NaN; nullopt for a form outside the float lexical space.
// Rounded to nearest (a form beyond the range is an infinity, one below it 0).
std::optional<double> to_double(std::string_view lexical);
std::optional<long double> to_long_double(std::string_view lexical);

// A dateTime, dateTimeStamp, date or time as seconds from 1970-01-01T00:00:00Z
// (for a time: from midnight), the zone offset applied; has_zone false when
// the form gives no zone (the seconds are then as if it were Z).
struct Instant {
  long double seconds = 0;
  bool has_zone = false;
};
// nullopt unless well_formed(lexical, {kind}) for one of those four kinds.
std::optional<Instant> parse_instant(std::string_view lexical, Kind kind);

// The number a model's literal states, as lowering reads one (so it accepts
// exactly what sh:datatype accepts, plus what JSON-LD writes):
//   xsd:double, xsd:float, xsd:integer and the types derived from it: their
//     lexical space (integer ranges included);
//   xsd:decimal: its lexical space, and the canonical xsd:double form JSON-LD's
//     toRdf writes for a JSON number under a decimal coercion ("1.0E-3");
//   xsd:string (a number written as a string without a coercion): read as
//     xsd:double.
// Anything else -- another datatype, a form XSD rejects -- is not a number.
std::optional<double> number(std::string_view lexical, std::string_view datatype_iri);

}  // namespace mospec::rdf::xsd
