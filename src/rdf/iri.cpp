#include "rdf/iri.hpp"

#include <array>
#include <cstdint>
#include <optional>

namespace mospec::rdf {

namespace {

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_hex(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// Length of "scheme:" at the start of s (0 when there is none).
size_t scheme_length(std::string_view s) {
  if (s.empty() || !is_alpha(s[0])) return 0;
  for (size_t i = 1; i < s.size(); ++i) {
    const char c = s[i];
    if (c == ':') return i + 1;
    if (!is_alpha(c) && !is_digit(c) && c != '+' && c != '-' && c != '.') return 0;
  }
  return 0;
}

// RFC 3986 section 3 split. Undefined and empty components differ (a "?" with
// nothing after it is a defined, empty query), so each has a flag.
struct Parts {
  std::string_view scheme;  // without ':'
  std::string_view authority;
  std::string_view path;
  std::string_view query;
  std::string_view fragment;
  bool has_scheme = false, has_authority = false, has_query = false, has_fragment = false;
};

Parts split(std::string_view s) {
  Parts p;
  if (size_t n = scheme_length(s); n != 0) {
    p.has_scheme = true;
    p.scheme = s.substr(0, n - 1);
    s.remove_prefix(n);
  }
  if (size_t hash = s.find('#'); hash != std::string_view::npos) {
    p.has_fragment = true;
    p.fragment = s.substr(hash + 1);
    s = s.substr(0, hash);
  }
  if (size_t q = s.find('?'); q != std::string_view::npos) {
    p.has_query = true;
    p.query = s.substr(q + 1);
    s = s.substr(0, q);
  }
  if (s.starts_with("//")) {
    p.has_authority = true;
    s.remove_prefix(2);
    size_t slash = s.find('/');
    p.authority = s.substr(0, slash);
    s = slash == std::string_view::npos ? std::string_view{} : s.substr(slash);
  }
  p.path = s;
  return p;
}

// RFC 3986 section 5.2.4, on a copy of the input buffer.
std::string remove_dot_segments(std::string_view in) {
  std::string out;
  out.reserve(in.size());
  auto drop_last_segment = [&out] {
    size_t slash = out.rfind('/');
    out.erase(slash == std::string::npos ? 0 : slash);
  };
  while (!in.empty()) {
    if (in.starts_with("../")) {
      in.remove_prefix(3);
    } else if (in.starts_with("./")) {
      in.remove_prefix(2);
    } else if (in.starts_with("/./")) {
      in.remove_prefix(2);  // leaves "/"
    } else if (in == "/.") {
      in = "/";
    } else if (in.starts_with("/../")) {
      in.remove_prefix(3);  // leaves "/"
      drop_last_segment();
    } else if (in == "/..") {
      in = "/";
      drop_last_segment();
    } else if (in == "." || in == "..") {
      in = {};
    } else {
      // Move the first segment (with its leading '/', if any) to the output.
      size_t end = in.find('/', in[0] == '/' ? 1 : 0);
      if (end == std::string_view::npos) end = in.size();
      out.append(in.substr(0, end));
      in.remove_prefix(end);
    }
  }
  return out;
}

// RFC 3986 section 5.2.3.
std::string merge_paths(const Parts& base, std::string_view reference_path) {
  std::string out;
  if (base.has_authority && base.path.empty()) {
    out = "/";
  } else if (size_t slash = base.path.rfind('/'); slash != std::string_view::npos) {
    out = base.path.substr(0, slash + 1);
  }
  out.append(reference_path);
  return out;
}

}  // namespace

bool is_absolute_iri(std::string_view s) {
  return scheme_length(s) != 0;
}

namespace {

// What a plain one-segment reference ("link-1": no scheme, authority, query,
// fragment or dot segment) is appended to when resolved against `base`, or
// nullopt when 5.2.2's merge and remove_dot_segments may change more than the
// base's last segment (a base path with dot segments).
std::optional<std::string> plain_segment_prefix(std::string_view base) {
  const Parts b = split(base);
  if (b.path.find("/.") != std::string_view::npos || b.path.starts_with('.')) return std::nullopt;
  std::string out;
  if (b.has_scheme) {
    out.append(b.scheme);
    out += ':';
  }
  if (b.has_authority) {
    out += "//";
    out.append(b.authority);
  }
  if (b.has_authority && b.path.empty()) {
    out += '/';
  } else if (size_t slash = b.path.rfind('/'); slash != std::string_view::npos) {
    out.append(b.path.substr(0, slash + 1));
  }
  return out;
}

bool is_plain_segment(std::string_view reference) {
  if (reference.empty() || reference == "." || reference == "..") return false;
  for (char c : reference) {
    if (c == ':' || c == '/' || c == '?' || c == '#') return false;
  }
  return true;
}

}  // namespace

namespace {

// RFC 3986 sections 5.2.2 and 5.3 in full, for a non-empty base.
std::string resolve_in_full(std::string_view base, std::string_view reference) {
  const Parts b = split(base);
  const Parts r = split(reference);

  // RFC 3986 section 5.2.2 (strict: a reference with a scheme is never
  // treated as relative, even when the scheme equals the base's).
  Parts t;
  std::string path;
  if (r.has_scheme) {
    t = r;
    path = remove_dot_segments(r.path);
  } else {
    if (r.has_authority) {
      t.has_authority = true;
      t.authority = r.authority;
      path = remove_dot_segments(r.path);
      t.has_query = r.has_query;
      t.query = r.query;
    } else {
      if (r.path.empty()) {
        path = std::string(b.path);
        if (r.has_query) {
          t.has_query = true;
          t.query = r.query;
        } else {
          t.has_query = b.has_query;
          t.query = b.query;
        }
      } else {
        path = remove_dot_segments(r.path.starts_with('/') ? std::string(r.path)
                                                           : merge_paths(b, r.path));
        t.has_query = r.has_query;
        t.query = r.query;
      }
      t.has_authority = b.has_authority;
      t.authority = b.authority;
    }
    t.has_scheme = b.has_scheme;
    t.scheme = b.scheme;
  }
  t.has_fragment = r.has_fragment;
  t.fragment = r.fragment;

  // RFC 3986 section 5.3.
  std::string out;
  out.reserve(base.size() + reference.size());
  if (t.has_scheme) {
    out.append(t.scheme);
    out += ':';
  }
  if (t.has_authority) {
    out += "//";
    out.append(t.authority);
  }
  out += path;
  if (t.has_query) {
    out += '?';
    out.append(t.query);
  }
  if (t.has_fragment) {
    out += '#';
    out.append(t.fragment);
  }
  return out;
}

}  // namespace

std::string resolve_iri(std::string_view base, std::string_view reference) {
  if (base.empty()) return std::string(reference);
  // The common case: a plain segment against a base without dot segments;
  // the result is written directly (what 5.2.2 - 5.3 would give).
  if (is_plain_segment(reference)) {
    if (std::optional<std::string> prefix = plain_segment_prefix(base)) {
      return std::move(prefix->append(reference));
    }
  }
  return resolve_in_full(base, reference);
}

IriBase::IriBase(std::string iri) : iri_(std::move(iri)) {
  if (!iri_.empty()) plain_prefix_ = plain_segment_prefix(iri_);
}

void IriBase::resolve_into(std::string& out, std::string_view reference) const {
  if (iri_.empty()) {
    out.assign(reference);
    return;
  }
  if (plain_prefix_ && is_plain_segment(reference)) {
    out.reserve(plain_prefix_->size() + reference.size());
    out.assign(*plain_prefix_).append(reference);
    return;
  }
  out = resolve_in_full(iri_, reference);
}

std::string IriBase::resolve(std::string_view reference) const {
  std::string out;
  resolve_into(out, reference);
  return out;
}

namespace {

// RFC 3987 well-formedness as far as it matters for RDF output: a scheme,
// no characters that IRIs exclude (space, controls, <>"{}|\^`), at most one
// '#', and percent signs that start an escape. Expansion leaves relative references in
// place when there is no base; those are not IRIs and their triples are dropped.
// Per byte after the scheme: 0 ordinary, 1 excluded (controls, space, DEL and
// <>"{}|\^`), 2 '#', 3 '%'.
constexpr std::array<uint8_t, 256> kIriByteClass = [] {
  std::array<uint8_t, 256> t{};
  for (int c = 0; c <= 0x20; ++c) t[static_cast<size_t>(c)] = 1;
  t[0x7f] = 1;
  for (char c : std::string_view("<>\"{}|\\^`")) t[static_cast<unsigned char>(c)] = 1;
  t['#'] = 2;
  t['%'] = 3;
  return t;
}();

}  // namespace

bool is_well_formed_iri(std::string_view s) {
  if (s.empty() || !is_alpha(s[0])) return false;
  size_t colon = 0;
  for (size_t i = 1; i < s.size(); ++i) {
    char c = s[i];
    if (c == ':') {
      colon = i;
      break;
    }
    if (!is_alpha(c) && !is_digit(c) && c != '+' && c != '-' && c != '.') return false;
  }
  if (colon == 0) return false;
  bool fragment = false;  // a fragment may not contain another '#'
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const size_t n = s.size();
  for (size_t i = colon + 1; i < n; ++i) {
    // Ordinary bytes four at a time (most of an IRI).
    while (i + 4 <= n && (kIriByteClass[p[i]] | kIriByteClass[p[i + 1]] | kIriByteClass[p[i + 2]] |
                          kIriByteClass[p[i + 3]]) == 0) {
      i += 4;
    }
    if (i >= n) break;
    const uint8_t cls = kIriByteClass[p[i]];
    if (cls == 0) continue;
    if (cls == 1) return false;
    if (cls == 2) {
      if (fragment) return false;
      fragment = true;
    } else if (i + 2 >= n || !is_hex(s[i + 1]) || !is_hex(s[i + 2])) {
      return false;
    }
  }
  return true;
}

std::string iri_problem(std::string_view s) {
  if (is_well_formed_iri(s)) return {};
  if (scheme_length(s) == 0) return "it has no scheme (it is not an absolute IRI)";
  size_t hashes = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const auto u = static_cast<unsigned char>(s[i]);
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string code = "U+00";
    code += kHex[u >> 4];
    code += kHex[u & 15];
    if (u == ' ') return "it contains a space (U+0020; write %20)";
    if (u < 0x20 || u == 0x7f) return "it contains the control character " + code;
    if (std::string_view("<>\"{}|\\^`").find(s[i]) != std::string_view::npos) {
      return std::string("it contains '") + s[i] + "' (" + code + "), which IRIs exclude";
    }
    if (s[i] == '#' && ++hashes > 1) return "it contains a second '#'";
    if (s[i] == '%' && (i + 2 >= s.size() || !is_hex(s[i + 1]) || !is_hex(s[i + 2]))) {
      return "it contains a '%' that starts no %XX escape";
    }
  }
  return "it is not a well-formed IRI";
}

}  // namespace mospec::rdf
