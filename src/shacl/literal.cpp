#include "shacl/literal.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "vocab/w3c.hpp"

namespace mospec::shacl {

namespace {

constexpr std::string_view kXsdNs = vocab::xsd::ns;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!is_digit(c)) return false;
  return true;
}

char lower(char c) {
  return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

// An exact decimal: sign, integer digits without leading zeros, fraction
// digits without trailing zeros. Zero is never negative.
struct Decimal {
  bool negative = false;
  std::string_view integer;
  std::string_view fraction;
};

std::optional<Decimal> parse_decimal(std::string_view s, bool allow_point) {
  Decimal d;
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
    d.negative = s[0] == '-';
    s.remove_prefix(1);
  }
  size_t point = s.find('.');
  std::string_view integer = s.substr(0, point);
  std::string_view fraction = point == std::string_view::npos ? "" : s.substr(point + 1);
  if (point != std::string_view::npos && !allow_point) return std::nullopt;
  if (integer.empty() && fraction.empty()) return std::nullopt;
  if (!integer.empty() && !all_digits(integer)) return std::nullopt;
  if (!fraction.empty() && !all_digits(fraction)) return std::nullopt;
  while (!integer.empty() && integer[0] == '0') integer.remove_prefix(1);
  while (!fraction.empty() && fraction.back() == '0') fraction.remove_suffix(1);
  d.integer = integer;
  d.fraction = fraction;
  if (integer.empty() && fraction.empty()) d.negative = false;
  return d;
}

int compare_magnitude(const Decimal& a, const Decimal& b) {
  if (a.integer.size() != b.integer.size()) return a.integer.size() < b.integer.size() ? -1 : 1;
  if (int c = a.integer.compare(b.integer); c != 0) return c < 0 ? -1 : 1;
  if (int c = a.fraction.compare(b.fraction); c != 0) return c < 0 ? -1 : 1;
  return 0;
}

int compare_decimal(const Decimal& a, const Decimal& b) {
  if (a.negative != b.negative) return a.negative ? -1 : 1;
  int m = compare_magnitude(a, b);
  return a.negative ? -m : m;
}

bool well_formed_float(std::string_view s) {
  if (s == "INF" || s == "-INF" || s == "+INF" || s == "NaN") return true;
  size_t e = s.find_first_of("eE");
  std::string_view mantissa = s.substr(0, e);
  if (!parse_decimal(mantissa, true)) return false;
  if (e == std::string_view::npos) return true;
  std::string_view exponent = s.substr(e + 1);
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.remove_prefix(1);
  return all_digits(exponent);
}

std::optional<double> parse_double(std::string_view s) {
  if (s == "INF" || s == "+INF") return HUGE_VAL;
  if (s == "-INF") return -HUGE_VAL;
  if (s == "NaN") return std::nan("");
  std::string copy(s);
  char* end = nullptr;
  double v = std::strtod(copy.c_str(), &end);
  if (end != copy.c_str() + copy.size()) return std::nullopt;
  return v;
}

// A dateTime/date as seconds from a fixed epoch, plus whether a zone was given.
struct Instant {
  long double seconds = 0;
  bool has_zone = false;
};

int64_t days_from_civil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

bool leap(int64_t y) {
  return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
}

unsigned days_in_month(int64_t y, unsigned m) {
  static constexpr std::array<unsigned, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && leap(y) ? 29 : kDays[m - 1];
}

bool take_digits(std::string_view& s, size_t n, int64_t& out) {
  if (s.size() < n) return false;
  int64_t v = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!is_digit(s[i])) return false;
    v = v * 10 + (s[i] - '0');
  }
  out = v;
  s.remove_prefix(n);
  return true;
}

bool take(std::string_view& s, char c) {
  if (s.empty() || s[0] != c) return false;
  s.remove_prefix(1);
  return true;
}

// Parses an optional zone suffix; returns its offset in seconds.
bool parse_zone(std::string_view s, bool& has_zone, int64_t& offset) {
  has_zone = false;
  offset = 0;
  if (s.empty()) return true;
  has_zone = true;
  if (s == "Z") return true;
  if (s.size() != 6 || (s[0] != '+' && s[0] != '-') || s[3] != ':') return false;
  bool negative = s[0] == '-';
  s.remove_prefix(1);
  int64_t h = 0, m = 0;
  if (!take_digits(s, 2, h) || !take(s, ':') || !take_digits(s, 2, m)) return false;
  if (h > 14 || m > 59 || (h == 14 && m != 0)) return false;
  offset = (h * 3600 + m * 60) * (negative ? -1 : 1);
  return true;
}

bool parse_date_part(std::string_view& s, int64_t& year, int64_t& month, int64_t& day) {
  bool negative = take(s, '-');
  size_t digits = 0;
  while (digits < s.size() && is_digit(s[digits])) ++digits;
  if (digits < 4 || (digits > 4 && s[0] == '0')) return false;
  if (!take_digits(s, digits, year)) return false;
  if (negative) year = -year;
  if (!take(s, '-') || !take_digits(s, 2, month) || !take(s, '-') || !take_digits(s, 2, day))
    return false;
  if (month < 1 || month > 12 || day < 1) return false;
  return day <= static_cast<int64_t>(days_in_month(year, static_cast<unsigned>(month)));
}

bool parse_time_part(std::string_view& s, long double& seconds_of_day) {
  int64_t h = 0, m = 0, sec = 0;
  if (!take_digits(s, 2, h) || !take(s, ':') || !take_digits(s, 2, m) || !take(s, ':') ||
      !take_digits(s, 2, sec))
    return false;
  long double fraction = 0;
  bool fraction_nonzero = false;
  if (take(s, '.')) {
    size_t n = 0;
    long double scale = 0.1L;
    while (n < s.size() && is_digit(s[n])) {
      fraction += scale * (s[n] - '0');
      fraction_nonzero = fraction_nonzero || s[n] != '0';
      scale /= 10;
      ++n;
    }
    if (n == 0) return false;
    s.remove_prefix(n);
  }
  if (m > 59 || sec > 59) return false;
  if (h > 24 || (h == 24 && (m != 0 || sec != 0 || fraction_nonzero))) return false;
  seconds_of_day = static_cast<long double>(h * 3600 + m * 60 + sec) + fraction;
  return true;
}

std::optional<Instant> parse_date_time(std::string_view s, bool with_time, bool require_zone) {
  int64_t y = 0, mo = 0, d = 0;
  if (!parse_date_part(s, y, mo, d)) return std::nullopt;
  long double tod = 0;
  if (with_time && (!take(s, 'T') || !parse_time_part(s, tod))) return std::nullopt;
  Instant out;
  int64_t offset = 0;
  if (!parse_zone(s, out.has_zone, offset)) return std::nullopt;
  if (require_zone && !out.has_zone) return std::nullopt;
  out.seconds = static_cast<long double>(
                    days_from_civil(y, static_cast<unsigned>(mo), static_cast<unsigned>(d))) *
                    86400.0L +
                tod - static_cast<long double>(offset);
  return out;
}

std::optional<Instant> parse_time(std::string_view s) {
  long double tod = 0;
  if (!parse_time_part(s, tod)) return std::nullopt;
  Instant out;
  int64_t offset = 0;
  if (!parse_zone(s, out.has_zone, offset)) return std::nullopt;
  out.seconds = tod - static_cast<long double>(offset);
  return out;
}

bool in_integer_range(const Decimal& d, const DatatypeInfo& type) {
  auto bound = [](std::string_view text) { return *parse_decimal(text, false); };
  if (!type.min.empty() && compare_decimal(d, bound(type.min)) < 0) return false;
  if (!type.max.empty() && compare_decimal(d, bound(type.max)) > 0) return false;
  return true;
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

bool numeric(Xsd k) {
  return k == Xsd::Decimal || k == Xsd::Integer || k == Xsd::Float || k == Xsd::Double;
}

Order compare_instants(const Instant& a, const Instant& b) {
  if (a.has_zone == b.has_zone) return order_of(a.seconds, b.seconds);
  // XSD 3.2.7.4: a value without a zone stands for every zone from -14:00 to +14:00.
  constexpr long double kSpan = 14 * 3600;
  const Instant& local = a.has_zone ? b : a;
  const Instant& zoned = a.has_zone ? a : b;
  Order local_vs_zoned = Order::Incomparable;
  if (local.seconds + kSpan < zoned.seconds) local_vs_zoned = Order::Less;
  if (local.seconds - kSpan > zoned.seconds) local_vs_zoned = Order::Greater;
  if (local_vs_zoned == Order::Incomparable || !a.has_zone) return local_vs_zoned;
  return local_vs_zoned == Order::Less ? Order::Greater : Order::Less;
}

}  // namespace

DatatypeInfo classify_datatype(std::string_view iri) {
  if (iri == vocab::rdf::langString) return {Xsd::LangString};
  if (iri.substr(0, kXsdNs.size()) != kXsdNs) return {};
  std::string_view n = iri.substr(kXsdNs.size());
  if (n == "string") return {Xsd::String};
  if (n == "boolean") return {Xsd::Boolean};
  if (n == "decimal") return {Xsd::Decimal};
  if (n == "float") return {Xsd::Float};
  if (n == "double") return {Xsd::Double};
  if (n == "dateTime") return {Xsd::DateTime};
  if (n == "dateTimeStamp") return {Xsd::DateTimeStamp};
  if (n == "date") return {Xsd::Date};
  if (n == "time") return {Xsd::Time};
  if (n == "integer") return {Xsd::Integer};
  if (n == "nonPositiveInteger") return {Xsd::Integer, "", "0"};
  if (n == "negativeInteger") return {Xsd::Integer, "", "-1"};
  if (n == "nonNegativeInteger") return {Xsd::Integer, "0", ""};
  if (n == "positiveInteger") return {Xsd::Integer, "1", ""};
  if (n == "long") return {Xsd::Integer, "-9223372036854775808", "9223372036854775807"};
  if (n == "int") return {Xsd::Integer, "-2147483648", "2147483647"};
  if (n == "short") return {Xsd::Integer, "-32768", "32767"};
  if (n == "byte") return {Xsd::Integer, "-128", "127"};
  if (n == "unsignedLong") return {Xsd::Integer, "0", "18446744073709551615"};
  if (n == "unsignedInt") return {Xsd::Integer, "0", "4294967295"};
  if (n == "unsignedShort") return {Xsd::Integer, "0", "65535"};
  if (n == "unsignedByte") return {Xsd::Integer, "0", "255"};
  return {};
}

bool well_formed(std::string_view s, const DatatypeInfo& type) {
  switch (type.kind) {
    case Xsd::Other:
    case Xsd::String:
    case Xsd::LangString:
      return true;
    case Xsd::Boolean:
      return s == "true" || s == "false" || s == "1" || s == "0";
    case Xsd::Decimal:
      return parse_decimal(s, true).has_value();
    case Xsd::Integer: {
      auto d = parse_decimal(s, false);
      return d && in_integer_range(*d, type);
    }
    case Xsd::Float:
    case Xsd::Double:
      return well_formed_float(s);
    case Xsd::DateTime:
      return parse_date_time(s, true, false).has_value();
    case Xsd::DateTimeStamp:
      return parse_date_time(s, true, true).has_value();
    case Xsd::Date:
      return parse_date_time(s, false, false).has_value();
    case Xsd::Time:
      return parse_time(s).has_value();
  }
  return true;
}

Order compare_literals(const LiteralView& a, const LiteralView& b) {
  if (!a.language.empty() || !b.language.empty()) return Order::Incomparable;
  const DatatypeInfo ta = classify_datatype(a.datatype);
  const DatatypeInfo tb = classify_datatype(b.datatype);
  if (!well_formed(a.lexical, ta) || !well_formed(b.lexical, tb)) return Order::Incomparable;
  if (numeric(ta.kind) && numeric(tb.kind)) {
    bool exact = (ta.kind == Xsd::Decimal || ta.kind == Xsd::Integer) &&
                 (tb.kind == Xsd::Decimal || tb.kind == Xsd::Integer);
    if (exact)
      return from_int(
          compare_decimal(*parse_decimal(a.lexical, true), *parse_decimal(b.lexical, true)));
    auto x = parse_double(a.lexical);
    auto y = parse_double(b.lexical);
    if (!x || !y) return Order::Incomparable;
    return order_of(*x, *y);
  }
  if (ta.kind != tb.kind) {
    bool both_date_time = (ta.kind == Xsd::DateTime || ta.kind == Xsd::DateTimeStamp) &&
                          (tb.kind == Xsd::DateTime || tb.kind == Xsd::DateTimeStamp);
    if (!both_date_time) return Order::Incomparable;
  }
  switch (ta.kind) {
    case Xsd::String:
      return from_int(a.lexical.compare(b.lexical));
    case Xsd::Boolean: {
      bool x = a.lexical == "true" || a.lexical == "1";
      bool y = b.lexical == "true" || b.lexical == "1";
      return order_of(x, y);
    }
    case Xsd::DateTime:
    case Xsd::DateTimeStamp:
      return compare_instants(*parse_date_time(a.lexical, true, false),
                              *parse_date_time(b.lexical, true, false));
    case Xsd::Date:
      return compare_instants(*parse_date_time(a.lexical, false, false),
                              *parse_date_time(b.lexical, false, false));
    case Xsd::Time:
      return compare_instants(*parse_time(a.lexical), *parse_time(b.lexical));
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
