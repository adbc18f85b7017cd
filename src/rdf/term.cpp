#include "rdf/term.hpp"

#include <charconv>
#include <cstring>
#include <functional>

#include "rdf/iri.hpp"

namespace mospec::rdf {

namespace {

constexpr size_t kBlockSize = 64 * 1024;

using detail::hash_text;

// value_hash: hash_text(t.value).
uint64_t hash_term(const Term& t, uint64_t value_hash) {
  uint64_t h = detail::mix64(static_cast<uint64_t>(t.kind));
  h = detail::combine(h, value_hash);
  if (t.kind == TermKind::Literal) {
    h = detail::combine(h, t.datatype.index);
    if (!t.language.empty()) h = detail::combine(h, hash_text(t.language));
    if (!t.direction.empty()) h = detail::combine(h, hash_text(t.direction));
  }
  return h;
}

uint64_t hash_term(const Term& t) {
  return hash_term(t, hash_text(t.value));
}

bool same_term(const Term& a, const Term& b) {
  return a.kind == b.kind && a.value == b.value && a.datatype == b.datatype &&
         a.language == b.language && a.direction == b.direction;
}

}  // namespace

TermTable::TermTable() {
  terms_.push_back(Term{});  // the default graph owns index 0
  index_.insert(hash_term(terms_[0]), 0);
  // Fixed ids 1..3 (see xsd_string() etc.), interned in this order.
  iri(kXsdString);
  iri(kRdfLangString);
  iri(kRdfDirLangString);
}

std::string_view TermTable::store(std::string_view text) {
  if (text.empty()) return {};
  if (text.size() > kBlockSize / 4) {
    // Large strings get their own block so they do not waste a shared one.
    auto block = std::make_unique_for_overwrite<char[]>(text.size());
    std::memcpy(block.get(), text.data(), text.size());
    std::string_view view(block.get(), text.size());
    // Keep the current shared block last so later small strings keep using it.
    blocks_.insert(blocks_.empty() ? blocks_.end() : blocks_.end() - 1, std::move(block));
    text_bytes_ += text.size();
    return view;
  }
  if (blocks_.empty() || block_used_ + text.size() > block_size_) {
    blocks_.push_back(std::make_unique_for_overwrite<char[]>(kBlockSize));
    block_used_ = 0;
    block_size_ = kBlockSize;
    text_bytes_ += kBlockSize;
  }
  char* dst = blocks_.back().get() + block_used_;
  std::memcpy(dst, text.data(), text.size());
  block_used_ += text.size();
  return {dst, text.size()};
}

TermId TermTable::lookup(const Term& t, uint64_t hash) const {
  uint32_t found = index_.find(hash, [&](uint32_t id) { return same_term(terms_[id], t); });
  return found == detail::IdHashSet::kNone ? TermId::any() : TermId{found};
}

TermId TermTable::intern(const Term& t) {
  const uint64_t hash = hash_term(t);
  if (TermId existing = lookup(t, hash); !existing.is_any()) return existing;
  return insert(t, hash);
}

TermId TermTable::insert(const Term& t, uint64_t hash) {
  Term stored = t;
  stored.value = store(t.value);
  stored.language = store(t.language);
  // Directions are one of two constants; no need to copy them.
  if (t.direction == "ltr") {
    stored.direction = "ltr";
  } else if (t.direction == "rtl") {
    stored.direction = "rtl";
  } else {
    stored.direction = store(t.direction);
  }
  const auto id = static_cast<uint32_t>(terms_.size());
  terms_.push_back(stored);
  index_.insert(hash, id);
  if (stored.kind == TermKind::Blank) {
    if (size_t cut = stored.value.find('_'); cut != std::string_view::npos)
      blank_stems_.insert(stored.value.substr(0, cut + 1));
  }
  return TermId{id};
}

TermId TermTable::iri(std::string_view iri) {
  return intern(Term{TermKind::Iri, iri, {}, {}, {}});
}

TermId TermTable::well_formed_iri(std::string_view iri) {
  return well_formed_iri(iri, hash_text(iri));
}

TermId TermTable::well_formed_iri(std::string_view iri, uint64_t text_hash) {
  const Term key{TermKind::Iri, iri, {}, {}, {}};
  const uint64_t hash = hash_term(key, text_hash);
  TermId id = lookup(key, hash);
  if (!id.is_any() && id.index < well_formed_.size() && well_formed_[id.index]) return id;
  if (!is_well_formed_iri(iri)) return TermId::any();
  if (id.is_any()) id = insert(key, hash);
  if (id.index >= well_formed_.size()) well_formed_.resize(terms_.size());
  well_formed_[id.index] = true;
  return id;
}

TermId TermTable::blank(std::string_view label) {
  return intern(Term{TermKind::Blank, label, {}, {}, {}});
}

TermId TermTable::fresh_blank() {
  for (;;) {
    char label[24] = {'b'};
    const char* end = std::to_chars(label + 1, label + sizeof label, next_fresh_++).ptr;
    const Term key{TermKind::Blank, std::string_view(label, end - label), {}, {}, {}};
    const uint64_t hash = hash_term(key);
    if (lookup(key, hash).is_any()) return insert(key, hash);
  }
}

std::string TermTable::fresh_blank_prefix() {
  for (;;) {
    std::string prefix(1, 'r');
    prefix += std::to_string(next_prefix_++);
    prefix += '_';
    // "rN" has no '_', so any label starting with the prefix has it as its stem.
    if (!blank_stems_.contains(prefix)) {
      // Reserve it even if the document turns out to have no blank nodes.
      blank_stems_.insert(store(prefix));
      return prefix;
    }
  }
}

Term TermTable::literal_key(std::string_view lexical, TermId datatype, std::string_view language,
                            std::string_view direction) const {
  if (datatype == TermId::default_graph()) {
    if (language.empty()) {
      datatype = xsd_string();
    } else {
      datatype = direction.empty() ? rdf_lang_string() : rdf_dir_lang_string();
    }
  }
  return Term{TermKind::Literal, lexical, datatype, language, direction};
}

TermId TermTable::literal(std::string_view lexical, TermId datatype, std::string_view language,
                          std::string_view direction) {
  return intern(literal_key(lexical, datatype, language, direction));
}

TermId TermTable::literal(std::string_view lexical, std::string_view datatype_iri) {
  return literal(lexical, iri(datatype_iri));
}

TermId TermTable::find_iri(std::string_view iri) const {
  Term key{TermKind::Iri, iri, {}, {}, {}};
  return lookup(key, hash_term(key));
}

TermId TermTable::find_blank(std::string_view label) const {
  Term key{TermKind::Blank, label, {}, {}, {}};
  return lookup(key, hash_term(key));
}

TermId TermTable::find_literal(std::string_view lexical, TermId datatype, std::string_view language,
                               std::string_view direction) const {
  Term key = literal_key(lexical, datatype, language, direction);
  return lookup(key, hash_term(key));
}

TermId TermTable::find_equivalent(const TermTable& other, TermId id) const {
  if (id.is_any()) return id;
  const Term& t = other[id];
  switch (t.kind) {
    case TermKind::DefaultGraph:
      return TermId::default_graph();
    case TermKind::Iri:
      return find_iri(t.value);
    case TermKind::Blank:
      return find_blank(t.value);
    case TermKind::Literal: {
      TermId dt = find_iri(other[t.datatype].value);
      if (dt.is_any()) return dt;
      Term key{TermKind::Literal, t.value, dt, t.language, t.direction};
      return lookup(key, hash_term(key));
    }
  }
  return TermId::any();
}

TermId TermTable::import(const TermTable& other, TermId id) {
  const Term& t = other[id];
  switch (t.kind) {
    case TermKind::DefaultGraph:
      return TermId::default_graph();
    case TermKind::Iri:
      return iri(t.value);
    case TermKind::Blank:
      return blank(t.value);
    case TermKind::Literal: {
      TermId dt = iri(other[t.datatype].value);
      return intern(Term{TermKind::Literal, t.value, dt, t.language, t.direction});
    }
  }
  return TermId::any();
}

size_t TermTable::memory_bytes() const {
  return text_bytes_ + terms_.capacity() * sizeof(Term) + index_.memory_bytes() +
         well_formed_.capacity() / 8 +
         blank_stems_.size() * (sizeof(std::string_view) + 2 * sizeof(void*)) +
         blocks_.capacity() * sizeof(void*);
}

namespace {

void append_hex4(std::string& out, unsigned c) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  out += "\\u";
  for (int shift = 12; shift >= 0; shift -= 4) out += kHex[(c >> shift) & 0xF];
}

}  // namespace

// Canonical literal escaping (see nquads.hpp): ECHAR for the four characters
// that may not appear raw, UCHAR for the remaining control characters.
void append_escaped_literal(std::string& out, std::string_view s) {
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (c < 0x20 || c == 0x7F) {
          append_hex4(out, c);
        } else {
          out += ch;
        }
    }
  }
}

void append_ntriples(std::string& out, const TermTable& table, TermId id) {
  const Term& t = table[id];
  switch (t.kind) {
    case TermKind::DefaultGraph:
      return;
    case TermKind::Iri:
      out += '<';
      out += t.value;
      out += '>';
      return;
    case TermKind::Blank:
      out += "_:";
      out += t.value;
      return;
    case TermKind::Literal:
      out += '"';
      append_escaped_literal(out, t.value);
      out += '"';
      if (t.datatype == TermTable::rdf_dir_lang_string() && !t.language.empty() &&
          !t.direction.empty()) {
        out += '@';
        out += t.language;
        out += "--";
        out += t.direction;
      } else if (t.datatype == TermTable::rdf_lang_string() && !t.language.empty() &&
                 t.direction.empty()) {
        out += '@';
        out += t.language;
      } else if (t.datatype != TermTable::xsd_string()) {
        out += "^^<";
        out += table[t.datatype].value;
        out += '>';
      }
      return;
  }
}

std::string to_ntriples(const TermTable& table, TermId id) {
  std::string out;
  append_ntriples(out, table, id);
  return out;
}

}  // namespace mospec::rdf
