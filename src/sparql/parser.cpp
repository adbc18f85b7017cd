// Stage 1: SPARQL 1.1 query text -> syntax tree (ast.hpp).
//
// A hand-written recursive-descent parser over an on-demand lexer, following
// the grammar of SPARQL 1.1 section 19.8 for the supported subset. Keywords
// are case-insensitive except 'a'. Constructs outside the subset are reported
// at their keyword, so the caller never gets a partial query.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>

#include "rdf/iri.hpp"
#include "sparql/ast.hpp"
#include "support/utf8.hpp"
#include "vocab/w3c.hpp"

namespace mospec::sparql {

namespace {
std::string with_position(uint32_t line, uint32_t column, const std::string& message) {
  if (line == 0) return message;
  return "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + message;
}
}  // namespace

QueryError::QueryError(std::string code, uint32_t line, uint32_t column, const std::string& message)
    : Error(std::move(code), with_position(line, column, message)), line_(line), column_(column) {}

namespace ast {

void fail(std::string_view code, Pos pos, const std::string& message) {
  throw QueryError(std::string(code), pos.line, pos.column, message);
}

namespace {

constexpr std::string_view kSyntax = "sparql-syntax";
constexpr std::string_view kUnsupported = "unsupported-sparql";
constexpr std::string_view kRdf = vocab::rdf::ns;
constexpr std::string_view kXsd = vocab::xsd::ns;

enum class Tok : uint8_t {
  End,
  IriRef,   // text: the IRI as written (unresolved)
  PName,    // prefix: before ':', text: local part (unescaped)
  Blank,    // text: label
  Var,      // text: name
  LangTag,  // text: tag
  Integer,
  Decimal,
  Double,
  String,  // text: unescaped content
  Word,    // text: as written
  Punct,   // text: the operator
};

struct Token {
  Tok kind = Tok::End;
  std::string text;
  std::string prefix;
  size_t begin = 0, end = 0;
};

bool is_name_start(unsigned char c) {
  return std::isalpha(c) || c >= 0x80;
}
bool is_name_char(unsigned char c) {
  return std::isalnum(c) || c == '_' || c == '-' || c >= 0x80;
}
bool is_var_char(unsigned char c) {
  return std::isalnum(c) || c == '_' || c >= 0x80;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

class Parser {
 public:
  Parser(std::string_view text, const PrefixMap& prefixes, std::string_view base)
      : text_(text), prefixes_(prefixes), base_(base) {
    line_starts_.push_back(0);
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts_.push_back(i + 1);
  }

  Query parse_query() {
    Query q;
    parse_prologue();
    const Token& t = peek();
    const std::string kw = t.kind == Tok::Word ? upper(t.text) : std::string();
    if (kw == "SELECT") {
      parse_select_clause(q);
    } else if (kw == "ASK") {
      next();
      q.form = QueryForm::Ask;
    } else if (kw == "CONSTRUCT" || kw == "DESCRIBE") {
      unsupported(t, kw + " queries are");
    } else if (kw == "INSERT" || kw == "DELETE" || kw == "LOAD" || kw == "CLEAR" || kw == "DROP" ||
               kw == "CREATE" || kw == "WITH" || kw == "COPY" || kw == "MOVE" || kw == "ADD") {
      unsupported(t, "SPARQL Update (" + kw + ") is");
    } else {
      expected(t, "SELECT or ASK");
    }
    if (is_keyword(peek(), "FROM")) unsupported(peek(), "FROM (dataset clauses) is");
    if (is_keyword(peek(), "WHERE")) next();
    if (!is_punct(peek(), "{")) expected(peek(), "'{' to start the WHERE clause");
    q.where = parse_group();
    parse_modifiers(q);
    if (is_keyword(peek(), "VALUES")) unsupported(peek(), "VALUES is");
    if (peek().kind != Tok::End) expected(peek(), "end of query");
    q.base = base_;
    return q;
  }

 private:
  // ---- positions and errors ----
  Pos at(size_t offset) const {
    auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
    const size_t line = static_cast<size_t>(it - line_starts_.begin());
    return Pos{static_cast<uint32_t>(line), static_cast<uint32_t>(offset - *(it - 1) + 1)};
  }
  Pos pos(const Token& t) const { return at(t.begin); }

  std::string describe(const Token& t) const {
    switch (t.kind) {
      case Tok::End:
        return "end of query";
      case Tok::IriRef:
        return "IRI <" + t.text + ">";
      case Tok::PName:
        return "prefixed name " + t.prefix + ":" + t.text;
      case Tok::Blank:
        return "blank node _:" + t.text;
      case Tok::Var:
        return "variable ?" + t.text;
      case Tok::LangTag:
        return "language tag @" + t.text;
      case Tok::Integer:
      case Tok::Decimal:
      case Tok::Double:
        return "number " + t.text;
      case Tok::String:
        return "string literal";
      case Tok::Word:
        return "'" + t.text + "'";
      case Tok::Punct:
        return "'" + t.text + "'";
    }
    return "token";
  }
  [[noreturn]] void expected(const Token& t, const std::string& what) const {
    fail(kSyntax, pos(t), "expected " + what + ", found " + describe(t));
  }
  [[noreturn]] void unsupported(const Token& t, const std::string& what) const {
    fail(kUnsupported, pos(t), what + " not supported");
  }
  [[noreturn]] void lex_error(size_t offset, const std::string& message) const {
    fail(kSyntax, at(offset), message);
  }

  // ---- nesting ----
  // Every recursive production (groups, blank nodes and collections, property
  // path groups, parenthesised expressions and argument lists, unary operators)
  // passes through a Nested guard, so the parser's recursion, and the later
  // stages' recursion over the tree it builds, are bounded by kMaxNesting no
  // matter how the constructs are mixed.
  static constexpr int kMaxNesting = 256;
  int nesting_ = 0;
  class Nested {
   public:
    explicit Nested(Parser& p) : p_(p) {
      if (p_.nesting_ >= kMaxNesting) {
        fail(kSyntax, p_.pos(p_.peek()),
             "query nested deeper than " + std::to_string(kMaxNesting) +
                 " levels (groups, parentheses, blank nodes, collections, paths and unary "
                 "operators count together); simplify the query");
      }
      ++p_.nesting_;
    }
    ~Nested() { --p_.nesting_; }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;

   private:
    Parser& p_;
  };

  // ---- lexer ----
  void skip_space(size_t& i) const {
    while (i < text_.size()) {
      const char c = text_[i];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        ++i;
      } else if (c == '#') {
        while (i < text_.size() && text_[i] != '\n') ++i;
      } else {
        break;
      }
    }
  }

  uint32_t hex_value(size_t at_offset, size_t digits) const {
    if (at_offset + digits > text_.size()) lex_error(at_offset, "incomplete \\u escape");
    uint32_t v = 0;
    for (size_t k = 0; k < digits; ++k) {
      const char c = text_[at_offset + k];
      int d;
      if (c >= '0' && c <= '9') {
        d = c - '0';
      } else if (c >= 'a' && c <= 'f') {
        d = c - 'a' + 10;
      } else if (c >= 'A' && c <= 'F') {
        d = c - 'A' + 10;
      } else {
        lex_error(at_offset + k, "invalid hex digit in \\u escape");
      }
      v = v * 16 + static_cast<uint32_t>(d);
    }
    if (v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF))
      lex_error(at_offset, "\\u escape is not a Unicode scalar value");
    return v;
  }

  Token lex_string(size_t& i) const {
    Token t;
    t.kind = Tok::String;
    t.begin = i;
    const char quote = text_[i];
    const bool long_form = text_.compare(i, 3, std::string(3, quote)) == 0;
    i += long_form ? 3 : 1;
    for (;;) {
      if (i >= text_.size())
        fail(kSyntax, at(t.begin), "unterminated string literal (opened here)");
      const char c = text_[i];
      if (c == quote) {
        if (!long_form) {
          ++i;
          break;
        }
        if (text_.compare(i, 3, std::string(3, quote)) == 0) {
          i += 3;
          // """a"""" ends with the last three quotes: extra quotes belong to the text.
          while (i < text_.size() && text_[i] == quote) {
            t.text += quote;
            ++i;
          }
          break;
        }
        t.text += c;
        ++i;
        continue;
      }
      if (!long_form && (c == '\n' || c == '\r'))
        lex_error(i, "line break in a short string literal (use \"\"\" or \\n)");
      if (c == '\\') {
        if (i + 1 >= text_.size()) lex_error(i, "incomplete escape");
        const char e = text_[i + 1];
        switch (e) {
          case 't':
            t.text += '\t';
            break;
          case 'b':
            t.text += '\b';
            break;
          case 'n':
            t.text += '\n';
            break;
          case 'r':
            t.text += '\r';
            break;
          case 'f':
            t.text += '\f';
            break;
          case '"':
            t.text += '"';
            break;
          case '\'':
            t.text += '\'';
            break;
          case '\\':
            t.text += '\\';
            break;
          case 'u':
            append_utf8(t.text, hex_value(i + 2, 4));
            i += 6;
            continue;
          case 'U':
            append_utf8(t.text, hex_value(i + 2, 8));
            i += 10;
            continue;
          default:
            lex_error(i, std::string("invalid escape \\") + e + " in string literal");
        }
        i += 2;
        continue;
      }
      t.text += c;
      ++i;
    }
    t.end = i;
    return t;
  }

  // PN_LOCAL after the ':' (escapes \x and %xx allowed; no trailing '.').
  std::string lex_local(size_t& i) const {
    std::string out;
    size_t last_good = i;
    std::string at_last_good;
    bool first = true;
    while (i < text_.size()) {
      const auto c = static_cast<unsigned char>(text_[i]);
      if (c == '\\') {
        if (i + 1 >= text_.size()) lex_error(i, "incomplete escape in prefixed name");
        const char e = text_[i + 1];
        if (std::string_view("_~.-!$&'()*+,;=/?#@%").find(e) == std::string_view::npos)
          lex_error(i, std::string("invalid escape \\") + e + " in prefixed name");
        out += e;
        i += 2;
      } else if (c == '%') {
        if (i + 2 >= text_.size() || !std::isxdigit(static_cast<unsigned char>(text_[i + 1])) ||
            !std::isxdigit(static_cast<unsigned char>(text_[i + 2])))
          lex_error(i, "'%' in a prefixed name must start a %XX escape");
        out.append(text_.substr(i, 3));
        i += 3;
      } else if (is_name_char(c) || c == ':' || (first && std::isdigit(c))) {
        out += static_cast<char>(c);
        ++i;
      } else if (c == '.' && !first) {
        out += '.';
        ++i;
        continue;  // a trailing '.' is not part of the name
      } else {
        break;
      }
      first = false;
      last_good = i;
      at_last_good = out;
    }
    i = last_good;
    return at_last_good;
  }

  Token lex(size_t& i, bool operator_mode) const {
    skip_space(i);
    Token t;
    t.begin = i;
    if (i >= text_.size()) {
      t.kind = Tok::End;
      t.end = i;
      return t;
    }
    const auto c = static_cast<unsigned char>(text_[i]);
    auto punct = [&](size_t n) {
      t.kind = Tok::Punct;
      t.text = std::string(text_.substr(i, n));
      i += n;
      t.end = i;
      return t;
    };
    auto starts = [&](std::string_view s) { return text_.compare(i, s.size(), s) == 0; };

    if (c == '<') {
      if (!operator_mode) {
        size_t j = i + 1;
        while (j < text_.size()) {
          const auto d = static_cast<unsigned char>(text_[j]);
          if (d == '>' || d <= 0x20 ||
              std::string_view("<\"{}|^`\\").find(static_cast<char>(d)) != std::string_view::npos)
            break;
          ++j;
        }
        if (j < text_.size() && text_[j] == '>') {
          t.kind = Tok::IriRef;
          t.text = std::string(text_.substr(i + 1, j - i - 1));
          i = j + 1;
          t.end = i;
          return t;
        }
      }
      return punct(starts("<=") ? 2 : 1);
    }
    if (c == '"' || c == '\'') return lex_string(i);
    if (c == '?' || c == '$') {
      size_t j = i + 1;
      while (j < text_.size() && is_var_char(static_cast<unsigned char>(text_[j]))) ++j;
      if (j == i + 1) {
        if (c == '$') lex_error(i, "'$' must start a variable name");
        return punct(1);
      }
      t.kind = Tok::Var;
      t.text = std::string(text_.substr(i + 1, j - i - 1));
      i = j;
      t.end = i;
      return t;
    }
    if (c == '@') {
      size_t j = i + 1;
      while (j < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[j])) || (text_[j] == '-' && j > i + 1)))
        ++j;
      if (j == i + 1 || !std::isalpha(static_cast<unsigned char>(text_[i + 1])))
        lex_error(i, "'@' must start a language tag");
      t.kind = Tok::LangTag;
      t.text = std::string(text_.substr(i + 1, j - i - 1));
      i = j;
      t.end = i;
      return t;
    }
    if (std::isdigit(c) || (c == '.' && i + 1 < text_.size() &&
                            std::isdigit(static_cast<unsigned char>(text_[i + 1])))) {
      size_t j = i;
      while (j < text_.size() && std::isdigit(static_cast<unsigned char>(text_[j]))) ++j;
      t.kind = Tok::Integer;
      if (j + 1 < text_.size() && text_[j] == '.' &&
          std::isdigit(static_cast<unsigned char>(text_[j + 1]))) {
        t.kind = Tok::Decimal;
        ++j;
        while (j < text_.size() && std::isdigit(static_cast<unsigned char>(text_[j]))) ++j;
      } else if (j + 1 < text_.size() && text_[j] == '.' &&
                 (text_[j + 1] == 'e' || text_[j + 1] == 'E')) {
        ++j;  // "1.e5"
        t.kind = Tok::Decimal;
      }
      if (j < text_.size() && (text_[j] == 'e' || text_[j] == 'E')) {
        size_t k = j + 1;
        if (k < text_.size() && (text_[k] == '+' || text_[k] == '-')) ++k;
        if (k < text_.size() && std::isdigit(static_cast<unsigned char>(text_[k]))) {
          while (k < text_.size() && std::isdigit(static_cast<unsigned char>(text_[k]))) ++k;
          j = k;
          t.kind = Tok::Double;
        } else {
          lex_error(j, "exponent without digits in a number");
        }
      }
      t.text = std::string(text_.substr(i, j - i));
      i = j;
      t.end = i;
      return t;
    }
    if (c == '_' && i + 1 < text_.size() && text_[i + 1] == ':') {
      size_t j = i + 2;
      std::string label = lex_local(j);
      if (label.empty()) lex_error(i, "blank node label expected after '_:'");
      t.kind = Tok::Blank;
      t.text = label;
      i = j;
      t.end = i;
      return t;
    }
    if (is_name_start(c) || c == ':') {
      size_t j = i;
      while (j < text_.size() &&
             (is_name_char(static_cast<unsigned char>(text_[j])) || text_[j] == '.'))
        ++j;
      while (j > i && text_[j - 1] == '.') --j;
      if (j < text_.size() && text_[j] == ':') {
        t.kind = Tok::PName;
        t.prefix = std::string(text_.substr(i, j - i));
        size_t k = j + 1;
        t.text = lex_local(k);
        i = k;
        t.end = i;
        return t;
      }
      // Keywords and function names are plain words.
      size_t k = i;
      while (k < text_.size() &&
             (std::isalnum(static_cast<unsigned char>(text_[k])) || text_[k] == '_'))
        ++k;
      if (k == i) lex_error(i, "unexpected character");
      t.kind = Tok::Word;
      t.text = std::string(text_.substr(i, k - i));
      i = k;
      t.end = i;
      return t;
    }
    for (std::string_view p : {"^^", "!=", ">=", "&&", "||"})
      if (starts(p)) return punct(2);
    if (std::string_view("{}()[].;,*/|^!?+-=><").find(static_cast<char>(c)) !=
        std::string_view::npos)
      return punct(1);
    // Unprintable bytes are named by code: a query may come from a file that is
    // not text, and a message must not carry its bytes to the terminal.
    if (c >= 0x20 && c < 0x7F) {
      lex_error(i, std::string("unexpected character '") + static_cast<char>(c) + "'");
    }
    char code[8];
    std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned>(c));
    lex_error(i, std::string("unexpected byte ") + code);
  }

  const Token& peek() {
    if (!have_) {
      size_t i = offset_;
      cur_ = lex(i, false);
      after_ = i;
      have_ = true;
    }
    return cur_;
  }
  // Peek where an operator is expected: '<' is less-than, never an IRI.
  const Token& peek_operator() {
    const Token& t = peek();
    if (t.kind == Tok::IriRef) {
      size_t i = t.begin;
      cur_ = lex(i, true);
      after_ = i;
    }
    return cur_;
  }
  Token next() {
    peek();
    have_ = false;
    offset_ = after_;
    return std::move(cur_);
  }
  // The token after the current one (one more of lookahead).
  Token peek2() {
    peek();
    size_t i = after_;
    return lex(i, false);
  }

  static bool is_punct(const Token& t, std::string_view p) {
    return t.kind == Tok::Punct && t.text == p;
  }
  static bool is_keyword(const Token& t, std::string_view kw) {
    if (t.kind != Tok::Word || t.text.size() != kw.size()) return false;
    for (size_t i = 0; i < kw.size(); ++i)
      if (std::toupper(static_cast<unsigned char>(t.text[i])) != kw[i]) return false;
    return true;
  }
  void expect_punct(std::string_view p, const std::string& context = {}) {
    if (!is_punct(peek(), p))
      expected(peek(), "'" + std::string(p) + "'" + (context.empty() ? "" : " " + context));
    next();
  }

  // ---- terms ----
  std::string resolve(std::string_view iri) const {
    if (base_.empty() || rdf::is_absolute_iri(iri)) return std::string(iri);
    return rdf::resolve_iri(base_, iri);
  }
  std::string expand(const Token& t) const {
    auto it = prefixes_local_.find(t.prefix);
    if (it != prefixes_local_.end()) return it->second + t.text;
    auto jt = prefixes_.find(t.prefix);
    if (jt != prefixes_.end()) return jt->second + t.text;
    fail(kSyntax, pos(t), "undeclared prefix '" + t.prefix + ":'");
  }
  bool at_iri() { return peek().kind == Tok::IriRef || peek().kind == Tok::PName; }
  std::string parse_iri() {
    Token t = next();
    if (t.kind == Tok::IriRef) return resolve(t.text);
    if (t.kind == Tok::PName) return expand(t);
    expected(t, "an IRI");
  }

  void parse_prologue() {
    for (;;) {
      const Token& t = peek();
      if (is_keyword(t, "BASE")) {
        next();
        if (peek().kind != Tok::IriRef) expected(peek(), "an IRI after BASE");
        base_ = resolve(next().text);
      } else if (is_keyword(t, "PREFIX")) {
        next();
        Token p = next();
        if (p.kind != Tok::PName || !p.text.empty())
          expected(p, "a prefix name like 'ex:' after PREFIX");
        if (peek().kind != Tok::IriRef) expected(peek(), "an IRI after PREFIX " + p.prefix + ":");
        prefixes_local_[p.prefix] = resolve(next().text);
      } else {
        return;
      }
    }
  }

  Term parse_var() {
    Token t = next();
    if (t.kind != Tok::Var) expected(t, "a variable");
    return Term{Term::Kind::Var, t.text, {}, {}, pos(t)};
  }

  // A literal (string with optional @lang / ^^datatype, number, boolean); the
  // current token is known to start one. `negative` applies a leading '-'.
  Term parse_literal(bool negative = false, bool positive = false) {
    Token t = next();
    Term term;
    term.kind = Term::Kind::Literal;
    term.pos = pos(t);
    const std::string sign = negative ? "-" : positive ? "+" : "";
    switch (t.kind) {
      case Tok::String:
        term.value = t.text;
        if (peek().kind == Tok::LangTag) {
          term.language = next().text;
        } else if (is_punct(peek(), "^^")) {
          next();
          if (!at_iri()) expected(peek(), "a datatype IRI after '^^'");
          term.datatype = parse_iri();
        }
        return term;
      case Tok::Integer:
        term.value = sign + t.text;
        term.datatype = std::string(kXsd) + "integer";
        return term;
      case Tok::Decimal:
        term.value = sign + t.text;
        term.datatype = std::string(kXsd) + "decimal";
        return term;
      case Tok::Double:
        term.value = sign + t.text;
        term.datatype = std::string(kXsd) + "double";
        return term;
      case Tok::Word:
        if (is_keyword(t, "TRUE") || is_keyword(t, "FALSE")) {
          term.value = is_keyword(t, "TRUE") ? "true" : "false";
          term.datatype = std::string(kXsd) + "boolean";
          return term;
        }
        break;
      default:
        break;
    }
    expected(t, "a literal");
  }

  bool at_literal() {
    const Token& t = peek();
    return t.kind == Tok::String || t.kind == Tok::Integer || t.kind == Tok::Decimal ||
           t.kind == Tok::Double || is_keyword(t, "TRUE") || is_keyword(t, "FALSE");
  }

  // VarOrTerm, or a blank node property list / collection (triples nodes).
  Node parse_node() {
    const Nested nested(*this);
    const Token& t = peek();
    Node n;
    n.pos = pos(t);
    if (t.kind == Tok::Var) {
      n.term = parse_var();
      return n;
    }
    if (t.kind == Tok::IriRef || t.kind == Tok::PName) {
      n.term = Term{Term::Kind::Iri, parse_iri(), {}, {}, n.pos};
      return n;
    }
    if (t.kind == Tok::Blank) {
      n.term = Term{Term::Kind::Blank, next().text, {}, {}, n.pos};
      return n;
    }
    if (is_punct(t, "[")) {
      next();
      n.term = Term{Term::Kind::Blank, "", {}, {}, n.pos};
      if (is_punct(peek(), "]")) {
        next();
        return n;
      }
      n.kind = Node::Kind::BlankPropertyList;
      n.properties = parse_property_list();
      if (!is_punct(peek(), "]"))
        expected(peek(), "']' to close the blank node started at line " +
                             std::to_string(n.pos.line) + ", column " +
                             std::to_string(n.pos.column));
      next();
      return n;
    }
    if (is_punct(t, "(")) {
      next();
      if (is_punct(peek(), ")")) {
        next();
        n.term = Term{Term::Kind::Nil, std::string(kRdf) + "nil", {}, {}, n.pos};
        return n;
      }
      n.kind = Node::Kind::Collection;
      while (!is_punct(peek(), ")")) {
        if (peek().kind == Tok::End || is_punct(peek(), "}") || is_punct(peek(), "."))
          expected(peek(), "')' to close the collection started at line " +
                               std::to_string(n.pos.line) + ", column " +
                               std::to_string(n.pos.column));
        n.members.push_back(parse_node());
      }
      next();
      return n;
    }
    if (is_punct(t, "-") || is_punct(t, "+")) {
      const bool neg = is_punct(t, "-");
      next();
      const Token& num = peek();
      if (num.kind != Tok::Integer && num.kind != Tok::Decimal && num.kind != Tok::Double)
        expected(num, "a number after the sign");
      n.term = parse_literal(neg, !neg);
      n.term.pos = n.pos;
      return n;
    }
    if (at_literal()) {
      n.term = parse_literal();
      return n;
    }
    expected(t, "a variable, IRI, literal, blank node or collection");
  }

  // ---- property paths ----
  bool at_verb() {
    const Token& t = peek();
    return t.kind == Tok::Var || t.kind == Tok::IriRef || t.kind == Tok::PName ||
           (t.kind == Tok::Word && t.text == "a") || is_punct(t, "^") || is_punct(t, "!") ||
           is_punct(t, "(");
  }
  Path parse_verb() {
    if (peek().kind == Tok::Var) {
      Term v = parse_var();
      return Path{Path::Kind::Var, v.value, {}, v.pos};
    }
    return parse_path_alternative();
  }
  Path parse_path_alternative() {
    const Nested nested(*this);
    Pos p = pos(peek());
    Path first = parse_path_sequence();
    if (!is_punct(peek(), "|")) return first;
    Path alt{Path::Kind::Alternative, {}, {}, p};
    alt.items.push_back(std::move(first));
    while (is_punct(peek(), "|")) {
      next();
      alt.items.push_back(parse_path_sequence());
    }
    return alt;
  }
  Path parse_path_sequence() {
    Pos p = pos(peek());
    Path first = parse_path_elt_or_inverse();
    if (!is_punct(peek(), "/")) return first;
    Path seq{Path::Kind::Sequence, {}, {}, p};
    seq.items.push_back(std::move(first));
    while (is_punct(peek(), "/")) {
      next();
      seq.items.push_back(parse_path_elt_or_inverse());
    }
    return seq;
  }
  Path parse_path_elt_or_inverse() {
    if (is_punct(peek(), "^")) {
      Pos p = pos(next());
      Path inv{Path::Kind::Inverse, {}, {}, p};
      inv.items.push_back(parse_path_elt());
      return inv;
    }
    return parse_path_elt();
  }
  Path parse_path_elt() {
    Path primary = parse_path_primary();
    const Token& t = peek();
    Path::Kind mod;
    if (is_punct(t, "*")) {
      mod = Path::Kind::ZeroOrMore;
    } else if (is_punct(t, "+")) {
      mod = Path::Kind::OneOrMore;
    } else if (is_punct(t, "?")) {
      mod = Path::Kind::ZeroOrOne;
    } else {
      return primary;
    }
    Path m{mod, {}, {}, pos(t)};
    next();
    m.items.push_back(std::move(primary));
    return m;
  }
  Path parse_path_one_in_set() {
    const Token& t = peek();
    Pos p = pos(t);
    if (is_punct(t, "^")) {
      next();
      Path inv{Path::Kind::Inverse, {}, {}, p};
      inv.items.push_back(parse_path_iri());
      return inv;
    }
    return parse_path_iri();
  }
  Path parse_path_iri() {
    const Token& t = peek();
    Pos p = pos(t);
    if (t.kind == Tok::Word && t.text == "a") {
      next();
      return Path{Path::Kind::Iri, std::string(kRdf) + "type", {}, p};
    }
    if (!at_iri()) expected(t, "an IRI or 'a' in the property path");
    return Path{Path::Kind::Iri, parse_iri(), {}, p};
  }
  Path parse_path_primary() {
    const Token& t = peek();
    Pos p = pos(t);
    if (is_punct(t, "!")) {
      next();
      Path neg{Path::Kind::Negated, {}, {}, p};
      if (is_punct(peek(), "(")) {
        next();
        if (!is_punct(peek(), ")")) {
          neg.items.push_back(parse_path_one_in_set());
          while (is_punct(peek(), "|")) {
            next();
            neg.items.push_back(parse_path_one_in_set());
          }
        }
        expect_punct(")", "to close the negated property set");
        if (neg.items.empty()) fail(kSyntax, p, "empty negated property set '!()'");
      } else {
        neg.items.push_back(parse_path_one_in_set());
      }
      return neg;
    }
    if (is_punct(t, "(")) {
      next();
      Path inner = parse_path_alternative();
      if (!is_punct(peek(), ")"))
        expected(peek(), "')' to close the path group started at line " + std::to_string(p.line) +
                             ", column " + std::to_string(p.column));
      next();
      return inner;
    }
    return parse_path_iri();
  }

  // PropertyListPathNotEmpty.
  std::vector<PropertyObjects> parse_property_list() {
    std::vector<PropertyObjects> out;
    for (;;) {
      if (!at_verb()) expected(peek(), "a predicate (IRI, 'a', variable or path)");
      PropertyObjects po;
      po.verb = parse_verb();
      po.objects.push_back(parse_node());
      while (is_punct(peek(), ",")) {
        next();
        po.objects.push_back(parse_node());
      }
      out.push_back(std::move(po));
      if (!is_punct(peek(), ";")) return out;
      while (is_punct(peek(), ";")) next();
      if (!at_verb()) return out;
    }
  }

  bool at_triples_start() {
    const Token& t = peek();
    return t.kind == Tok::Var || t.kind == Tok::IriRef || t.kind == Tok::PName ||
           t.kind == Tok::Blank || is_punct(t, "[") || is_punct(t, "(") || at_literal() ||
           ((is_punct(t, "-") || is_punct(t, "+")));
  }

  Triples parse_triples_same_subject() {
    Triples tr;
    tr.subject = parse_node();
    const bool bare_node = tr.subject.kind != Node::Kind::Term;
    if (bare_node && !at_verb()) return tr;  // "[ :p :o ] ." alone is allowed
    tr.properties = parse_property_list();
    return tr;
  }

  // ---- group graph patterns ----
  Group parse_group() {
    const Nested nested(*this);
    Token open = next();  // '{'
    Group g;
    g.pos = pos(open);
    if (is_keyword(peek(), "SELECT")) {
      // SPARQL 1.1 grammar [53]: a sub-SELECT is the whole of its group.
      Element e;
      e.kind = Element::Kind::SubSelect;
      e.pos = pos(peek());
      e.sub = std::make_shared<Query>();
      parse_select_clause(*e.sub);
      if (is_keyword(peek(), "WHERE")) next();
      if (!is_punct(peek(), "{")) expected(peek(), "'{' to start the sub-SELECT's WHERE clause");
      e.sub->where = parse_group();
      parse_modifiers(*e.sub);
      if (is_keyword(peek(), "VALUES")) unsupported(peek(), "VALUES is");
      if (!is_punct(peek(), "}"))
        expected(peek(), "'}' to close the group of the sub-SELECT at line " +
                             std::to_string(e.pos.line) + ", column " +
                             std::to_string(e.pos.column));
      next();
      g.elements.push_back(std::move(e));
      return g;
    }
    auto close_error = [&]() {
      expected(peek(), "'}' to close the group started at line " + std::to_string(g.pos.line) +
                           ", column " + std::to_string(g.pos.column));
    };
    for (;;) {
      const Token& t = peek();
      if (is_punct(t, "}")) {
        next();
        return g;
      }
      if (at_triples_start()) {
        Element e;
        e.kind = Element::Kind::Triples;
        e.pos = pos(t);
        for (;;) {
          e.triples.push_back(parse_triples_same_subject());
          if (!is_punct(peek(), ".")) break;
          next();
          if (!at_triples_start()) break;
        }
        g.elements.push_back(std::move(e));
        continue;
      }
      if (is_punct(t, "{")) {
        Element e;
        e.pos = pos(t);
        e.groups.push_back(parse_group());
        e.kind = Element::Kind::Group;
        while (is_keyword(peek(), "UNION")) {
          e.kind = Element::Kind::Union;
          next();
          if (!is_punct(peek(), "{")) expected(peek(), "'{' after UNION");
          e.groups.push_back(parse_group());
        }
        g.elements.push_back(std::move(e));
      } else if (is_keyword(t, "OPTIONAL")) {
        Element e;
        e.kind = Element::Kind::Optional;
        e.pos = pos(next());
        if (!is_punct(peek(), "{")) expected(peek(), "'{' after OPTIONAL");
        e.groups.push_back(parse_group());
        g.elements.push_back(std::move(e));
      } else if (is_keyword(t, "FILTER")) {
        Element e;
        e.kind = Element::Kind::Filter;
        e.pos = pos(next());
        e.expr = parse_constraint();
        g.elements.push_back(std::move(e));
      } else if (is_keyword(t, "BIND")) {
        Element e;
        e.kind = Element::Kind::Bind;
        e.pos = pos(next());
        expect_punct("(", "after BIND");
        e.expr = parse_expression();
        if (!is_keyword(peek(), "AS")) expected(peek(), "AS in BIND");
        next();
        if (peek().kind != Tok::Var) expected(peek(), "a variable after AS");
        e.var = parse_var();
        expect_punct(")", "to close BIND");
        g.elements.push_back(std::move(e));
      } else if (is_keyword(t, "MINUS")) {
        unsupported(t, "MINUS is");
      } else if (is_keyword(t, "SERVICE")) {
        unsupported(t, "SERVICE (federated query) is");
      } else if (is_keyword(t, "VALUES")) {
        unsupported(t, "VALUES is");
      } else if (is_keyword(t, "GRAPH")) {
        unsupported(t, "GRAPH is");
      } else if (is_keyword(t, "SELECT")) {
        expected(t, "'{' before the sub-SELECT (a sub-SELECT is a group of its own)");
      } else {
        close_error();
      }
      if (is_punct(peek(), ".")) next();
    }
  }

  // ---- expressions ----
  Expr parse_constraint() {
    const Token& t = peek();
    if (is_punct(t, "(")) return parse_bracketted();
    if (t.kind == Tok::Word) return parse_builtin();
    if (at_iri()) return parse_iri_or_function(true);
    expected(t, "'(' or a function call after FILTER");
  }
  Expr parse_bracketted() {
    Token open = next();
    Expr e = parse_expression();
    if (!is_punct(peek(), ")"))
      expected(peek(), "')' to close the expression started at line " +
                           std::to_string(pos(open).line) + ", column " +
                           std::to_string(pos(open).column));
    next();
    return e;
  }
  Expr parse_expression() {
    const Nested nested(*this);
    return parse_or();
  }
  Expr binary(Expr::Kind k, std::string name, Expr a, Expr b, Pos p) {
    Expr e;
    e.kind = k;
    e.name = std::move(name);
    e.pos = p;
    e.args.push_back(std::move(a));
    e.args.push_back(std::move(b));
    return e;
  }
  Expr parse_or() {
    Expr left = parse_and();
    while (is_punct(peek_operator(), "||")) {
      Pos p = pos(next());
      left = binary(Expr::Kind::Or, "||", std::move(left), parse_and(), p);
    }
    return left;
  }
  Expr parse_and() {
    Expr left = parse_relational();
    while (is_punct(peek_operator(), "&&")) {
      Pos p = pos(next());
      left = binary(Expr::Kind::And, "&&", std::move(left), parse_relational(), p);
    }
    return left;
  }
  Expr parse_relational() {
    Expr left = parse_additive();
    const Token& t = peek_operator();
    for (std::string_view op : {"=", "!=", "<", ">", "<=", ">="}) {
      if (is_punct(t, op)) {
        Pos p = pos(next());
        return binary(Expr::Kind::Compare, std::string(op), std::move(left), parse_additive(), p);
      }
    }
    bool negated = false;
    if (is_keyword(t, "NOT")) {
      Token tn = peek2();
      if (!is_keyword(tn, "IN")) return left;
      next();
      negated = true;
    }
    if (is_keyword(peek(), "IN")) {
      Expr e;
      e.kind = negated ? Expr::Kind::NotIn : Expr::Kind::In;
      e.pos = pos(next());
      e.args.push_back(std::move(left));
      expect_punct("(", "after IN");
      if (!is_punct(peek(), ")")) {
        e.args.push_back(parse_expression());
        while (is_punct(peek(), ",")) {
          next();
          e.args.push_back(parse_expression());
        }
      }
      expect_punct(")", "to close the IN list");
      return e;
    }
    return left;
  }
  Expr parse_additive() {
    Expr left = parse_multiplicative();
    for (;;) {
      const Token& t = peek_operator();
      if (is_punct(t, "+") || is_punct(t, "-")) {
        std::string op = t.text;
        Pos p = pos(next());
        left = binary(Expr::Kind::Arith, op, std::move(left), parse_multiplicative(), p);
      } else {
        return left;
      }
    }
  }
  Expr parse_multiplicative() {
    Expr left = parse_unary();
    for (;;) {
      const Token& t = peek_operator();
      if (is_punct(t, "*") || is_punct(t, "/")) {
        std::string op = t.text;
        Pos p = pos(next());
        left = binary(Expr::Kind::Arith, op, std::move(left), parse_unary(), p);
      } else {
        return left;
      }
    }
  }
  Expr parse_unary() {
    const Token& t = peek();
    Expr::Kind k;
    if (is_punct(t, "!")) {
      k = Expr::Kind::Not;
    } else if (is_punct(t, "-")) {
      k = Expr::Kind::Negate;
    } else if (is_punct(t, "+")) {
      k = Expr::Kind::Plus;
    } else {
      return parse_primary();
    }
    const Nested nested(*this);
    Expr e;
    e.kind = k;
    e.pos = pos(next());
    e.args.push_back(parse_unary());
    return e;
  }
  Expr parse_primary() {
    const Token& t = peek();
    Expr e;
    e.pos = pos(t);
    if (is_punct(t, "(")) return parse_bracketted();
    if (t.kind == Tok::Var) {
      e.term = parse_var();
      return e;
    }
    if (at_iri()) return parse_iri_or_function(false);
    if (at_literal()) {
      e.term = parse_literal();
      return e;
    }
    if (t.kind == Tok::Word) return parse_builtin();
    expected(t, "an expression");
  }
  std::vector<Expr> parse_arg_list(const std::string& fname) {
    std::vector<Expr> args;
    expect_punct("(", "after " + fname);
    if (is_keyword(peek(), "DISTINCT")) unsupported(peek(), "DISTINCT in a function call is");
    if (is_punct(peek(), ")")) {
      next();
      return args;
    }
    args.push_back(parse_expression());
    while (is_punct(peek(), ",")) {
      next();
      args.push_back(parse_expression());
    }
    if (!is_punct(peek(), ")")) expected(peek(), "',' or ')' in the arguments of " + fname);
    next();
    return args;
  }
  Expr parse_iri_or_function(bool must_call) {
    Pos p = pos(peek());
    Token t = peek();
    std::string iri = parse_iri();
    Expr e;
    e.pos = p;
    if (is_punct(peek(), "(")) {
      e.kind = Expr::Kind::Call;
      e.is_iri = true;
      e.name = iri;
      e.args = parse_arg_list("<" + iri + ">");
      return e;
    }
    if (must_call) expected(peek(), "'(' after the function IRI");
    e.term = Term{Term::Kind::Iri, iri, {}, {}, p};
    return e;
  }
  Expr parse_builtin() {
    Token t = next();
    Pos p = pos(t);
    const std::string name = upper(t.text);
    Expr e;
    e.pos = p;
    if (name == "NOT") {
      if (!is_keyword(peek(), "EXISTS")) expected(peek(), "EXISTS after NOT");
      next();
      e.kind = Expr::Kind::NotExists;
    } else if (name == "EXISTS") {
      e.kind = Expr::Kind::Exists;
    }
    if (e.kind == Expr::Kind::Exists || e.kind == Expr::Kind::NotExists) {
      if (!is_punct(peek(), "{")) expected(peek(), "'{' after EXISTS");
      e.pattern = std::make_shared<Group>(parse_group());
      return e;
    }
    if (name == "GROUP_CONCAT") return parse_group_concat(e);
    static const char* const kAggregates[] = {"COUNT", "SUM", "MIN", "MAX", "AVG", "SAMPLE"};
    for (const char* a : kAggregates)
      if (name == a) unsupported(t, "aggregate " + name + " is");
    if (name == "TRUE" || name == "FALSE") expected(t, "an expression");  // unreachable
    if (!is_punct(peek(), "(")) expected(peek(), "'(' after " + t.text);
    e.kind = Expr::Kind::Call;
    e.name = name;
    if (name == "BOUND") {
      next();
      if (peek().kind != Tok::Var) expected(peek(), "a variable in BOUND");
      Expr v;
      v.pos = pos(peek());
      v.term = parse_var();
      e.args.push_back(std::move(v));
      expect_punct(")", "to close BOUND");
      return e;
    }
    e.args = parse_arg_list(name);
    return e;
  }

  // GROUP_CONCAT '(' DISTINCT? Expression ( ';' SEPARATOR '=' String )? ')'
  // (grammar [127]); where it may stand is the algebra builder's concern.
  Expr parse_group_concat(Expr& e) {
    e.kind = Expr::Kind::Aggregate;
    e.name = "GROUP_CONCAT";
    expect_punct("(", "after GROUP_CONCAT");
    if (is_keyword(peek(), "DISTINCT")) {
      next();
      e.distinct = true;
    }
    e.args.push_back(parse_expression());
    if (is_punct(peek(), ";")) {
      next();
      if (!is_keyword(peek(), "SEPARATOR")) expected(peek(), "SEPARATOR after ';' in GROUP_CONCAT");
      next();
      expect_punct("=", "after SEPARATOR");
      if (peek().kind != Tok::String) expected(peek(), "a string after SEPARATOR =");
      e.separator = next().text;
    }
    expect_punct(")", "to close GROUP_CONCAT");
    return e;
  }

  // ---- SELECT clause and solution modifiers ----
  void parse_select_clause(Query& q) {
    next();  // SELECT
    if (is_keyword(peek(), "DISTINCT") || is_keyword(peek(), "REDUCED")) {
      next();
      q.distinct = true;
    }
    if (is_punct(peek(), "*")) {
      next();
      q.star = true;
      return;
    }
    for (;;) {
      const Token& t = peek();
      if (t.kind == Tok::Var) {
        Projection pr;
        pr.var = parse_var();
        q.projection.push_back(std::move(pr));
      } else if (is_punct(t, "(")) {
        Pos open = pos(next());
        Projection pr;
        pr.has_expr = true;
        pr.expr = parse_expression();
        if (!is_keyword(peek(), "AS")) expected(peek(), "AS in the SELECT expression");
        next();
        if (peek().kind != Tok::Var) expected(peek(), "a variable after AS");
        pr.var = parse_var();
        if (!is_punct(peek(), ")"))
          expected(peek(), "')' to close the SELECT expression started at line " +
                               std::to_string(open.line) + ", column " +
                               std::to_string(open.column));
        next();
        q.projection.push_back(std::move(pr));
      } else {
        break;
      }
    }
    if (q.projection.empty()) expected(peek(), "'*' or a variable after SELECT");
  }

  int64_t parse_count(const char* what) {
    Token t = next();
    if (t.kind != Tok::Integer) expected(t, std::string("an integer after ") + what);
    int64_t v = 0;
    auto [ptr, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec != std::errc()) fail(kSyntax, pos(t), std::string(what) + " value is too large");
    return v;
  }

  void parse_modifiers(Query& q) {
    if (is_keyword(peek(), "GROUP")) {
      q.group_pos = pos(next());
      if (!is_keyword(peek(), "BY")) expected(peek(), "BY after GROUP");
      next();
      while (peek().kind == Tok::Var) q.group_by.push_back(parse_var());
      if (q.group_by.empty()) {
        if (is_punct(peek(), "(") || peek().kind == Tok::Word || at_iri())
          unsupported(peek(), "GROUP BY an expression is (group by variables)");
        expected(peek(), "a variable after GROUP BY");
      }
    }
    if (is_keyword(peek(), "HAVING")) unsupported(peek(), "HAVING is");
    if (is_keyword(peek(), "ORDER")) {
      next();
      if (!is_keyword(peek(), "BY")) expected(peek(), "BY after ORDER");
      next();
      for (;;) {
        const Token& t = peek();
        OrderKey key;
        if (is_keyword(t, "ASC") || is_keyword(t, "DESC")) {
          key.descending = is_keyword(t, "DESC");
          next();
          if (!is_punct(peek(), "(")) expected(peek(), "'(' after ASC/DESC");
          key.expr = parse_bracketted();
        } else if (t.kind == Tok::Var) {
          key.expr.pos = pos(t);
          key.expr.term = parse_var();
        } else if (is_punct(t, "(") ||
                   (t.kind == Tok::Word && !is_keyword(t, "LIMIT") && !is_keyword(t, "OFFSET") &&
                    !is_keyword(t, "VALUES")) ||
                   at_iri()) {
          key.expr = parse_constraint();
        } else {
          break;
        }
        q.order.push_back(std::move(key));
      }
      if (q.order.empty()) expected(peek(), "an ordering condition after ORDER BY");
    }
    for (int k = 0; k < 2; ++k) {
      if (is_keyword(peek(), "LIMIT") && q.limit < 0) {
        next();
        q.limit = parse_count("LIMIT");
      } else if (is_keyword(peek(), "OFFSET")) {
        next();
        q.offset = parse_count("OFFSET");
      }
    }
  }

  std::string_view text_;
  const PrefixMap& prefixes_;
  std::map<std::string, std::string, std::less<>> prefixes_local_;
  std::string base_;
  std::vector<size_t> line_starts_;
  size_t offset_ = 0;
  size_t after_ = 0;
  bool have_ = false;
  Token cur_;
};

}  // namespace

Query parse(std::string_view text, const PrefixMap& prefixes, std::string_view base_iri) {
  return Parser(text, prefixes, base_iri).parse_query();
}

}  // namespace ast
}  // namespace mospec::sparql
