#include "json/json.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <system_error>
#include <utility>

#include "support/utf8.hpp"

namespace mospec::json {

namespace detail {

// Positions of an object's members by key: the duplicate-key check of the
// parser and Object's own lookups cost O(1) per member instead of a scan of
// the members (quadratic: an object with 100k keys took minutes). Small
// objects, the common case, are scanned; past kScanLimit members an
// open-addressing table of member indices takes over. The table stores indices
// rather than views of the keys because the members' vector reallocates.
class KeyIndex {
 public:
  explicit KeyIndex(Resource* resource = std::pmr::get_default_resource()) : slots_(resource) {}
  // A copy on the heap, as every copy (json.hpp).
  KeyIndex(const KeyIndex& o) : slots_(o.slots_.begin(), o.slots_.end()), used_(o.used_) {}
  KeyIndex(KeyIndex&&) noexcept = default;
  KeyIndex& operator=(const KeyIndex&) = delete;
  KeyIndex& operator=(KeyIndex&&) = delete;

  static constexpr size_t kScanLimit = 16;
  static constexpr size_t kNone = std::numeric_limits<size_t>::max();

  void clear() {
    slots_.clear();
    used_ = 0;
  }
  // clear(), also giving back a table grown past `keep` slots.
  void clear_keeping(size_t keep) {
    clear();
    if (slots_.capacity() > keep) std::pmr::vector<uint32_t>(slots_.get_allocator()).swap(slots_);
  }

  // The position of `key` in `members`, or kNone.
  size_t find(std::span<const Object::Member> members, std::string_view key) const {
    if (slots_.empty()) {
      for (size_t i = 0; i < members.size(); ++i) {
        if (members[i].key == key) return i;
      }
      return kNone;
    }
    const size_t mask = slots_.size() - 1;
    for (size_t s = hash(key) & mask;; s = (s + 1) & mask) {
      const uint32_t slot = slots_[s];
      if (slot == kEmpty) return kNone;
      if (members[slot].key == key) return slot;
    }
  }

  // Records members.back(), which find() did not find.
  void added(std::span<const Object::Member> members) {
    if (slots_.empty()) {
      if (members.size() > kScanLimit) rebuild(members);
      return;
    }
    if (2 * (used_ + 1) > slots_.size()) {
      rebuild(members);
      return;
    }
    insert(members.back().key, static_cast<uint32_t>(members.size() - 1));
  }

  // Indexes `members` afresh (after an erase or a bulk append).
  void rebuild(std::span<const Object::Member> members) {
    clear();
    if (members.size() <= kScanLimit) return;
    size_t capacity = 64;
    while (capacity < 4 * members.size()) capacity *= 2;
    slots_.assign(capacity, kEmpty);
    for (size_t i = 0; i < members.size(); ++i) {
      insert(members[i].key, static_cast<uint32_t>(i));
    }
  }

 private:
  static constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();
  std::pmr::vector<uint32_t> slots_;
  size_t used_ = 0;

  static size_t hash(std::string_view key) { return std::hash<std::string_view>{}(key); }

  void insert(std::string_view key, uint32_t index) {
    const size_t mask = slots_.size() - 1;
    size_t s = hash(key) & mask;
    while (slots_[s] != kEmpty) s = (s + 1) & mask;
    slots_[s] = index;
    ++used_;
  }
};

}  // namespace detail

using detail::KeyIndex;

// ---------------------------------------------------------------------------
// Object

Object::IndexPtr::IndexPtr() noexcept = default;
Object::IndexPtr::IndexPtr(const IndexPtr& o) {
  if (o.p != nullptr) {
    resource_ = std::pmr::get_default_resource();
    p = new (resource_->allocate(sizeof(KeyIndex), alignof(KeyIndex))) KeyIndex(*o.p);
  }
}
Object::IndexPtr& Object::IndexPtr::operator=(const IndexPtr& o) {
  if (this != &o) {
    IndexPtr copy(o);
    *this = std::move(copy);
  }
  return *this;
}
Object::IndexPtr::IndexPtr(IndexPtr&& o) noexcept
    : p(std::exchange(o.p, nullptr)), resource_(std::exchange(o.resource_, nullptr)) {}
Object::IndexPtr& Object::IndexPtr::operator=(IndexPtr&& o) noexcept {
  if (this != &o) {
    reset();
    p = std::exchange(o.p, nullptr);
    resource_ = std::exchange(o.resource_, nullptr);
  }
  return *this;
}
Object::IndexPtr::~IndexPtr() {
  reset();
}

void Object::IndexPtr::create(Resource* resource) {
  reset();
  resource_ = resource;
  p = new (resource->allocate(sizeof(KeyIndex), alignof(KeyIndex))) KeyIndex(resource);
}

void Object::IndexPtr::reset() noexcept {
  if (p == nullptr) return;
  p->~KeyIndex();
  resource_->deallocate(p, sizeof(KeyIndex), alignof(KeyIndex));
  p = nullptr;
  resource_ = nullptr;
}

Object& Object::operator=(const Object& o) {
  if (this != &o) {
    members_ = o.members_;
    index_.reset();
    reindex();
  }
  return *this;
}

Object& Object::operator=(Object&& o) noexcept {
  if (this != &o) {
    const bool same_resource = resource() == o.resource();
    members_ = std::move(o.members_);
    if (same_resource) {
      index_ = std::move(o.index_);
    } else {
      o.index_.reset();
      index_.reset();
      reindex();
    }
  }
  return *this;
}

void Object::reindex() {
  if (members_.size() <= KeyIndex::kScanLimit) {
    index_.reset();
    return;
  }
  if (!index_.p) index_.create(resource());
  index_.p->rebuild(members_);
}

size_t Object::index_of(std::string_view key) const {
  if (index_.p) {
    const size_t i = index_.p->find(members_, key);
    return i == KeyIndex::kNone ? std::string::npos : i;
  }
  for (size_t i = 0; i < members_.size(); ++i) {
    if (members_[i].key == key) return i;
  }
  return std::string::npos;
}

const Value* Object::find(std::string_view key) const {
  if (index_.p) {
    const size_t i = index_.p->find(members_, key);
    return i == KeyIndex::kNone ? nullptr : &members_[i].value;
  }
  for (const Member& m : members_) {
    if (m.key == key) return &m.value;
  }
  return nullptr;
}

Value* Object::find(std::string_view key) {
  return const_cast<Value*>(static_cast<const Object&>(*this).find(key));
}

Value& Object::set(std::string_view key, Value v) {
  if (Value* slot = find(key)) {
    *slot = std::move(v);
    return *slot;
  }
  return append_new(key, std::move(v));
}

Value& Object::append_new(std::string_view key, Value v) {
  // Built in place (a temporary Member would cost a move and a destruction of
  // its key and value): the key in the object's resource (a Member is not
  // allocator-aware, so emplace_back does not pass it on), the value moved in.
  members_.emplace_back(String(key, members_.get_allocator()), std::move(v), SourceLoc{});
  if (!index_.p && members_.size() > KeyIndex::kScanLimit) index_.create(resource());
  if (index_.p) index_.p->added(members_);
  return members_.back().value;
}

bool Object::erase(std::string_view key) {
  for (auto it = members_.begin(); it != members_.end(); ++it) {
    if (it->key == key) {
      members_.erase(it);
      reindex();
      return true;
    }
  }
  return false;
}

std::vector<std::string_view> Object::sorted_keys() const {
  std::vector<std::string_view> out;
  out.reserve(members_.size());
  for (const Member& m : members_) out.push_back(m.key);
  // Byte order of UTF-8 equals code-point order, which is what the JSON-LD
  // algorithms mean by "lexicographical order".
  std::sort(out.begin(), out.end());
  return out;
}

bool operator==(const Value& a, const Value& b) {
  if (a.kind() != b.kind()) return false;
  switch (a.kind()) {
    case Kind::Null:
      return true;
    case Kind::Boolean:
      return a.as_bool() == b.as_bool();
    case Kind::Number:
      return a.as_number() == b.as_number();
    case Kind::String:
      return a.as_string() == b.as_string();
    case Kind::Array: {
      const Array& x = a.as_array();
      const Array& y = b.as_array();
      if (x.size() != y.size()) return false;
      for (size_t i = 0; i < x.size(); ++i) {
        if (!(x[i] == y[i])) return false;
      }
      return true;
    }
    case Kind::Object: {
      const Object& x = a.as_object();
      const Object& y = b.as_object();
      if (x.size() != y.size()) return false;
      // Keys are unique, so equal sizes plus "every key of x maps to an equal
      // value in y" is equality regardless of member order.
      for (size_t i = 0; i < x.size(); ++i) {
        const Value* other = y.find(x.key(i));
        if (other == nullptr || !(x.value(i) == *other)) return false;
      }
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------------------
// Parser

namespace {

// Deep enough for any real document, shallow enough that recursion cannot
// exhaust the stack on hostile input.
constexpr int kMaxDepth = 512;

// The bytes that end a run of a string's ordinary bytes: the closing quote, a
// backslash, control characters and the bytes of multi-byte UTF-8.
constexpr std::array<bool, 256> kEndsRun = [] {
  std::array<bool, 256> t{};
  for (int c = 0; c < 256; ++c) t[static_cast<size_t>(c)] = c < 0x20 || c >= 0x80;
  t['"'] = true;
  t['\\'] = true;
  return t;
}();

}  // namespace

// Members and elements are collected in per-depth scratch buffers and moved
// into an exactly sized container, so that each object or array costs one
// allocation. The buffers are reused across objects and, through the
// caller's ParseScratch, across documents (a load parses dozens); ~Parser
// empties them.
struct ParseScratch::Buffers {
  std::vector<std::vector<Object::Member>> members;
  std::vector<std::vector<Value>> elements;
  std::vector<KeyIndex> key_indexes;
};

ParseScratch::ParseScratch() : buffers_(std::make_unique<Buffers>()) {}
ParseScratch::~ParseScratch() = default;

namespace {

class Parser {
 public:
  Parser(std::string_view text, uint32_t file_id, std::string_view file_name, Resource* resource,
         ParseScratch::Buffers& scratch)
      : text_(text),
        file_id_(file_id),
        file_name_(file_name),
        resource_(resource),
        scratch_(scratch) {}

  Value parse_document() {
    // RFC 8259 section 8.1: a parser may ignore a leading byte order mark.
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") {
      pos_ = 3;
      line_start_ = 3;
    }
    skip_ws();
    Value v;
    parse_value(v, 0);
    skip_ws();
    if (pos_ != text_.size()) fail("unexpected trailing characters after the JSON value");
    return v;
  }

 private:
  std::string_view text_;
  uint32_t file_id_;
  std::string_view file_name_;
  Resource* resource_;
  size_t pos_ = 0;
  uint32_t line_ = 1;
  size_t line_start_ = 0;

  SourceLoc here() const { return loc_at(pos_); }
  SourceLoc loc_at(size_t p) const {
    return SourceLoc{file_id_, line_, static_cast<uint32_t>(p - line_start_ + 1)};
  }

  [[noreturn]] void fail_at(size_t p, const std::string& message) const {
    fail_at(loc_at(p), message);
  }
  [[noreturn]] void fail_at(SourceLoc l, const std::string& message) const {
    throw Error("invalid json", message, std::string(file_name_), l.line, l.column);
  }
  [[noreturn]] void fail(const std::string& message) const { fail_at(pos_, message); }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }

  void skip_ws() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == ' ') {
        // Indentation: a run of spaces.
        const size_t run = text_.find_first_not_of(' ', pos_ + 1);
        pos_ = run == std::string_view::npos ? text_.size() : run;
      } else if (c == '\t' || c == '\r') {
        ++pos_;
      } else if (c == '\n') {
        ++pos_;
        ++line_;
        line_start_ = pos_;
      } else {
        break;
      }
    }
  }

  static std::string describe(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F) return std::string("'") + c + "'";
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02X", u);
    return std::string("byte ") + buf;
  }

  // Parses one value into `out` (null on entry), building it in place: an
  // object's members and an array's elements are parsed straight into their
  // slots, so no value is moved or destroyed on the way up.
  void parse_value(Value& out, int depth) {
    if (at_end()) fail("unexpected end of input; expected a JSON value");
    const SourceLoc start = here();
    switch (peek()) {
      case '{':
        parse_object(out, depth);
        break;
      case '[':
        parse_array(out, depth);
        break;
      case '"':
        parse_string(out.emplace_string(resource_));
        break;
      case 't':
        expect_literal("true");
        out = Value(true);
        break;
      case 'f':
        expect_literal("false");
        out = Value(false);
        break;
      case 'n':
        expect_literal("null");
        break;
      default: {
        const char c = peek();
        if (c == '-' || (c >= '0' && c <= '9')) {
          out = Value(parse_number());
          break;
        }
        fail("unexpected " + describe(c) + "; expected a JSON value");
      }
    }
    out.set_location(start);
  }

  void expect_literal(std::string_view lit) {
    const size_t start = pos_;
    size_t n = 0;
    while (start + n < text_.size() && n < lit.size() && text_[start + n] == lit[n]) ++n;
    if (n != lit.size()) fail_at(start, "invalid literal; expected 'true', 'false' or 'null'");
    pos_ += n;
    // "nullx" / "true1": the literal must not run on into an identifier.
    if (!at_end()) {
      const char c = peek();
      if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_') {
        fail_at(start, "invalid literal; expected 'true', 'false' or 'null'");
      }
    }
  }

  ParseScratch::Buffers& scratch_;

  // After an error the buffers still hold parsed values, whose blocks may be
  // in the caller's arena: they go now, while it exists. Buffers grown past
  // kKeptScratch entries by a huge object or array are given back, so a
  // ParseScratch keeps only what an ordinary document needs.
  static constexpr size_t kKeptScratch = 1024;
  template <class T>
  static void empty(std::vector<std::vector<T>>& levels) {
    for (std::vector<T>& level : levels) {
      level.clear();
      if (level.capacity() > kKeptScratch) std::vector<T>().swap(level);
    }
  }

 public:
  ~Parser() {
    empty(scratch_.members);
    empty(scratch_.elements);
    for (KeyIndex& index : scratch_.key_indexes) index.clear_keeping(4 * kKeptScratch);
  }
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

 private:
  template <class T>
  static T& scratch_at(std::vector<T>& s, int depth) {
    const auto d = static_cast<size_t>(depth);
    if (s.size() <= d) s.resize(d + 1);
    return s[d];
  }

  void parse_object(Value& out, int depth) {
    if (depth >= kMaxDepth) fail("nesting deeper than 512 levels");
    ++pos_;  // '{'
    skip_ws();
    if (!at_end() && peek() == '}') {
      ++pos_;
      out.emplace_object(resource_);
      return;
    }
    scratch_at(scratch_.members, depth).clear();
    scratch_at(scratch_.key_indexes, depth).clear();
    for (;;) {
      if (at_end()) fail("unexpected end of input; expected a string key in object");
      if (peek() != '"') fail("expected a string key in object, found " + describe(peek()));
      const SourceLoc key_loc = here();
      String key(resource_);
      parse_string(key);
      skip_ws();
      if (at_end() || peek() != ':') fail("expected ':' after object key");
      ++pos_;
      skip_ws();
      // Duplicate keys: the last wins, as in JavaScript's JSON.parse. The
      // scratch vectors are looked up again after each nested value: parsing
      // it may grow the per-depth lists (moving the vectors, not their
      // elements, so `slot` stays valid).
      std::vector<Object::Member>& members = scratch_.members[static_cast<size_t>(depth)];
      KeyIndex& index = scratch_.key_indexes[static_cast<size_t>(depth)];
      if (const size_t same = index.find(members, key); same != KeyIndex::kNone) {
        Value v;
        parse_value(v, depth + 1);
        Object::Member& m = scratch_.members[static_cast<size_t>(depth)][same];
        m.value = std::move(v);
        m.key_loc = key_loc;
      } else {
        // The key moves in with its resource (assigning it to a default
        // member's key would copy it to the heap).
        Object::Member& m = members.emplace_back(std::move(key), Value(), key_loc);
        index.added(members);
        Value* slot = &m.value;
        parse_value(*slot, depth + 1);
      }
      skip_ws();
      if (at_end()) fail("unexpected end of input; expected ',' or '}' after object member");
      const char c = peek();
      if (c == '}') {
        ++pos_;
        std::vector<Object::Member>& done = scratch_.members[static_cast<size_t>(depth)];
        out.emplace_object(resource_).append_members(std::make_move_iterator(done.begin()),
                                                     std::make_move_iterator(done.end()));
        done.clear();
        return;
      }
      if (c != ',') fail("expected ',' or '}' after object member");
      const SourceLoc comma = here();
      ++pos_;
      skip_ws();
      if (!at_end() && peek() == '}') fail_at(comma, "trailing comma in object");
    }
  }

  void parse_array(Value& out, int depth) {
    if (depth >= kMaxDepth) fail("nesting deeper than 512 levels");
    ++pos_;  // '['
    skip_ws();
    if (!at_end() && peek() == ']') {
      ++pos_;
      out.emplace_array(resource_);
      return;
    }
    scratch_at(scratch_.elements, depth).clear();
    for (;;) {
      // As in parse_object: the element's slot survives the nested parse,
      // the reference to this depth's vector may not.
      Value* slot = &scratch_.elements[static_cast<size_t>(depth)].emplace_back();
      parse_value(*slot, depth + 1);
      skip_ws();
      if (at_end()) fail("unexpected end of input; expected ',' or ']' after array element");
      const char c = peek();
      if (c == ']') {
        ++pos_;
        std::vector<Value>& elements = scratch_.elements[static_cast<size_t>(depth)];
        out.emplace_array(resource_).assign(std::make_move_iterator(elements.begin()),
                                            std::make_move_iterator(elements.end()));
        elements.clear();
        return;
      }
      if (c != ',') fail("expected ',' or ']' after array element");
      const SourceLoc comma = here();
      ++pos_;
      skip_ws();
      if (!at_end() && peek() == ']') fail_at(comma, "trailing comma in array");
    }
  }

  double parse_number() {
    const size_t start = pos_;
    if (peek() == '-') ++pos_;
    if (at_end() || !is_digit(peek())) fail("expected a digit in number");
    if (peek() == '0') {
      ++pos_;
      if (!at_end() && is_digit(peek())) fail_at(start, "leading zeros are not allowed in numbers");
    } else {
      while (!at_end() && is_digit(peek())) ++pos_;
    }
    bool negative_exponent = false;
    if (!at_end() && peek() == '.') {
      ++pos_;
      if (at_end() || !is_digit(peek())) fail("expected a digit after '.' in number");
      while (!at_end() && is_digit(peek())) ++pos_;
    }
    if (!at_end() && (peek() == 'e' || peek() == 'E')) {
      ++pos_;
      if (!at_end() && (peek() == '+' || peek() == '-')) {
        negative_exponent = peek() == '-';
        ++pos_;
      }
      if (at_end() || !is_digit(peek())) fail("expected a digit in number exponent");
      while (!at_end() && is_digit(peek())) ++pos_;
    }
    const char* first = text_.data() + start;
    const char* last = text_.data() + pos_;
    double d = 0;
    auto [ptr, ec] = std::from_chars(first, last, d);
    if (ec == std::errc::result_out_of_range) {
      // JavaScript semantics: overflow gives +-Infinity, underflow +-0.
      const bool neg = *first == '-';
      if (negative_exponent) {
        d = neg ? -0.0 : 0.0;
      } else {
        d = neg ? -std::numeric_limits<double>::infinity()
                : std::numeric_limits<double>::infinity();
      }
    } else if (ec != std::errc() || ptr != last) {
      fail_at(start, "malformed number");
    }
    return d;
  }

  static bool is_digit(char c) { return c >= '0' && c <= '9'; }

  static int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  }

  // Reads the 4 hex digits after "\u" (pos_ at the first digit).
  uint32_t read_hex4(size_t escape_start) {
    if (text_.size() - pos_ < 4) fail_at(escape_start, "invalid \\u escape: expected 4 hex digits");
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
      const int h = hex_value(text_[pos_ + static_cast<size_t>(i)]);
      if (h < 0) fail_at(escape_start, "invalid \\u escape: expected 4 hex digits");
      v = v * 16 + static_cast<uint32_t>(h);
    }
    pos_ += 4;
    return v;
  }

  // Length of the valid UTF-8 sequence starting at p (0 when invalid). Rejects
  // overlong forms, surrogates and code points above U+10FFFF (RFC 3629).
  size_t utf8_length(size_t p) const {
    const auto b0 = static_cast<unsigned char>(text_[p]);
    size_t n;
    uint32_t cp;
    if (b0 >= 0xC2 && b0 <= 0xDF) {
      n = 2;
      cp = b0 & 0x1F;
    } else if (b0 >= 0xE0 && b0 <= 0xEF) {
      n = 3;
      cp = b0 & 0x0F;
    } else if (b0 >= 0xF0 && b0 <= 0xF4) {
      n = 4;
      cp = b0 & 0x07;
    } else {
      return 0;
    }
    if (text_.size() - p < n) return 0;
    for (size_t i = 1; i < n; ++i) {
      const auto b = static_cast<unsigned char>(text_[p + i]);
      if ((b & 0xC0) != 0x80) return 0;
      cp = (cp << 6) | (b & 0x3F);
    }
    if ((n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000) || cp > 0x10FFFF ||
        (cp >= 0xD800 && cp <= 0xDFFF)) {
      return 0;
    }
    return n;
  }

  // Parses the string at pos_ into `out` (empty, in the document's resource).
  void parse_string(String& out) {
    const size_t open = pos_;
    ++pos_;  // opening quote
    {
      // Most strings are one run of ordinary bytes: sized once.
      const auto* bytes = reinterpret_cast<const unsigned char*>(text_.data());
      size_t end = pos_;
      while (end < text_.size() && !kEndsRun[bytes[end]]) ++end;
      if (end < text_.size() && text_[end] == '"') {
        out.assign(text_.data() + pos_, end - pos_);
        pos_ = end + 1;
        return;
      }
    }
    for (;;) {
      // Copy the longest run of ordinary bytes in one go.
      const size_t run = pos_;
      const auto* bytes = reinterpret_cast<const unsigned char*>(text_.data());
      while (pos_ < text_.size() && !kEndsRun[bytes[pos_]]) ++pos_;
      out.append(text_.data() + run, pos_ - run);
      if (at_end()) fail_at(open, "unterminated string");
      const auto c = static_cast<unsigned char>(peek());
      if (c == '"') {
        ++pos_;
        return;
      }
      if (c < 0x20) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "unescaped control character U+%04X in string", c);
        fail(buf);
      }
      if (c >= 0x80) {
        const size_t n = utf8_length(pos_);
        if (n == 0) fail("invalid UTF-8 in string");
        out.append(text_.data() + pos_, n);
        pos_ += n;
        continue;
      }
      // Backslash escape.
      const size_t esc = pos_;
      ++pos_;
      if (at_end()) fail_at(open, "unterminated string");
      const char e = peek();
      ++pos_;
      switch (e) {
        case '"':
          out += '"';
          break;
        case '\\':
          out += '\\';
          break;
        case '/':
          out += '/';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          uint32_t cp = read_hex4(esc);
          if (cp >= 0xDC00 && cp <= 0xDFFF) {
            fail_at(esc,
                    "unpaired low surrogate " + std::string(text_.substr(esc, 6)) + " in string");
          }
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            // A high surrogate must be followed by an escaped low surrogate; lone
            // surrogates have no UTF-8 form, so they are rejected.
            if (text_.size() - pos_ < 6 || text_[pos_] != '\\' || text_[pos_ + 1] != 'u') {
              fail_at(esc, "lone high surrogate " + std::string(text_.substr(esc, 6)) +
                               " in string (expected a following \\uDC00-\\uDFFF escape)");
            }
            const size_t esc2 = pos_;
            pos_ += 2;
            const uint32_t lo = read_hex4(esc2);
            if (lo < 0xDC00 || lo > 0xDFFF) {
              fail_at(esc, "lone high surrogate " + std::string(text_.substr(esc, 6)) +
                               " in string (expected a following \\uDC00-\\uDFFF escape)");
            }
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          append_utf8(out, cp);
          break;
        }
        default: {
          // A raw byte is quoted only when printable (describe escapes the rest).
          const auto u = static_cast<unsigned char>(e);
          if (u >= 0x20 && u < 0x7F) {
            fail_at(esc, "invalid escape sequence '\\" + std::string(1, e) + "' in string");
          }
          fail_at(esc, "invalid escape sequence: '\\' followed by " + describe(e) + " in string");
        }
      }
    }
  }
};

}  // namespace

Value parse(std::string_view text, uint32_t file_id, std::string_view file_name, Resource* resource,
            ParseScratch* scratch) {
  std::optional<ParseScratch> own;
  if (scratch == nullptr) scratch = &own.emplace();
  Parser p(text, file_id, file_name, resource, scratch->buffers());
  return p.parse_document();
}

// ---------------------------------------------------------------------------
// Serialisation

bool lives_in(const Value& v, const Resource* resource) {
  switch (v.kind()) {
    case Kind::String:
      return std::get<String>(v.data_).get_allocator().resource() == resource;
    case Kind::Array: {
      const Array& a = v.as_array();
      if (a.get_allocator().resource() != resource) return false;
      for (const Value& e : a) {
        if (!lives_in(e, resource)) return false;
      }
      return true;
    }
    case Kind::Object: {
      const Object& o = v.as_object();
      if (o.resource() != resource) return false;
      if (o.index_.p != nullptr && o.index_.resource_ != resource) return false;
      for (const Object::Member& m : o.members_) {
        if (m.key.get_allocator().resource() != resource || !lives_in(m.value, resource)) {
          return false;
        }
      }
      return true;
    }
    default:
      return true;
  }
}

std::string number_to_string(double d) {
  if (std::isnan(d)) return "NaN";
  if (d == 0) return "0";  // covers -0 as well
  if (std::isinf(d)) return d < 0 ? "-Infinity" : "Infinity";
  std::string out;
  if (d < 0) {
    out += '-';
    d = -d;
  }
  // Shortest round-trip digits in scientific form: "d[.ddd]e[+-]xx". These are
  // ECMAScript's s (digits, k of them) and n (decimal exponent + 1).
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, d, std::chars_format::scientific);
  const std::string_view sci(buf, static_cast<size_t>(res.ptr - buf));
  const size_t epos = sci.find('e');
  std::string digits;
  for (char c : sci.substr(0, epos)) {
    if (c != '.') digits += c;
  }
  int exp10 = 0;
  std::string_view es = sci.substr(epos + 1);
  if (!es.empty() && es[0] == '+') es.remove_prefix(1);
  std::from_chars(es.data(), es.data() + es.size(), exp10);
  const int k = static_cast<int>(digits.size());
  const int n = exp10 + 1;
  // ECMAScript Number::toString, steps for the four layouts.
  if (k <= n && n <= 21) {
    out += digits;
    out.append(static_cast<size_t>(n - k), '0');
  } else if (0 < n && n <= 21) {
    out += digits.substr(0, static_cast<size_t>(n));
    out += '.';
    out += digits.substr(static_cast<size_t>(n));
  } else if (-6 < n && n <= 0) {
    out += "0.";
    out.append(static_cast<size_t>(-n), '0');
    out += digits;
  } else {
    out += digits[0];
    if (k > 1) {
      out += '.';
      out += digits.substr(1);
    }
    out += 'e';
    out += (n - 1 < 0) ? '-' : '+';
    out += std::to_string(std::abs(n - 1));
  }
  return out;
}

namespace {

// Escapes only what JSON requires (RFC 8785 section 3.2.2.2): quote, backslash
// and control characters, using the short forms where they exist.
void write_string(std::string& out, std::string_view s) {
  out += '"';
  size_t run = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c != '"' && c != '\\') continue;
    out.append(s.data() + run, i - run);
    run = i + 1;
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default: {
        static constexpr char kHex[] = "0123456789abcdef";
        out += "\\u00";
        out += kHex[c >> 4];
        out += kHex[c & 0xF];
      }
    }
  }
  out.append(s.data() + run, s.size() - run);
  out += '"';
}

void newline(std::string& out, int indent, int level) {
  if (indent < 0) return;
  out += '\n';
  out.append(static_cast<size_t>(indent * level), ' ');
}

void dump_to(std::string& out, const Value& v, int indent, int level) {
  switch (v.kind()) {
    case Kind::Null:
      out += "null";
      break;
    case Kind::Boolean:
      out += v.as_bool() ? "true" : "false";
      break;
    case Kind::Number:
      // JSON has no Infinity/NaN; JSON.stringify writes null for them.
      if (std::isfinite(v.as_number())) {
        out += number_to_string(v.as_number());
      } else {
        out += "null";
      }
      break;
    case Kind::String:
      write_string(out, v.as_string());
      break;
    case Kind::Array: {
      const Array& a = v.as_array();
      if (a.empty()) {
        out += "[]";
        break;
      }
      out += '[';
      for (size_t i = 0; i < a.size(); ++i) {
        if (i != 0) out += ',';
        newline(out, indent, level + 1);
        dump_to(out, a[i], indent, level + 1);
      }
      newline(out, indent, level);
      out += ']';
      break;
    }
    case Kind::Object: {
      const Object& o = v.as_object();
      if (o.empty()) {
        out += "{}";
        break;
      }
      out += '{';
      for (size_t i = 0; i < o.size(); ++i) {
        if (i != 0) out += ',';
        newline(out, indent, level + 1);
        write_string(out, o.key(i));
        out += indent < 0 ? ":" : ": ";
        dump_to(out, o.value(i), indent, level + 1);
      }
      newline(out, indent, level);
      out += '}';
      break;
    }
  }
}

// UTF-16 code units of a UTF-8 string, for RFC 8785's member ordering (which
// differs from code-point order for U+E000..U+FFFF versus astral characters).
std::u16string to_utf16(std::string_view s) {
  std::u16string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    const auto b0 = static_cast<unsigned char>(s[i]);
    uint32_t cp;
    size_t n;
    if (b0 < 0x80) {
      cp = b0;
      n = 1;
    } else if (b0 < 0xE0) {
      cp = b0 & 0x1F;
      n = 2;
    } else if (b0 < 0xF0) {
      cp = b0 & 0x0F;
      n = 3;
    } else {
      cp = b0 & 0x07;
      n = 4;
    }
    for (size_t j = 1; j < n && i + j < s.size(); ++j) {
      cp = (cp << 6) | (static_cast<unsigned char>(s[i + j]) & 0x3F);
    }
    i += n;
    if (cp >= 0x10000) {
      cp -= 0x10000;
      out += static_cast<char16_t>(0xD800 + (cp >> 10));
      out += static_cast<char16_t>(0xDC00 + (cp & 0x3FF));
    } else {
      out += static_cast<char16_t>(cp);
    }
  }
  return out;
}

void canonicalize_to(std::string& out, const Value& v) {
  switch (v.kind()) {
    case Kind::Number:
      if (!std::isfinite(v.as_number())) {
        const SourceLoc l = v.location();
        throw Error("invalid json",
                    "RFC 8785 canonicalization: " + number_to_string(v.as_number()) +
                        " is not a JSON number",
                    {}, l.line, l.column);
      }
      out += number_to_string(v.as_number());
      break;
    case Kind::Array: {
      out += '[';
      const Array& a = v.as_array();
      for (size_t i = 0; i < a.size(); ++i) {
        if (i != 0) out += ',';
        canonicalize_to(out, a[i]);
      }
      out += ']';
      break;
    }
    case Kind::Object: {
      const Object& o = v.as_object();
      std::vector<std::pair<std::u16string, size_t>> order;
      order.reserve(o.size());
      for (size_t i = 0; i < o.size(); ++i) order.emplace_back(to_utf16(o.key(i)), i);
      std::sort(order.begin(), order.end());
      out += '{';
      for (size_t i = 0; i < order.size(); ++i) {
        if (i != 0) out += ',';
        write_string(out, o.key(order[i].second));
        out += ':';
        canonicalize_to(out, o.value(order[i].second));
      }
      out += '}';
      break;
    }
    default:
      dump_to(out, v, -1, 0);
  }
}

}  // namespace

std::string dump(const Value& v, int indent) {
  std::string out;
  dump_to(out, v, indent, 0);
  return out;
}

std::string canonicalize(const Value& v) {
  std::string out;
  canonicalize_to(out, v);
  return out;
}

std::string_view kind_name(Kind kind) {
  switch (kind) {
    case Kind::Null:
      return "null";
    case Kind::Boolean:
      return "a boolean";
    case Kind::Number:
      return "a number";
    case Kind::String:
      return "a string";
    case Kind::Array:
      return "an array";
    case Kind::Object:
      return "an object";
  }
  return "a value";
}

}  // namespace mospec::json
