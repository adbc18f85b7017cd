#include "sparql/regex.hpp"

#include <re2/re2.h>

namespace mospec::sparql {

namespace {

// XML 1.0 (fifth edition) NameStartChar and the rest of NameChar, as class
// bodies (XPath's \i and \c).
constexpr std::string_view kNameStart =
    ":A-Z_a-z\\x{C0}-\\x{D6}\\x{D8}-\\x{F6}\\x{F8}-\\x{2FF}\\x{370}-\\x{37D}\\x{37F}-\\x{1FFF}"
    "\\x{200C}-\\x{200D}\\x{2070}-\\x{218F}\\x{2C00}-\\x{2FEF}\\x{3001}-\\x{D7FF}"
    "\\x{F900}-\\x{FDCF}\\x{FDF0}-\\x{FFFD}\\x{10000}-\\x{EFFFF}";
constexpr std::string_view kNameRest = "\\-.0-9\\x{B7}\\x{300}-\\x{36F}\\x{203F}-\\x{2040}";

// The pattern as messages quote it: at most 80 bytes, cut at a character
// boundary, so that a huge pattern does not make a huge message.
std::string quoted(std::string_view pattern) {
  constexpr size_t kMax = 80;
  if (pattern.size() <= kMax) return "\"" + std::string(pattern) + "\"";
  size_t cut = kMax;
  while (cut > 0 && (static_cast<unsigned char>(pattern[cut]) & 0xC0) == 0x80) --cut;
  return "\"" + std::string(pattern.substr(0, cut)) + "...\" (" + std::to_string(pattern.size()) +
         " bytes)";
}

struct Flags {
  bool dot_all = false, multiline = false, icase = false, extended = false, literal = false;
};

Flags parse_flags(std::string_view flags) {
  Flags f;
  for (char c : flags) {
    switch (c) {
      case 's':
        f.dot_all = true;
        break;
      case 'm':
        f.multiline = true;
        break;
      case 'i':
        f.icase = true;
        break;
      case 'x':
        f.extended = true;
        break;
      case 'q':
        f.literal = true;
        break;
      default:
        throw RegexError(RegexError::Kind::Flag, std::string("invalid regular expression flag '") +
                                                     c + "' (allowed: s, m, i, x, q)");
    }
  }
  return f;
}

std::string translate(std::string_view pattern, const Flags& f) {
  std::string out;
  if (f.icase) out += "(?i)";
  if (f.literal) {  // q: every other flag is ignored (F&O 3.1, 5.6.1.1)
    out += RE2::QuoteMeta(re2::StringPiece(pattern.data(), pattern.size()));
    return out;
  }
  if (f.multiline) out += "(?m)";
  if (f.dot_all) out += "(?s)";
  auto unsupported = [&](const std::string& what) {
    throw RegexError(RegexError::Kind::Unsupported,
                     what + " is not supported (in regular expression " + quoted(pattern) + ")");
  };
  bool in_class = false;
  for (size_t i = 0; i < pattern.size(); ++i) {
    const char c = pattern[i];
    if (c == '\\') {
      if (i + 1 == pattern.size())
        throw RegexError(RegexError::Kind::Invalid,
                         "invalid regular expression " + quoted(pattern) + ": trailing '\\'");
      const char n = pattern[++i];
      switch (n) {
        case 'i':
        case 'c': {
          std::string body(kNameStart);
          if (n == 'c') body += kNameRest;
          out += in_class ? body : "[" + body + "]";
          break;
        }
        case 'I':
        case 'C': {
          if (in_class)
            unsupported(std::string("XPath escape \\") + n + " inside a character class");
          std::string body(kNameStart);
          if (n == 'C') body += kNameRest;
          out += "[^" + body + "]";
          break;
        }
        case 'p':
        case 'P': {
          const size_t close = pattern.find('}', i);
          if (i + 1 < pattern.size() && pattern[i + 1] == '{' && close != std::string_view::npos &&
              pattern.substr(i + 2, 2) == "Is") {
            unsupported("XPath block escape \\" + std::string(pattern.substr(i, close - i + 1)));
          }
          out += '\\';
          out += n;
          break;
        }
        default:
          out += '\\';
          out += n;
      }
      continue;
    }
    if (in_class) {
      if (c == '-' && i + 1 < pattern.size() && pattern[i + 1] == '[')
        unsupported("XPath character class subtraction '-['");
      if (c == '[') {  // literal in XPath; RE2 would read "[:alpha:]"
        out += "\\[";
        continue;
      }
      if (c == ']') in_class = false;
      out += c;
      continue;
    }
    if (f.extended && (c == ' ' || c == '\t' || c == '\n' || c == '\r')) continue;
    if (c == '[') {
      in_class = true;
      out += c;
      if (i + 1 < pattern.size() && pattern[i + 1] == '^') out += pattern[++i];
      if (i + 1 < pattern.size() && pattern[i + 1] == ']') {
        out += "\\]";
        ++i;
      }
      continue;
    }
    if (c == '.' && !f.dot_all) {
      out += "[^\\n\\r]";
      continue;
    }
    out += c;
  }
  return out;
}

}  // namespace

Regex::Regex(std::string_view pattern, std::string_view flags)
    : translated_(translate(pattern, parse_flags(flags))) {
  RE2::Options options;
  options.set_log_errors(false);  // errors are returned, never printed
  auto re = std::make_shared<const RE2>(re2::StringPiece(translated_.data(), translated_.size()),
                                        options);
  if (!re->ok()) {
    throw RegexError(RegexError::Kind::Invalid,
                     "invalid regular expression " + quoted(pattern) + ": " + re->error());
  }
  re_ = std::move(re);
}

bool Regex::search(std::string_view text) const {
  return RE2::PartialMatch(re2::StringPiece(text.data(), text.size()), *re_);
}

}  // namespace mospec::sparql
