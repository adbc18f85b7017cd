#include "rdf/xsd.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>

#include "vocab/w3c.hpp"

namespace mospec::rdf::xsd {

namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!is_digit(c)) return false;
  return true;
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

bool in_integer_range(const Decimal& d, const Datatype& type) {
  auto bound = [](std::string_view text) { return *parse_decimal(text, false); };
  if (!type.min.empty() && compare(d, bound(type.min)) < 0) return false;
  if (!type.max.empty() && compare(d, bound(type.max)) > 0) return false;
  return true;
}

// The canonical xsd:double form of a finite JSON number, as JSON-LD's
// object-to-RDF conversion writes it: -?d.d+E-?d+ with a non-zero leading
// digit (or 0.0E0).
bool canonical_double_form(std::string_view s) {
  auto digits = [](std::string_view d) { return all_digits(d); };
  if (!s.empty() && s.front() == '-') s.remove_prefix(1);
  const size_t e = s.find('E');
  if (e == std::string_view::npos || e < 3 || s[1] != '.') return false;
  std::string_view exponent = s.substr(e + 1);
  if (!exponent.empty() && exponent.front() == '-') exponent.remove_prefix(1);
  return digits(s.substr(0, 1)) && digits(s.substr(2, e - 2)) && digits(exponent) &&
         (s.front() != '0' || s.substr(0, e) == "0.0");
}

// A float-lexical-space form's value in T (double or long double).
template <class T>
std::optional<T> to_floating(std::string_view lexical) {
  if (!well_formed_float(lexical)) return std::nullopt;
  constexpr T kInf = std::numeric_limits<T>::infinity();
  if (lexical == "INF" || lexical == "+INF") return kInf;
  if (lexical == "-INF") return -kInf;
  if (lexical == "NaN") return std::numeric_limits<T>::quiet_NaN();
  // from_chars reads no leading '+': strip the sign and apply it afterwards.
  // A range error ("1e400": inf, "1e-400": 0) or a form from_chars reads
  // differently from XSD goes to strtod, which rounds the same way.
  const bool negative = lexical.front() == '-';
  if (lexical.front() == '+' || negative) lexical.remove_prefix(1);
  T v = 0;
  auto [p, ec] = std::from_chars(lexical.data(), lexical.data() + lexical.size(), v);
  if (ec != std::errc() || p != lexical.data() + lexical.size()) {
    const std::string copy(lexical);
    if constexpr (std::is_same_v<T, double>)
      v = std::strtod(copy.c_str(), nullptr);
    else
      v = std::strtold(copy.c_str(), nullptr);
  }
  return negative ? -v : v;
}

}  // namespace

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

int compare(const Decimal& a, const Decimal& b) {
  if (a.negative != b.negative) return a.negative ? -1 : 1;
  int m = 0;
  if (a.integer.size() != b.integer.size()) {
    m = a.integer.size() < b.integer.size() ? -1 : 1;
  } else if (int c = a.integer.compare(b.integer); c != 0) {
    m = c < 0 ? -1 : 1;
  } else if (int f = a.fraction.compare(b.fraction); f != 0) {
    m = f < 0 ? -1 : 1;
  }
  return a.negative ? -m : m;
}

Datatype classify(std::string_view iri) {
  if (iri == vocab::rdf::langString) return {Kind::LangString};
  if (!iri.starts_with(vocab::xsd::ns)) return {};
  std::string_view n = iri.substr(vocab::xsd::ns.size());
  if (n == "string") return {Kind::String};
  if (n == "boolean") return {Kind::Boolean};
  if (n == "decimal") return {Kind::Decimal};
  if (n == "float") return {Kind::Float};
  if (n == "double") return {Kind::Double};
  if (n == "dateTime") return {Kind::DateTime};
  if (n == "dateTimeStamp") return {Kind::DateTimeStamp};
  if (n == "date") return {Kind::Date};
  if (n == "time") return {Kind::Time};
  if (n == "integer") return {Kind::Integer};
  if (n == "nonPositiveInteger") return {Kind::Integer, "", "0"};
  if (n == "negativeInteger") return {Kind::Integer, "", "-1"};
  if (n == "nonNegativeInteger") return {Kind::Integer, "0", ""};
  if (n == "positiveInteger") return {Kind::Integer, "1", ""};
  if (n == "long") return {Kind::Integer, "-9223372036854775808", "9223372036854775807"};
  if (n == "int") return {Kind::Integer, "-2147483648", "2147483647"};
  if (n == "short") return {Kind::Integer, "-32768", "32767"};
  if (n == "byte") return {Kind::Integer, "-128", "127"};
  if (n == "unsignedLong") return {Kind::Integer, "0", "18446744073709551615"};
  if (n == "unsignedInt") return {Kind::Integer, "0", "4294967295"};
  if (n == "unsignedShort") return {Kind::Integer, "0", "65535"};
  if (n == "unsignedByte") return {Kind::Integer, "0", "255"};
  return {};
}

bool well_formed(std::string_view s, const Datatype& type) {
  switch (type.kind) {
    case Kind::Other:
    case Kind::String:
    case Kind::LangString:
      return true;
    case Kind::Boolean:
      return s == "true" || s == "false" || s == "1" || s == "0";
    case Kind::Decimal:
      return parse_decimal(s, true).has_value();
    case Kind::Integer: {
      auto d = parse_decimal(s, false);
      return d && in_integer_range(*d, type);
    }
    case Kind::Float:
    case Kind::Double:
      return well_formed_float(s);
    case Kind::DateTime:
    case Kind::DateTimeStamp:
    case Kind::Date:
    case Kind::Time:
      return parse_instant(s, type.kind).has_value();
  }
  return true;
}

std::optional<double> to_double(std::string_view lexical) {
  return to_floating<double>(lexical);
}

std::optional<long double> to_long_double(std::string_view lexical) {
  return to_floating<long double>(lexical);
}

std::optional<Instant> parse_instant(std::string_view s, Kind kind) {
  switch (kind) {
    case Kind::DateTime:
      return parse_date_time(s, true, false);
    case Kind::DateTimeStamp:
      return parse_date_time(s, true, true);
    case Kind::Date:
      return parse_date_time(s, false, false);
    case Kind::Time:
      return parse_time(s);
    default:
      return std::nullopt;
  }
}

std::optional<double> number(std::string_view lexical, std::string_view datatype_iri) {
  Datatype type = classify(datatype_iri);
  if (type.kind == Kind::String) type = Datatype(Kind::Double);
  bool ok = false;
  switch (type.kind) {
    case Kind::Decimal:
      ok = well_formed(lexical, type) || canonical_double_form(lexical);
      break;
    case Kind::Integer:
    case Kind::Float:
    case Kind::Double:
      ok = well_formed(lexical, type);
      break;
    default:
      break;
  }
  if (!ok) return std::nullopt;
  return to_double(lexical);
}

}  // namespace mospec::rdf::xsd
