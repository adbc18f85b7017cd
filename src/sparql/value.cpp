// SPARQL operator semantics on expression values.
#include "sparql/value.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

#include "rdf/xsd.hpp"
#include "vocab/w3c.hpp"

namespace mospec::sparql::detail {

namespace {

int sign(long double a, long double b) {
  if (std::isnan(a) || std::isnan(b)) return 2;
  return a < b ? -1 : a > b ? 1 : 0;
}

bool iequal(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(a[k])) !=
        std::tolower(static_cast<unsigned char>(b[k])))
      return false;
  return true;
}

int compare_numeric(const Value& a, const Value& b) {
  if (a.num == Num::Integer && b.num == Num::Integer) return a.i < b.i ? -1 : a.i > b.i ? 1 : 0;
  return sign(a.as_long_double(), b.as_long_double());
}

int three_way(std::string_view a, std::string_view b) {
  const int c = a.compare(b);
  return c < 0 ? -1 : c > 0 ? 1 : 0;
}

template <class F>
std::string shortest_scientific(F v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "INF" : "-INF";
  char buf[64];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  std::string s(buf, p);
  const size_t e = s.find('e');
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  int exponent = std::stoi(s.substr(e + 1));
  return mantissa + "E" + std::to_string(exponent);
}

}  // namespace

Value decode_literal(std::string_view lexical, std::string_view datatype_iri,
                     std::string_view language, rdf::TermId id) {
  Value v;
  v.id = id;
  v.str = lexical;
  v.datatype = datatype_iri;
  if (!language.empty()) {
    v.kind = Value::Kind::LangString;
    v.lang = language;
    return v;
  }
  using rdf::xsd::Kind;
  const Kind kind = rdf::xsd::classify(datatype_iri).kind;
  switch (kind) {
    case Kind::String:
      v.kind = Value::Kind::String;
      return v;
    case Kind::Integer: {
      // Every integer-derived type reads as an integer; its range is not checked.
      if (!rdf::xsd::parse_decimal(lexical, false)) break;
      const bool neg = lexical.front() == '-';
      std::string_view body = lexical;
      if (neg || body.front() == '+') body.remove_prefix(1);
      v.kind = Value::Kind::Numeric;
      int64_t x = 0;
      auto [p, ec] = std::from_chars(body.data(), body.data() + body.size(), x);
      if (ec == std::errc() && p == body.data() + body.size()) {
        v.num = Num::Integer;
        v.i = neg ? -x : x;
      } else {
        // Beyond 64 bits: kept as a decimal value (see query.hpp).
        v.num = Num::Decimal;
        v.d = *rdf::xsd::to_long_double(lexical);
      }
      return v;
    }
    case Kind::Decimal:
      if (!rdf::xsd::parse_decimal(lexical, true)) break;
      v.kind = Value::Kind::Numeric;
      v.num = Num::Decimal;
      v.d = *rdf::xsd::to_long_double(lexical);
      return v;
    case Kind::Float:
    case Kind::Double: {
      const auto d = rdf::xsd::to_long_double(lexical);
      if (!d) break;
      v.kind = Value::Kind::Numeric;
      v.num = kind == Kind::Float ? Num::Float : Num::Double;
      v.d = *d;
      return v;
    }
    case Kind::Boolean:
      if (lexical == "true" || lexical == "1") {
        v.kind = Value::Kind::Bool;
        v.b = true;
        return v;
      }
      if (lexical == "false" || lexical == "0") {
        v.kind = Value::Kind::Bool;
        v.b = false;
        return v;
      }
      break;
    case Kind::DateTime: {
      const auto t = rdf::xsd::parse_instant(lexical, Kind::DateTime);
      if (!t) break;
      v.kind = Value::Kind::DateTime;
      v.d = t->seconds;
      v.has_tz = t->has_zone;
      return v;
    }
    default:  // xsd:dateTimeStamp, date, time and other datatypes: plain literals
      v.kind = Value::Kind::Literal;
      return v;
  }
  v.kind = Value::Kind::Literal;
  v.ill_typed = true;
  return v;
}

Tri ebv(const Value& v) {
  switch (v.kind) {
    case Value::Kind::Bool:
      return tri(v.b);
    case Value::Kind::Numeric:
      if (v.num == Num::Integer) return tri(v.i != 0);
      return tri(!(v.d == 0 || std::isnan(v.d)));
    case Value::Kind::String:
    case Value::Kind::LangString:
      return tri(!v.str.empty());
    case Value::Kind::Literal:
      return v.ill_typed ? Tri::False : Tri::Error;
    default:
      return Tri::Error;
  }
}

Tri equal(const Value& a, const Value& b) {
  if (a.error() || b.error()) return Tri::Error;
  if (a.kind == b.kind) {
    switch (a.kind) {
      case Value::Kind::Numeric: {
        const int c = compare_numeric(a, b);
        return tri(c == 0);
      }
      case Value::Kind::String:
        return tri(a.str == b.str);
      case Value::Kind::LangString:
        return tri(a.str == b.str && iequal(a.lang, b.lang));
      case Value::Kind::Bool:
        return tri(a.b == b.b);
      case Value::Kind::DateTime:
        return tri(sign(a.d, b.d) == 0);
      case Value::Kind::Iri:
      case Value::Kind::Blank:
        return tri(a.str == b.str);
      default:
        break;
    }
  }
  if (!a.is_literal() || !b.is_literal()) return Tri::False;  // different kinds of terms
  if (a.kind == Value::Kind::Literal && b.kind == Value::Kind::Literal && a.str == b.str &&
      a.datatype == b.datatype)
    return Tri::True;  // the same term
  // Values of different known types (e.g. "a"@en and "a") are simply different.
  if (a.kind != Value::Kind::Literal && b.kind != Value::Kind::Literal) return Tri::False;
  // Two different literals whose values cannot be compared: a type error (17.4.1.7).
  return Tri::Error;
}

int compare(const Value& a, const Value& b) {
  if (a.error() || b.error() || a.kind != b.kind) return 3;
  switch (a.kind) {
    case Value::Kind::Numeric:
      return compare_numeric(a, b);
    case Value::Kind::String:
      return three_way(a.str, b.str);
    case Value::Kind::Bool:
      return a.b == b.b ? 0 : a.b ? 1 : -1;
    case Value::Kind::DateTime:
      return sign(a.d, b.d);
    default:
      return 3;
  }
}

int order(const Value& a, const Value& b) {
  auto rank = [](const Value& v) {
    switch (v.kind) {
      case Value::Kind::Error:
        return 0;
      case Value::Kind::Blank:
        return 1;
      case Value::Kind::Iri:
        return 2;
      case Value::Kind::Numeric:
        return 3;
      case Value::Kind::Bool:
        return 4;
      case Value::Kind::DateTime:
        return 5;
      case Value::Kind::String:
        return 6;
      case Value::Kind::LangString:
        return 7;
      case Value::Kind::Literal:
        return 8;
    }
    return 9;
  };
  const int ra = rank(a), rb = rank(b);
  if (ra != rb) return ra < rb ? -1 : 1;
  switch (a.kind) {
    case Value::Kind::Error:
      return 0;
    case Value::Kind::Numeric: {
      const int c = compare_numeric(a, b);
      if (c == 2) {
        // NaN sorts first, consistently.
        const bool na = std::isnan(a.as_long_double()), nb = std::isnan(b.as_long_double());
        return na == nb ? 0 : na ? -1 : 1;
      }
      return c;
    }
    case Value::Kind::Bool:
    case Value::Kind::DateTime: {
      const int c = compare(a, b);
      return c == 2 || c == 3 ? 0 : c;
    }
    case Value::Kind::LangString: {
      const int c = three_way(a.str, b.str);
      return c != 0 ? c : three_way(a.lang, b.lang);
    }
    case Value::Kind::Literal: {
      const int c = three_way(a.datatype, b.datatype);
      return c != 0 ? c : three_way(a.str, b.str);
    }
    default:
      return three_way(a.str, b.str);
  }
}

Value arithmetic(char op, const Value& a, const Value& b) {
  if (a.kind != Value::Kind::Numeric || b.kind != Value::Kind::Numeric) return Value::make_error();
  Num t = std::max(a.num, b.num);
  if (t == Num::Integer) {
    int64_t r = 0;
    bool overflow = false;
    switch (op) {
      case '+':
        overflow = __builtin_add_overflow(a.i, b.i, &r);
        break;
      case '-':
        overflow = __builtin_sub_overflow(a.i, b.i, &r);
        break;
      case '*':
        overflow = __builtin_mul_overflow(a.i, b.i, &r);
        break;
      default:
        t = Num::Decimal;
        break;  // integer division yields a decimal
    }
    if (t == Num::Integer) return overflow ? Value::make_error() : Value::integer(r);
  }
  const long double x = a.as_long_double(), y = b.as_long_double();
  long double r = 0;
  switch (op) {
    case '+':
      r = x + y;
      break;
    case '-':
      r = x - y;
      break;
    case '*':
      r = x * y;
      break;
    default:
      // Decimal division by zero is an error; float/double follow IEEE 754.
      if (t == Num::Decimal && y == 0) return Value::make_error();
      r = x / y;
      break;
  }
  if (t == Num::Float) r = static_cast<float>(r);
  if (t == Num::Double) r = static_cast<double>(r);
  return Value::number(t, r);
}

std::string canonical_lexical(const Value& v) {
  if (v.kind == Value::Kind::Bool) return v.b ? "true" : "false";
  switch (v.num) {
    case Num::Integer:
      return std::to_string(v.i);
    case Num::Decimal: {
      char buf[128];
      auto [p, ec] = std::to_chars(buf, buf + sizeof buf, v.d, std::chars_format::fixed);
      if (ec != std::errc()) return "0.0";
      std::string s(buf, p);
      if (s.find('.') == std::string::npos) s += ".0";
      if (s == "-0.0") s = "0.0";
      return s;
    }
    case Num::Float:
      return shortest_scientific(static_cast<float>(v.d));
    case Num::Double:
      return shortest_scientific(static_cast<double>(v.d));
  }
  return {};
}

std::string_view datatype_of(const Value& v) {
  if (v.kind == Value::Kind::Bool) return vocab::xsd::boolean;
  switch (v.num) {
    case Num::Integer:
      return vocab::xsd::integer;
    case Num::Decimal:
      return vocab::xsd::decimal;
    case Num::Float:
      return vocab::xsd::float_;
    case Num::Double:
      return vocab::xsd::double_;
  }
  return {};
}

}  // namespace mospec::sparql::detail
