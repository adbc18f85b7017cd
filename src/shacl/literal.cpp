#include "shacl/literal.hpp"

#include "rdf/xsd.hpp"

namespace mospec::shacl {

namespace {

using rdf::xsd::Kind;

char lower(char c) {
  return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

Order from_int(int c) {
  return c < 0 ? Order::Less : c > 0 ? Order::Greater : Order::Equal;
}

template <class T>
Order order_of(T a, T b) {
  if (a < b) return Order::Less;
  if (b < a) return Order::Greater;
  if (a == b) return Order::Equal;
  return Order::Incomparable;  // NaN
}

bool numeric(Kind k) {
  return k == Kind::Decimal || k == Kind::Integer || k == Kind::Float || k == Kind::Double;
}

Order compare_instants(const rdf::xsd::Instant& a, const rdf::xsd::Instant& b) {
  if (a.has_zone == b.has_zone) return order_of(a.seconds, b.seconds);
  // XSD 3.2.7.4: a value without a zone stands for every zone from -14:00 to +14:00.
  constexpr long double kSpan = 14 * 3600;
  const rdf::xsd::Instant& local = a.has_zone ? b : a;
  const rdf::xsd::Instant& zoned = a.has_zone ? a : b;
  Order local_vs_zoned = Order::Incomparable;
  if (local.seconds + kSpan < zoned.seconds) local_vs_zoned = Order::Less;
  if (local.seconds - kSpan > zoned.seconds) local_vs_zoned = Order::Greater;
  if (local_vs_zoned == Order::Incomparable || !a.has_zone) return local_vs_zoned;
  return local_vs_zoned == Order::Less ? Order::Greater : Order::Less;
}

}  // namespace

Order compare_literals(const LiteralView& a, const LiteralView& b) {
  using rdf::xsd::parse_decimal;
  using rdf::xsd::parse_instant;
  if (!a.language.empty() || !b.language.empty()) return Order::Incomparable;
  const rdf::xsd::Datatype ta = rdf::xsd::classify(a.datatype);
  const rdf::xsd::Datatype tb = rdf::xsd::classify(b.datatype);
  if (!rdf::xsd::well_formed(a.lexical, ta) || !rdf::xsd::well_formed(b.lexical, tb))
    return Order::Incomparable;
  if (numeric(ta.kind) && numeric(tb.kind)) {
    bool exact = (ta.kind == Kind::Decimal || ta.kind == Kind::Integer) &&
                 (tb.kind == Kind::Decimal || tb.kind == Kind::Integer);
    if (exact)
      return from_int(
          rdf::xsd::compare(*parse_decimal(a.lexical, true), *parse_decimal(b.lexical, true)));
    auto x = rdf::xsd::to_double(a.lexical);
    auto y = rdf::xsd::to_double(b.lexical);
    if (!x || !y) return Order::Incomparable;
    return order_of(*x, *y);
  }
  if (ta.kind != tb.kind) {
    bool both_date_time = (ta.kind == Kind::DateTime || ta.kind == Kind::DateTimeStamp) &&
                          (tb.kind == Kind::DateTime || tb.kind == Kind::DateTimeStamp);
    if (!both_date_time) return Order::Incomparable;
  }
  switch (ta.kind) {
    case Kind::String:
      return from_int(a.lexical.compare(b.lexical));
    case Kind::Boolean: {
      bool x = a.lexical == "true" || a.lexical == "1";
      bool y = b.lexical == "true" || b.lexical == "1";
      return order_of(x, y);
    }
    case Kind::DateTime:
    case Kind::DateTimeStamp:
      return compare_instants(*parse_instant(a.lexical, Kind::DateTime),
                              *parse_instant(b.lexical, Kind::DateTime));
    case Kind::Date:
    case Kind::Time:
      return compare_instants(*parse_instant(a.lexical, ta.kind),
                              *parse_instant(b.lexical, ta.kind));
    default:
      return Order::Incomparable;
  }
}

size_t utf8_length(std::string_view text) {
  size_t n = 0;
  for (char c : text)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
}

bool lang_matches(std::string_view tag, std::string_view range) {
  if (tag.empty()) return false;
  if (range == "*") return true;
  if (tag.size() < range.size()) return false;
  for (size_t i = 0; i < range.size(); ++i)
    if (lower(tag[i]) != lower(range[i])) return false;
  return tag.size() == range.size() || tag[range.size()] == '-';
}

}  // namespace mospec::shacl
