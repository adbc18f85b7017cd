#include "support/spelling.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace mospec {

size_t edit_distance(std::string_view a, std::string_view b, size_t limit) {
  if (a.size() > b.size() + limit || b.size() > a.size() + limit) return limit + 1;
  // One row of the table; on the stack for names of ordinary length, as this
  // runs against every term of a context for each misspelt key.
  std::array<size_t, 64> small;
  std::vector<size_t> large;
  size_t* row = small.data();
  if (b.size() + 1 > small.size()) {
    large.resize(b.size() + 1);
    row = large.data();
  }
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    size_t best = row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
      best = std::min(best, row[j]);
    }
    if (best > limit) return limit + 1;
  }
  return row[b.size()];
}

size_t typo_limit(std::string_view name) {
  // Names of one to three letters are near too many others to guess.
  return name.size() < 4 ? 0 : std::max<size_t>(1, name.size() / 5);
}

namespace {
bool upper(char c) {
  return c >= 'A' && c <= 'Z';
}
}  // namespace

void Nearest::offer(std::string_view candidate) {
  if (limit_ == 0 || candidate == name_ || candidate.empty()) return;
  // A class name (capitalised) is no typo of a property name, nor the reverse.
  if (upper(candidate[0]) != upper(name_[0])) return;
  if (candidate.size() > name_.size() + limit_ || name_.size() > candidate.size() + limit_) return;
  const size_t d = edit_distance(name_, candidate, limit_);
  if (d > limit_) return;
  if (d < distance_ || (d == distance_ && candidate < best_)) {
    distance_ = d;
    best_ = candidate;
  }
}

}  // namespace mospec
