#include "support/spelling.hpp"

#include <algorithm>
#include <vector>

namespace mospec {

size_t edit_distance(std::string_view a, std::string_view b, size_t limit) {
  if (a.size() > b.size() + limit || b.size() > a.size() + limit) return limit + 1;
  std::vector<size_t> row(b.size() + 1);
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
  return std::max<size_t>(2, name.size() / 3);
}

void Nearest::offer(std::string_view candidate) {
  if (candidate == name_) return;
  const size_t d = edit_distance(name_, candidate, limit_);
  if (d > limit_) return;
  if (d < distance_ || (d == distance_ && candidate < best_)) {
    distance_ = d;
    best_ = candidate;
  }
}

}  // namespace mospec
