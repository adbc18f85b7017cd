// The logic-less templates of the code generator: the part of Mustache that
// src/codegen/templates uses (variables {{x}} and {{{x}}}, sections {{#x}},
// inverted sections {{^x}}, comments {{! }}), substituted verbatim (C++ and
// CMake, not HTML), over a data tree built for one render. It lives in
// support, not codegen, because every IR step kind builds its own template
// section (ir/emit.hpp) and codegen renders them.
//
// It renders what kainjow's Mustache (the library codegen used before) renders
// for these templates, blank-line rule included: a line that held a section
// tag of a section that rendered and ends up empty or only blanks is dropped
// with its line break. Lookups search the section stack innermost first; a
// name found nowhere renders nothing and counts as false. Partials, lambdas,
// dotted names and set-delimiter tags are refused when the template is parsed.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mospec::mustache {

// A value of the data tree: an object (named members, in insertion order), a
// list, a string or a boolean. A section renders once for a string, an object
// or true (the value pushed on the stack), once per item for a non-empty list,
// and not at all for false or an empty list.
class Data {
 public:
  enum class Kind : uint8_t { Object, List, String, True, False };

  // Defined below, once Member is complete: a Member holds a Data, so
  // these cannot be implicit or in the class (clang needs ~vector<Member>
  // where a constructor is defined).
  inline Data();  // an empty object
  inline Data(std::string text);
  inline Data(const char* text);
  inline Data(bool b);
  inline ~Data();
  inline Data(const Data&);
  inline Data(Data&&) noexcept;
  inline Data& operator=(const Data&);
  inline Data& operator=(Data&&) noexcept;
  static inline Data list();

  Kind kind() const { return kind_; }
  // Sets member `key` of an object (replacing a member of that name).
  void put(std::string_view key, Data value);
  // Appends an item to a list.
  void append(Data value) { items_.push_back(std::move(value)); }
  // The items of a list.
  const std::vector<Data>& items() const { return items_; }
  const std::string& text() const { return text_; }
  // Member `key` of an object; nullptr for a missing key or a non-object.
  const Data* find(std::string_view key) const;

 private:
  Kind kind_ = Kind::Object;
  std::string text_;
  struct Member;
  std::vector<Data> items_;      // a list's items
  std::vector<Member> members_;  // an object's members, in insertion order
};

struct Data::Member {
  std::string key;
  Data value;
};

inline Data::Data() = default;
inline Data::Data(std::string text) : kind_(Kind::String), text_(std::move(text)) {}
inline Data::Data(const char* text) : kind_(Kind::String), text_(text) {}
inline Data::Data(bool b) : kind_(b ? Kind::True : Kind::False) {}
inline Data::~Data() = default;
inline Data::Data(const Data&) = default;
inline Data::Data(Data&&) noexcept = default;
inline Data& Data::operator=(const Data&) = default;
inline Data& Data::operator=(Data&&) noexcept = default;
inline Data Data::list() {
  Data d;
  d.kind_ = Kind::List;
  return d;
}

// Renders `text` with `data` as the outermost context. A malformed template
// (an unclosed tag or section, a section closed under another name, a tag
// this subset does not have) throws mospec::Error "codegen-template" naming
// the byte offset.
std::string render(std::string_view text, const Data& data);

}  // namespace mospec::mustache
