// "Did you mean ...?" for a misspelt name: the candidate nearest in edit
// distance, if it is near enough to be a plausible typo.
#pragma once

#include <cstddef>
#include <string_view>

namespace mospec {

// Levenshtein distance between a and b, or limit + 1 once it is certainly
// above `limit` (so comparing against many candidates stays cheap).
size_t edit_distance(std::string_view a, std::string_view b, size_t limit);

// How many edits a name of this length may be away from a candidate and still
// be taken for a typo of it: a fifth of the name, at least one (compound
// names share long parts: "AngleConstraint" is no typo of "ForceConstraint");
// none for names shorter than four letters.
size_t typo_limit(std::string_view name);

// Keeps the nearest candidate offered to it (ties: the lexically smallest), so
// the answer does not depend on the order candidates come in. A candidate
// whose first letter differs in case (a class for a property) is not offered.
class Nearest {
 public:
  explicit Nearest(std::string_view name) : name_(name), limit_(typo_limit(name)) {}
  void offer(std::string_view candidate);
  // The nearest candidate within the typo limit, or "" when none is.
  std::string_view best() const { return best_; }

 private:
  std::string_view name_;
  size_t limit_;
  size_t distance_ = static_cast<size_t>(-1);
  std::string_view best_;
};

}  // namespace mospec
