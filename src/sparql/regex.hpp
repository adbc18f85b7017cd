// XPath regular expressions (XQuery 1.0 and XPath Functions and Operators,
// section 7.6), as SPARQL's REGEX and SHACL's sh:pattern / sh:flags use them,
// run by RE2: matching takes time linear in the text whatever the pattern, and
// never recurses per character (libstdc++'s regex did both: `^(a|a)*$` on 35
// characters hung, `^(a|b)*$` on 20,000 overflowed the stack).
//
// The one translation from XPath syntax to RE2 syntax:
//  - flags: s (dot matches newlines), m (^ and $ at line breaks), i (case
//    insensitive, Unicode simple case folding), x (whitespace outside
//    character classes removed), q (the whole pattern is literal; only i
//    still applies). Any other flag is an error.
//  - '.' without s matches any character except \n and \r.
//  - \i and \c (XML name start and name characters) and their negations \I
//    and \C become explicit classes; \I and \C inside [...] are unsupported.
//  - \p{..} / \P{..} with a general category (\p{Lu}) pass through; the block
//    escapes \p{IsBasicLatin} are unsupported, as is class subtraction [a-[b]].
//  - \d, \w and \s are RE2's ASCII classes (as ECMAScript's were before).
// What RE2 itself cannot compile (back-references \1, counted repetition
// beyond 1000, a program over RE2's memory budget) is an error naming the
// pattern and RE2's reason.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace re2 {
class RE2;
}

namespace mospec::sparql {

class RegexError : public std::runtime_error {
 public:
  enum class Kind : uint8_t {
    Flag,         // a flag outside s, m, i, x, q
    Unsupported,  // valid XPath syntax RE2 cannot express (see above)
    Invalid,      // not a valid pattern, or RE2 refused it
  };
  RegexError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// A compiled pattern. Copies share the compiled program; const use is
// thread-safe.
class Regex {
 public:
  // Throws RegexError; its message names the pattern (or the flag).
  Regex(std::string_view pattern, std::string_view flags);

  // True when the pattern matches somewhere in `text` (fn:matches). Keeps
  // no state: SPARQL's REGEX runs it through Budget::regex(), which charges
  // and counts the work.
  bool search(std::string_view text) const;
  // The RE2 syntax the pattern was translated into (for tests and messages).
  const std::string& translated() const { return translated_; }

 private:
  std::shared_ptr<const re2::RE2> re_;
  std::string translated_;
};

}  // namespace mospec::sparql
