#include "rdf/nquads.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

#include "rdf/iri.hpp"
#include "support/utf8.hpp"

namespace mospec::rdf {

namespace {

bool is_alpha(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(unsigned char c) {
  return c >= '0' && c <= '9';
}
bool is_hex(unsigned char c) {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}
unsigned hex_value(unsigned char c) {
  if (is_digit(c)) return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return c - 'A' + 10;
}

// Characters IRIREF excludes (besides the controls and space).
bool forbidden_in_iri(uint32_t c) {
  return c <= 0x20 || c == '<' || c == '>' || c == '"' || c == '{' || c == '}' || c == '|' ||
         c == '^' || c == '`' || c == '\\';
}

// N-Triples PN_CHARS_BASE.
bool is_pn_chars_base(uint32_t c) {
  return (c < 0x80 && is_alpha(static_cast<unsigned char>(c))) || (c >= 0xC0 && c <= 0xD6) ||
         (c >= 0xD8 && c <= 0xF6) || (c >= 0xF8 && c <= 0x2FF) || (c >= 0x370 && c <= 0x37D) ||
         (c >= 0x37F && c <= 0x1FFF) || (c >= 0x200C && c <= 0x200D) ||
         (c >= 0x2070 && c <= 0x218F) || (c >= 0x2C00 && c <= 0x2FEF) ||
         (c >= 0x3001 && c <= 0xD7FF) || (c >= 0xF900 && c <= 0xFDCF) ||
         (c >= 0xFDF0 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0xEFFFF);
}
// N-Triples PN_CHARS_U (which, unlike Turtle's, includes ':').
bool is_pn_chars_u(uint32_t c) {
  return is_pn_chars_base(c) || c == '_' || c == ':';
}
bool is_pn_chars(uint32_t c) {
  return is_pn_chars_u(c) || c == '-' || (c >= '0' && c <= '9') || c == 0xB7 ||
         (c >= 0x300 && c <= 0x36F) || (c >= 0x203F && c <= 0x2040);
}

class Parser {
 public:
  Parser(std::string_view text, Dataset& into, const NQuadsOptions& options, uint32_t file_id,
         std::string_view file_name)
      : options_(options),
        text_(text),
        data_(into),
        terms_(into.terms()),
        file_id_(file_id),
        file_name_(file_name),
        prefix_(into.terms().fresh_blank_prefix()) {}

  void run() {
    for (;;) {
      skip_space();
      if (at_end()) return;
      const unsigned char c = peek();
      if (c == '#') {
        skip_comment();
      } else if (c == '\n' || c == '\r') {
        newline();
      } else {
        statement();
      }
    }
  }

 private:
  // ---- cursor -------------------------------------------------------------
  bool at_end() const { return pos_ >= text_.size(); }
  unsigned char peek(size_t ahead = 0) const {
    return pos_ + ahead < text_.size() ? static_cast<unsigned char>(text_[pos_ + ahead]) : 0;
  }
  uint32_t column() const { return static_cast<uint32_t>(pos_ - line_start_ + 1); }

  void skip_space() {
    while (!at_end() && (peek() == ' ' || peek() == '\t')) ++pos_;
  }
  void skip_comment() {
    while (!at_end() && peek() != '\n' && peek() != '\r') ++pos_;
  }
  void newline() {
    // CR LF counts as one line break; a lone CR or LF as one each.
    if (peek() == '\r' && peek(1) == '\n') ++pos_;
    ++pos_;
    ++line_;
    line_start_ = pos_;
  }

  // What is at the cursor, for messages.
  std::string found() const {
    if (at_end()) return "end of input";
    const unsigned char c = peek();
    if (c == '\n' || c == '\r') return "end of line";
    if (c >= 0x21 && c < 0x7F) return std::string("'") + static_cast<char>(c) + "'";
    if (c == ' ') return "' '";
    char buf[16];
    std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
    return buf;
  }

  [[noreturn]] void fail(const std::string& message) const { fail_at(message, column()); }
  [[noreturn]] void fail_at(const std::string& message, uint32_t col) const {
    throw Error("syntax", message, std::string(file_name_), line_, col);
  }

  // Decodes one UTF-8 scalar value at the cursor and advances past it.
  uint32_t take_utf8() {
    const unsigned char b0 = peek();
    uint32_t c = 0;
    size_t len = 0;
    uint32_t min = 0;
    if (b0 < 0x80) {
      ++pos_;
      return b0;
    } else if ((b0 & 0xE0) == 0xC0) {
      c = b0 & 0x1F;
      len = 2;
      min = 0x80;
    } else if ((b0 & 0xF0) == 0xE0) {
      c = b0 & 0x0F;
      len = 3;
      min = 0x800;
    } else if ((b0 & 0xF8) == 0xF0) {
      c = b0 & 0x07;
      len = 4;
      min = 0x10000;
    } else {
      fail("invalid UTF-8 byte 0x" + hex2(b0));
    }
    for (size_t i = 1; i < len; ++i) {
      const unsigned char b = peek(i);
      if ((b & 0xC0) != 0x80 || pos_ + i >= text_.size())
        fail("invalid UTF-8 sequence starting with byte 0x" + hex2(b0));
      c = (c << 6) | (b & 0x3F);
    }
    if (c < min || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF))
      fail("invalid UTF-8 sequence starting with byte 0x" + hex2(b0));
    pos_ += len;
    return c;
  }
  static std::string hex2(unsigned char b) {
    char buf[4];
    std::snprintf(buf, sizeof buf, "%02X", b);
    return buf;
  }

  // UCHAR after the backslash: 'u' XXXX or 'U' XXXXXXXX.
  uint32_t take_uchar() {
    const uint32_t col = column() - 1;  // at the backslash
    const size_t digits = peek() == 'u' ? 4 : 8;
    ++pos_;
    uint32_t c = 0;
    for (size_t i = 0; i < digits; ++i) {
      if (!is_hex(peek()))
        fail_at(std::string("\\") + (digits == 4 ? 'u' : 'U') + " escape needs " +
                    std::to_string(digits) + " hexadecimal digits",
                col);
      c = (c << 4) | hex_value(peek());
      ++pos_;
    }
    if (c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "U+%04X is not a Unicode scalar value", c);
      fail_at(buf, col);
    }
    return c;
  }

  // ---- terms --------------------------------------------------------------
  TermId iri() {
    const uint32_t start_col = column();
    ++pos_;  // '<'
    scratch_.clear();
    for (;;) {
      if (at_end() || peek() == '\n' || peek() == '\r') fail_at("unterminated IRI", start_col);
      const unsigned char c = peek();
      if (c == '>') {
        ++pos_;
        break;
      }
      if (c == '\\') {
        ++pos_;
        if (peek() != 'u' && peek() != 'U')
          fail_at("only \\u and \\U escapes are allowed in IRIs", column() - 1);
        const uint32_t esc_col = column() - 1;
        const uint32_t cp = take_uchar();
        if (forbidden_in_iri(cp)) {
          char buf[64];
          std::snprintf(buf, sizeof buf, "escaped character U+%04X is not allowed in an IRI", cp);
          fail_at(buf, esc_col);
        }
        append_utf8(scratch_, cp);
        continue;
      }
      if (forbidden_in_iri(c)) fail("character " + found() + " is not allowed in an IRI");
      if (c < 0x80) {
        scratch_ += static_cast<char>(c);
        ++pos_;
      } else {
        append_utf8(scratch_, take_utf8());
      }
    }
    if (!is_absolute_iri(scratch_))
      fail_at("relative IRI <" + scratch_ + "> (N-Quads needs absolute IRIs)", start_col);
    return terms_.iri(scratch_);
  }

  TermId blank() {
    if (peek(1) != ':') fail("expected ':' after '_' in a blank node label");
    pos_ += 2;
    scratch_ = prefix_;
    if (at_end()) fail("empty blank node label");
    {
      const size_t before = pos_;
      const uint32_t c = take_utf8();
      if (!is_pn_chars_u(c) && !(c >= '0' && c <= '9')) {
        pos_ = before;
        fail("blank node label cannot start with " + found());
      }
      scratch_.append(text_.substr(before, pos_ - before));
    }
    // (PN_CHARS | '.')* but not ending in '.': a trailing '.' ends the statement.
    size_t last_good = pos_;
    size_t last_good_len = scratch_.size();
    while (!at_end()) {
      const size_t before = pos_;
      const unsigned char b = peek();
      uint32_t c = 0;
      if (b < 0x80) {
        c = b;
        if (!is_pn_chars(c) && c != '.') break;
        ++pos_;
      } else {
        c = take_utf8();
        if (!is_pn_chars(c)) {
          pos_ = before;
          break;
        }
      }
      scratch_.append(text_.substr(before, pos_ - before));
      if (c != '.') {
        last_good = pos_;
        last_good_len = scratch_.size();
      }
    }
    pos_ = last_good;
    scratch_.resize(last_good_len);
    return terms_.blank(scratch_);
  }

  TermId literal() {
    const uint32_t start_col = column();
    ++pos_;  // '"'
    std::string lexical;
    for (;;) {
      if (at_end()) fail_at("unterminated string literal", start_col);
      const unsigned char c = peek();
      if (c == '"') {
        ++pos_;
        break;
      }
      if (c == '\n' || c == '\r') fail("line break in string literal (write it as \\n or \\r)");
      if (c == '\\') {
        ++pos_;
        const unsigned char e = peek();
        switch (e) {
          case 't':
            lexical += '\t';
            break;
          case 'b':
            lexical += '\b';
            break;
          case 'n':
            lexical += '\n';
            break;
          case 'r':
            lexical += '\r';
            break;
          case 'f':
            lexical += '\f';
            break;
          case '"':
            lexical += '"';
            break;
          case '\'':
            lexical += '\'';
            break;
          case '\\':
            lexical += '\\';
            break;
          case 'u':
          case 'U':
            append_utf8(lexical, take_uchar());
            continue;
          default:
            fail_at("invalid escape sequence in string literal", column() - 1);
        }
        ++pos_;
        continue;
      }
      if (c < 0x80) {
        lexical += static_cast<char>(c);
        ++pos_;
      } else {
        append_utf8(lexical, take_utf8());
      }
    }
    if (peek() == '^' && peek(1) == '^') {
      pos_ += 2;
      if (peek() != '<') fail("expected datatype IRI after '^^', found " + found());
      const TermId datatype = iri();
      return terms_.literal(lexical, datatype);
    }
    if (peek() == '@') {
      ++pos_;
      const size_t lang_start = pos_;
      if (!is_alpha(peek())) fail("expected language tag after '@', found " + found());
      while (is_alpha(peek())) ++pos_;
      while (peek() == '-' && peek(1) != '-') {
        ++pos_;
        if (!is_alpha(peek()) && !is_digit(peek()))
          fail("expected letter or digit in language tag, found " + found());
        while (is_alpha(peek()) || is_digit(peek())) ++pos_;
      }
      const std::string_view language = text_.substr(lang_start, pos_ - lang_start);
      std::string_view direction;
      if (peek() == '-' && peek(1) == '-') {
        const uint32_t dir_col = column();
        pos_ += 2;
        const size_t dir_start = pos_;
        while (is_alpha(peek())) ++pos_;
        direction = text_.substr(dir_start, pos_ - dir_start);
        if (direction != "ltr" && direction != "rtl")
          fail_at("base direction must be 'ltr' or 'rtl'", dir_col);
      }
      return terms_.literal(lexical, TermId::default_graph(), language, direction);
    }
    return terms_.literal(lexical);
  }

  // ---- statements -----------------------------------------------------------
  TermId any_term(const char* role) {
    switch (peek()) {
      case '<':
        return iri();
      case '_':
        return blank();
      case '"':
        return literal();
      default:
        fail(std::string("expected ") + role + " (IRI, blank node or literal), found " + found());
    }
  }

  void statement() {
    const SourceLoc where{file_id_, line_, column()};
    Quad q{};
    if (options_.generalized) {
      q.subject = any_term("subject");
      skip_space();
      q.predicate = any_term("predicate");
      skip_space();
    } else {
      switch (peek()) {
        case '<':
          q.subject = iri();
          break;
        case '_':
          q.subject = blank();
          break;
        default:
          fail("expected subject (IRI or blank node), found " + found());
      }
      skip_space();
      if (peek() != '<') fail("expected predicate IRI, found " + found());
      q.predicate = iri();
      skip_space();
    }
    switch (peek()) {
      case '<':
        q.object = iri();
        break;
      case '_':
        q.object = blank();
        break;
      case '"':
        q.object = literal();
        break;
      default:
        fail("expected object (IRI, blank node or literal), found " + found());
    }
    skip_space();
    switch (peek()) {
      case '<':
        q.graph = iri();
        break;
      case '_':
        q.graph = blank();
        break;
      default:
        break;
    }
    skip_space();
    if (peek() != '.') fail("expected '.' at end of statement, found " + found());
    ++pos_;
    skip_space();
    if (peek() == '#') skip_comment();
    if (!at_end() && peek() != '\n' && peek() != '\r')
      fail("expected end of line after '.', found " + found());
    data_.add(q, where);
  }

  NQuadsOptions options_;
  std::string_view text_;
  size_t pos_ = 0;
  uint32_t line_ = 1;
  size_t line_start_ = 0;
  Dataset& data_;
  TermTable& terms_;
  uint32_t file_id_;
  std::string_view file_name_;
  std::string prefix_;
  std::string scratch_;
};

}  // namespace

void read_nquads(std::string_view text, Dataset& into, uint32_t file_id,
                 std::string_view file_name) {
  Parser(text, into, NQuadsOptions{}, file_id, file_name).run();
}

void read_nquads(std::string_view text, Dataset& into, const NQuadsOptions& options,
                 uint32_t file_id, std::string_view file_name) {
  Parser(text, into, options, file_id, file_name).run();
}

namespace {

std::vector<std::string> sorted_lines(const Dataset& data, Format format) {
  std::vector<std::string> lines;
  lines.reserve(data.size());
  const TermTable& terms = data.terms();
  for (const Quad& q : data.quads()) {
    std::string line;
    append_ntriples(line, terms, q.subject);
    line += ' ';
    append_ntriples(line, terms, q.predicate);
    line += ' ';
    append_ntriples(line, terms, q.object);
    if (format == Format::NQuads && q.graph != TermId::default_graph()) {
      line += ' ';
      append_ntriples(line, terms, q.graph);
    }
    line += " .\n";
    lines.push_back(std::move(line));
  }
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

}  // namespace

void write_nquads(const Dataset& data, std::ostream& out, Format format) {
  for (const std::string& line : sorted_lines(data, format)) out << line;
}

std::string to_nquads(const Dataset& data, Format format) {
  std::string out;
  for (const std::string& line : sorted_lines(data, format)) out += line;
  return out;
}

}  // namespace mospec::rdf
