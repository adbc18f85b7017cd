// A JSON document model that remembers where each value was written.
//
// JSON-LD processing needs (a) JavaScript number semantics (every number is a
// double), (b) the source position of each value so diagnostics and quads can
// point at file:line:col, and (c) stable member order for deterministic output.
// Objects keep their members in insertion order with unique keys.
//
// Strings, arrays and objects allocate from a std::pmr::memory_resource: the
// heap unless a value was built for an arena (parse(), the emplace_*
// functions and the constructors that take a Resource). A document parsed or
// expanded into a monotonic arena costs a bump of a pointer per string, array
// and object instead of a malloc, and is freed at once. Copies always go to
// the heap (std::pmr containers copy with the default resource), so a copy
// never outlives an arena by accident; a moved value keeps its resource, so a
// value built in an arena must not be moved into anything that outlives it.
#pragma once

#include <cstdint>
#include <memory>
#include <memory_resource>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "support/diagnostics.hpp"

namespace mospec::json {

class Value;
using Resource = std::pmr::memory_resource;
using String = std::pmr::string;
using Array = std::pmr::vector<Value>;

namespace detail {
class KeyIndex;  // json.cpp
}

class Object {
 public:
  // Declared here, defaulted below once Member is complete: Member holds a
  // Value, which holds an Object, so these cannot be implicit (clang needs
  // ~vector<Member> at the point they would be generated).
  inline Object();
  // An empty object whose members (keys included) live in `resource`.
  inline explicit Object(Resource* resource);
  inline ~Object();
  inline Object(const Object&);
  inline Object(Object&&) noexcept;
  // Assignment keeps this object's resource (std::pmr containers do), the
  // key index included.
  Object& operator=(const Object&);
  Object& operator=(Object&&) noexcept;

  // Bodies that touch members_ come after Member is complete (clang
  // instantiates std::vector members eagerly in inline bodies).
  inline size_t size() const;
  inline bool empty() const;
  // Where the members live (the heap unless built for an arena).
  Resource* resource() const { return members_.get_allocator().resource(); }
  inline void reserve(size_t n);
  const Value* find(std::string_view key) const;
  // The position of `key` among the members, or std::string::npos.
  size_t index_of(std::string_view key) const;
  Value* find(std::string_view key);
  bool contains(std::string_view key) const { return find(key) != nullptr; }
  // Inserts or replaces; returns the stored value. A new key is copied into
  // the object's resource.
  Value& set(std::string_view key, Value v);
  // Appends without looking for an existing member: the caller guarantees the
  // key is new (saves set()'s linear search when building large objects).
  Value& append_new(std::string_view key, Value v);
  bool erase(std::string_view key);
  inline std::string_view key(size_t i) const;
  inline const Value& value(size_t i) const;
  inline Value& value(size_t i);
  // Keys in code-point (byte) order, as the JSON-LD algorithms iterate them.
  std::vector<std::string_view> sorted_keys() const;
  // Where the key i was written (its opening quote).
  inline SourceLoc key_location(size_t i) const;
  inline void set_key_location(size_t i, SourceLoc l);

  // One member; members are kept together so that an object is one allocation.
  struct Member;
  // Appends members whose keys are unique and new to this object.
  template <class It>
  void append_members(It first, It last);

 private:
  // Member positions by key, kept once the object has more than 16 members so
  // that find() and set() stay O(1) on large objects (null below that). It
  // lives in the object's resource, like everything else the object holds,
  // so a tree built in an arena is in the arena whole; a copy is on the heap.
  class IndexPtr {
   public:
    IndexPtr() noexcept;
    IndexPtr(const IndexPtr&);
    IndexPtr& operator=(const IndexPtr&);
    IndexPtr(IndexPtr&&) noexcept;
    IndexPtr& operator=(IndexPtr&&) noexcept;
    ~IndexPtr();
    void create(Resource* resource);
    void reset() noexcept;
    detail::KeyIndex* p = nullptr;
    Resource* resource_ = nullptr;
  };
  void reindex();

  std::pmr::vector<Member> members_;
  IndexPtr index_;

  friend bool lives_in(const Value& v, const Resource* resource);
};

enum class Kind : uint8_t { Null, Boolean, Number, String, Array, Object };

// "null", "a boolean", "a number", "a string", "an array", "an object": a
// kind as a message names it ("\"duration\" is a string; ...").
std::string_view kind_name(Kind kind);

class Value {
 public:
  Value() = default;  // null
  Value(std::nullptr_t) {}
  Value(bool b) : data_(b) {}
  Value(double d) : data_(d) {}
  Value(int i) : data_(static_cast<double>(i)) {}
  Value(String s) : data_(std::move(s)) {}
  Value(const std::string& s) : data_(std::in_place_type<String>, s) {}
  Value(std::string_view s) : data_(std::in_place_type<String>, s) {}
  Value(const char* s) : data_(std::in_place_type<String>, s) {}
  // A string whose bytes live in `resource`.
  Value(std::string_view s, Resource* resource) : data_(std::in_place_type<String>, s, resource) {}
  Value(Array a) : data_(std::move(a)) {}
  Value(Object o) : data_(std::move(o)) {}

  Kind kind() const { return static_cast<Kind>(data_.index()); }
  bool is_null() const { return kind() == Kind::Null; }
  bool is_bool() const { return kind() == Kind::Boolean; }
  bool is_number() const { return kind() == Kind::Number; }
  bool is_string() const { return kind() == Kind::String; }
  bool is_array() const { return kind() == Kind::Array; }
  bool is_object() const { return kind() == Kind::Object; }
  bool is_scalar() const { return is_bool() || is_number() || is_string(); }

  bool as_bool() const { return std::get<bool>(data_); }
  double as_number() const { return std::get<double>(data_); }
  // The string's bytes, whatever resource holds them.
  std::string_view as_string() const { return std::get<String>(data_); }
  const Array& as_array() const { return std::get<Array>(data_); }
  Array& as_array() { return std::get<Array>(data_); }
  const Object& as_object() const { return std::get<Object>(data_); }
  Object& as_object() { return std::get<Object>(data_); }

  // Makes this an empty object, array or string in `resource` and returns
  // it, to be filled in place (the parser builds each value where it will
  // stay).
  Object& emplace_object(Resource* resource = std::pmr::get_default_resource()) {
    return data_.emplace<Object>(resource);
  }
  Array& emplace_array(Resource* resource = std::pmr::get_default_resource()) {
    return data_.emplace<Array>(resource);
  }
  String& emplace_string(Resource* resource = std::pmr::get_default_resource()) {
    return data_.emplace<String>(resource);
  }

  // Convenience for objects: member lookup (nullptr if not an object or absent).
  const Value* get(std::string_view key) const {
    return is_object() ? as_object().find(key) : nullptr;
  }

  SourceLoc location() const { return loc_; }
  void set_location(SourceLoc l) { loc_ = l; }
  // Returns a copy with the location set (handy when building output values).
  Value located(SourceLoc l) const& {
    Value v = *this;
    v.loc_ = l;
    return v;
  }

  // Deep structural equality (numbers by value, objects ignoring member order);
  // locations are ignored.
  friend bool operator==(const Value& a, const Value& b);

 private:
  std::variant<std::nullptr_t, bool, double, String, Array, Object> data_{nullptr};
  friend bool lives_in(const Value& v, const Resource* resource);
  SourceLoc loc_{};
};

struct Object::Member {
  // (A constructor, not aggregate initialisation, so that emplace_back builds
  // a member in place with clang 14 too.)
  Member(String&& k, Value&& v, SourceLoc loc)
      : key(std::move(k)), value(std::move(v)), key_loc(loc) {}
  String key;
  Value value;
  SourceLoc key_loc{};
};

inline Object::Object() = default;
inline Object::Object(Resource* resource) : members_(resource) {}
inline Object::~Object() = default;
inline Object::Object(const Object&) = default;
inline Object::Object(Object&&) noexcept = default;

inline size_t Object::size() const {
  return members_.size();
}
inline bool Object::empty() const {
  return members_.empty();
}
inline void Object::reserve(size_t n) {
  members_.reserve(n);
}
template <class It>
void Object::append_members(It first, It last) {
  members_.insert(members_.end(), first, last);
  reindex();
}

inline std::string_view Object::key(size_t i) const {
  return members_[i].key;
}
inline const Value& Object::value(size_t i) const {
  return members_[i].value;
}
inline Value& Object::value(size_t i) {
  return members_[i].value;
}
inline SourceLoc Object::key_location(size_t i) const {
  return members_[i].key_loc;
}
inline void Object::set_key_location(size_t i, SourceLoc l) {
  members_[i].key_loc = l;
}

// The parser's buffers (per nesting level, the members and elements being
// collected): a caller parsing many documents (the loader) owns one per
// thread and passes it to every parse(), so that a document costs one
// allocation per object or array once the buffers have grown. Not thread-safe.
class ParseScratch {
 public:
  ParseScratch();
  ~ParseScratch();
  ParseScratch(const ParseScratch&) = delete;
  ParseScratch& operator=(const ParseScratch&) = delete;

  struct Buffers;  // json.cpp
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

// Parses RFC 8259 JSON. Errors throw mospec::Error with code "invalid json"
// (the JSON-LD "loading document failed" family is decided by the caller) and the
// file name, line and column of the offending character. Duplicate keys: the last
// wins (as in JavaScript). Records locations with `file_id`. The value's
// strings, arrays and objects live in `resource` (the heap by default).
// Buffers come from `scratch`; without one, the call makes its own.
Value parse(std::string_view text, uint32_t file_id = 0, std::string_view file_name = "<input>",
            Resource* resource = std::pmr::get_default_resource(), ParseScratch* scratch = nullptr);

// Serialises compactly (no whitespace) or with `indent` spaces per level.
// Numbers are written as JavaScript does (shortest round-trip form; integers
// without a fraction).
std::string dump(const Value& v, int indent = -1);

// RFC 8785 JSON Canonicalization Scheme (used for @json literals): members sorted
// by UTF-16 code units, ECMAScript number serialisation, minimal escaping.
std::string canonicalize(const Value& v);

// ECMAScript Number::toString (e.g. 1 -> "1", 0.1 -> "0.1", 1e21 -> "1e+21").
std::string number_to_string(double d);

// Whether every string, array, object, key and key index of `v` allocates
// from `resource`: then dropping the resource frees all of `v`, and `v` need
// not be destroyed (the loader drops parsed and expanded trees that way).
bool lives_in(const Value& v, const Resource* resource);

}  // namespace mospec::json
