// Expression values and the SPARQL operator semantics on them (SPARQL 1.1
// sections 17.2-17.4, XPath numeric promotion). Internal to the evaluator.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "rdf/term.hpp"

namespace mospec::sparql::detail {

// Numeric types in promotion order (integer -> decimal -> float -> double).
enum class Num : uint8_t { Integer, Decimal, Float, Double };

struct Value {
  enum class Kind : uint8_t {
    Error,       // an expression error (unbound variable, type error, ...)
    Iri,         // str: the IRI
    Blank,       // str: the label
    Literal,     // any other literal: str lexical, datatype IRI
    Bool,        // b
    Numeric,     // num; i (Integer) or d
    String,      // simple literal / xsd:string: str
    LangString,  // str, lang
    DateTime,    // str lexical, seconds since 1970 (UTC), has_tz
  };
  Kind kind = Kind::Error;
  Num num = Num::Integer;
  bool b = false;
  bool has_tz = false;
  // Literal: the datatype is numeric/boolean/dateTime but the lexical form is
  // invalid (effective boolean value false, comparisons are errors).
  bool ill_typed = false;
  int64_t i = 0;
  long double d = 0;
  std::string_view str, lang, datatype;
  rdf::TermId id = rdf::TermId::any();  // the term this value came from, if any

  bool error() const { return kind == Kind::Error; }
  bool is_literal() const { return kind >= Kind::Literal; }
  static Value make_error() { return Value{}; }
  static Value boolean(bool v) {
    Value r;
    r.kind = Kind::Bool;
    r.b = v;
    return r;
  }
  static Value integer(int64_t v) {
    Value r;
    r.kind = Kind::Numeric;
    r.num = Num::Integer;
    r.i = v;
    return r;
  }
  static Value number(Num n, long double v) {
    Value r;
    r.kind = Kind::Numeric;
    r.num = n;
    r.d = v;
    if (n == Num::Integer) r.i = static_cast<int64_t>(v);
    return r;
  }
  static Value string(std::string_view s, std::string_view lang = {}) {
    Value r;
    r.kind = lang.empty() ? Kind::String : Kind::LangString;
    r.str = s;
    r.lang = lang;
    return r;
  }
  long double as_long_double() const {
    return num == Num::Integer ? static_cast<long double>(i) : d;
  }
};

enum class Tri : uint8_t { False, True, Error };
inline Tri tri(bool b) {
  return b ? Tri::True : Tri::False;
}

// A literal term as a value: recognises xsd numerics (and integer subtypes),
// boolean, string, dateTime, rdf:langString.
Value decode_literal(std::string_view lexical, std::string_view datatype_iri,
                     std::string_view language, rdf::TermId id);

// Effective boolean value (17.2.2).
Tri ebv(const Value& v);
// '=' (RDFterm-equal and the operator mapping).
Tri equal(const Value& a, const Value& b);
// '<' family: -1, 0, 1; 2 when unordered (NaN); 3 on a type error.
int compare(const Value& a, const Value& b);
// Total order for ORDER BY (15.1), with Error standing for unbound.
int order(const Value& a, const Value& b);

// + - * / with numeric type promotion; integer / integer is decimal.
Value arithmetic(char op, const Value& a, const Value& b);

// Canonical lexical form and datatype IRI of a Numeric or Bool value.
std::string canonical_lexical(const Value& v);
std::string_view datatype_of(const Value& v);

}  // namespace mospec::sparql::detail
