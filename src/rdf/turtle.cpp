#include "rdf/turtle.hpp"

#include <serd/serd.h>

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>

#include "rdf/iri.hpp"
#include "support/utf8.hpp"

namespace mospec::rdf {

namespace {

std::string_view view(const SerdNode* node) {
  return {reinterpret_cast<const char*>(node->buf), node->n_bytes};
}

bool is_alpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_alnum(char c) {
  return is_alpha(c) || (c >= '0' && c <= '9');
}

// Turtle's LANGTAG: [a-zA-Z]+ ('-' [a-zA-Z0-9]+)*
bool valid_language_tag(std::string_view tag) {
  size_t i = 0;
  while (i < tag.size() && is_alpha(tag[i])) ++i;
  if (i == 0) return false;
  while (i < tag.size()) {
    if (tag[i++] != '-') return false;
    const size_t start = i;
    while (i < tag.size() && is_alnum(tag[i])) ++i;
    if (i == start) return false;
  }
  return true;
}

// State shared with serd's C callbacks. Exceptions must not cross serd's C
// frames, so callbacks record the first error and return a failure status;
// the caller throws once serd has returned.
class TurtleReader {
 public:
  TurtleReader(std::string_view text, std::string_view base, Dataset& into, uint32_t file_id,
               std::string_view file_name)
      : text_(text),
        base_(std::string(base)),
        data_(into),
        file_id_(file_id),
        file_name_(file_name) {}

  void run(SerdSyntax syntax) {
    std::unique_ptr<SerdReader, decltype(&serd_reader_free)> reader(
        serd_reader_new(syntax, this, nullptr, &on_base, &on_prefix, &on_statement, nullptr),
        &serd_reader_free);
    serd_reader_set_strict(reader.get(), true);
    serd_reader_set_error_sink(reader.get(), &on_error, this);
    const std::string prefix = data_.terms().fresh_blank_prefix();
    serd_reader_add_blank_prefix(reader.get(), reinterpret_cast<const uint8_t*>(prefix.c_str()));
    const std::string name(file_name_);
    // One byte per read so that the bytes handed out mark serd's cursor,
    // which is how statements get their locations.
    const SerdStatus status =
        serd_reader_read_source(reader.get(), &source, &source_error, this,
                                reinterpret_cast<const uint8_t*>(name.c_str()), 1);
    if (error_) throw *error_;
    if (status > SERD_FAILURE)
      throw Error("syntax",
                  std::string("Turtle reader failed: ") +
                      reinterpret_cast<const char*>(serd_strerror(status)),
                  std::string(file_name_), line_, column());
  }

 private:
  uint32_t column() const { return static_cast<uint32_t>(offset_ - line_start_); }

  void record(std::string message, uint32_t line, uint32_t col) {
    if (!error_)
      error_.emplace(DiagnosticCode("syntax"), std::move(message), std::string(file_name_), line,
                     col);
  }

  static size_t source(void* buf, size_t size, size_t nmemb, void* stream) {
    auto* self = static_cast<TurtleReader*>(stream);
    const size_t want = size * nmemb;
    const size_t n = std::min(want, self->text_.size() - self->offset_);
    if (n == 1) {  // the page size run() asks for: one byte per call
      const char c = self->text_[self->offset_++];
      *static_cast<char*>(buf) = c;
      if (c == '\n') {
        ++self->line_;
        self->line_start_ = self->offset_;
      }
      return 1;
    }
    std::memcpy(buf, self->text_.data() + self->offset_, n);
    for (size_t i = 0; i < n; ++i) {
      if (self->text_[self->offset_ + i] == '\n') {
        ++self->line_;
        self->line_start_ = self->offset_ + i + 1;
      }
    }
    self->offset_ += n;
    return n;
  }
  static int source_error(void*) { return 0; }

  static SerdStatus on_error(void* handle, const SerdError* error) {
    auto* self = static_cast<TurtleReader*>(handle);
    char buf[512];
    va_list args;
    va_copy(args, *error->args);
    std::vsnprintf(buf, sizeof buf, error->fmt, args);
    va_end(args);
    std::string message(buf);
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    self->record(std::move(message), error->line, error->col);
    return SERD_SUCCESS;
  }

  static SerdStatus on_base(void* handle, const SerdNode* uri) {
    auto* self = static_cast<TurtleReader*>(handle);
    self->base_ = IriBase(self->base_.iri().empty() ? std::string(view(uri))
                                                    : self->base_.resolve(view(uri)));
    return SERD_SUCCESS;
  }

  static SerdStatus on_prefix(void* handle, const SerdNode* name, const SerdNode* uri) {
    auto* self = static_cast<TurtleReader*>(handle);
    // Kept unresolved-if-impossible: a relative namespace is only an error if used.
    self->prefixes_[std::string(view(name))] =
        is_absolute_iri(view(uri)) || self->base_.iri().empty() ? std::string(view(uri))
                                                                : self->base_.resolve(view(uri));
    return SERD_SUCCESS;
  }

  // The absolute IRI a URI or CURIE node denotes; records an error otherwise.
  std::optional<std::string> expand(const SerdNode* node) {
    std::string iri;
    if (node->type == SERD_CURIE) {
      const std::string_view curie = view(node);
      const size_t colon = curie.find(':');
      auto it = prefixes_.find(std::string(curie.substr(0, colon)));
      if (colon == std::string_view::npos || it == prefixes_.end()) {
        record("undefined prefix '" + std::string(curie.substr(0, colon)) + ":' in " +
                   std::string(curie),
               line_, column());
        return std::nullopt;
      }
      iri = it->second;
      iri.append(curie.substr(colon + 1));
    } else {
      const std::string_view ref = view(node);
      iri = is_absolute_iri(ref) || base_.iri().empty() ? std::string(ref) : base_.resolve(ref);
    }
    if (!is_absolute_iri(iri)) {
      record("relative IRI <" + iri + "> and no base IRI to resolve it against", line_, column());
      return std::nullopt;
    }
    return iri;
  }

  std::optional<TermId> term(const SerdNode* node, const SerdNode* datatype = nullptr,
                             const SerdNode* language = nullptr) {
    TermTable& terms = data_.terms();
    // serd 0.30 turns a \u or \U escape of a surrogate (\uDDDD) or of a code
    // point past U+10FFFF into bytes that are not UTF-8; RDF terms are
    // Unicode strings, and N-Quads could not write one back.
    for (const SerdNode* n : {node, datatype, language}) {
      if (n != nullptr && find_invalid_utf8(view(n)) != std::string_view::npos) {
        record(
            "a \\u or \\U escape names a code point that is not a Unicode character (a "
            "surrogate, U+D800 to U+DFFF, or one past U+10FFFF)",
            line_, column());
        return std::nullopt;
      }
    }
    switch (node->type) {
      case SERD_URI:
      case SERD_CURIE: {
        auto iri = expand(node);
        if (!iri) return std::nullopt;
        return terms.iri(*iri);
      }
      case SERD_BLANK:
        // serd 0.30 takes a '.' at the very end of the input into the label
        // ("_:b." with nothing after it); Turtle's labels never end in '.',
        // and N-Quads could not write one back.
        if (view(node).ends_with('.')) {
          record(
              "a blank node label ends with '.' (a label may not; end the statement with "
              "' .')",
              line_, column());
          return std::nullopt;
        }
        return terms.blank(view(node));
      case SERD_LITERAL: {
        if (datatype != nullptr && datatype->type != SERD_NOTHING) {
          auto iri = expand(datatype);
          if (!iri) return std::nullopt;
          return terms.literal(view(node), terms.iri(*iri));
        }
        if (language != nullptr && language->type != SERD_NOTHING) {
          // serd 0.30 accepts tags such as "en--"; N-Quads could not express them.
          if (!valid_language_tag(view(language))) {
            record("invalid language tag '" + std::string(view(language)) + "'", line_, column());
            return std::nullopt;
          }
          return terms.literal(view(node), TermId::default_graph(), view(language));
        }
        return terms.literal(view(node));
      }
      case SERD_NOTHING:
        break;
    }
    record("unexpected empty node from serd", line_, column());
    return std::nullopt;
  }

  static SerdStatus on_statement(void* handle, SerdStatementFlags, const SerdNode* graph,
                                 const SerdNode* subject, const SerdNode* predicate,
                                 const SerdNode* object, const SerdNode* object_datatype,
                                 const SerdNode* object_lang) {
    auto* self = static_cast<TurtleReader*>(handle);
    if (self->error_) return SERD_ERR_BAD_SYNTAX;
    const SourceLoc where{self->file_id_, self->line_, self->column()};
    auto s = self->term(subject);
    auto p = self->term(predicate);
    auto o = self->term(object, object_datatype, object_lang);
    std::optional<TermId> g = TermId::default_graph();
    if (graph != nullptr && graph->type != SERD_NOTHING) g = self->term(graph);
    if (!s || !p || !o || !g) return SERD_ERR_BAD_SYNTAX;
    self->data_.add(Quad{*s, *p, *o, *g}, where);
    return SERD_SUCCESS;
  }

  std::string_view text_;
  size_t offset_ = 0;  // bytes handed to serd so far
  uint32_t line_ = 1;
  size_t line_start_ = 0;
  IriBase base_;  // prepared: documents resolve many references against it
  std::unordered_map<std::string, std::string> prefixes_;
  Dataset& data_;
  uint32_t file_id_;
  std::string_view file_name_;
  std::optional<Error> error_;
};

// Turtle and TriG documents are UTF-8; serd passes ill-formed bytes through
// into literals, so the whole text is checked first.
void require_utf8(std::string_view text, std::string_view file_name) {
  const size_t bad = find_invalid_utf8(text);
  if (bad == std::string_view::npos) return;
  uint32_t line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < bad; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  static constexpr char kHex[] = "0123456789ABCDEF";
  const auto byte = static_cast<unsigned char>(text[bad]);
  std::string message = "invalid UTF-8 byte 0x";
  message += kHex[byte >> 4];
  message += kHex[byte & 0xF];
  throw Error("syntax", std::move(message), std::string(file_name), line,
              static_cast<uint32_t>(bad - line_start + 1));
}

// serd reads blank node property lists `[ ... ]` and collections `( ... )` by
// recursion, so a document nested thousands deep exhausts the stack. The same
// limit as for JSON (deep enough for any real document) is enforced here, before
// serd sees the text, by counting brackets outside the tokens that may contain
// them: comments, IRIs, short and long strings, and backslash escapes (which in
// prefixed names may escape a quote or '#'). Where this scan and serd's grammar
// disagree (only in a document serd rejects anyway), the scan can only count
// more brackets, never fewer.
constexpr int kMaxNesting = 512;

void require_bounded_nesting(std::string_view text, std::string_view file_name) {
  uint32_t line = 1;
  size_t line_start = 0;
  int depth = 0;
  const size_t n = text.size();
  auto newline_at = [&](size_t i) {
    ++line;
    line_start = i + 1;
  };
  size_t i = 0;
  while (i < n) {
    const char c = text[i];
    switch (c) {
      case '\n':
        newline_at(i);
        ++i;
        break;
      case '#':  // a comment runs to the end of the line
        while (i < n && text[i] != '\n') ++i;
        break;
      case '\\':  // an escape in a prefixed name: the next byte is not syntax
        i += 2;
        break;
      case '<':  // IRIREF: ends at '>' or at any byte an IRI cannot contain
        ++i;
        while (i < n) {
          const auto u = static_cast<unsigned char>(text[i]);
          if (u <= 0x20 || text[i] == '<' || text[i] == '"' || text[i] == '{' || text[i] == '}' ||
              text[i] == '|' || text[i] == '^' || text[i] == '`') {
            break;
          }
          ++i;
          if (text[i - 1] == '>') break;
        }
        break;
      case '"':
      case '\'': {
        const bool long_string = i + 2 < n && text[i + 1] == c && text[i + 2] == c;
        i += long_string ? 3 : 1;
        while (i < n) {
          if (text[i] == '\\') {
            i += 2;
            continue;
          }
          if (text[i] == '\n') {
            newline_at(i);
            ++i;
            if (!long_string) break;  // a short string cannot span lines
            continue;
          }
          if (text[i] == c) {
            if (!long_string) {
              ++i;
              break;
            }
            if (i + 2 < n && text[i + 1] == c && text[i + 2] == c) {
              i += 3;
              break;
            }
          }
          ++i;
        }
        break;
      }
      case '[':
      case '(':
        if (++depth > kMaxNesting) {
          throw Error("syntax",
                      std::string("blank nodes '[' and collections '(' nested deeper than ") +
                          std::to_string(kMaxNesting) +
                          " levels; flatten the data with named or labelled nodes (_:b)",
                      std::string(file_name), line, static_cast<uint32_t>(i - line_start + 1));
        }
        ++i;
        break;
      case ']':
      case ')':
        if (depth > 0) --depth;
        ++i;
        break;
      default:
        ++i;
    }
  }
}

}  // namespace

void read_turtle(std::string_view text, std::string_view base_iri, Dataset& into, uint32_t file_id,
                 std::string_view file_name) {
  require_utf8(text, file_name);
  require_bounded_nesting(text, file_name);
  TurtleReader(text, base_iri, into, file_id, file_name).run(SERD_TURTLE);
}

void read_trig(std::string_view text, std::string_view base_iri, Dataset& into, uint32_t file_id,
               std::string_view file_name) {
  require_utf8(text, file_name);
  require_bounded_nesting(text, file_name);
  TurtleReader(text, base_iri, into, file_id, file_name).run(SERD_TRIG);
}

}  // namespace mospec::rdf
