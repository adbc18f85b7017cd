// The "did you mean" helper: distances, the typo limit, and a nearest choice
// that does not depend on the order candidates come in.
#include "support/spelling.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mospec {
namespace {

TEST(Spelling, EditDistanceAndItsLimit) {
  EXPECT_EQ(edit_distance("kitten", "sitting", 10), 3u);
  EXPECT_EQ(edit_distance("", "abc", 10), 3u);
  EXPECT_EQ(edit_distance("same", "same", 0), 0u);
  // Past the limit only "more than the limit" is promised.
  EXPECT_GT(edit_distance("kitten", "sitting", 2), 2u);
  EXPECT_GT(edit_distance("a", "abcdefgh", 3), 3u);
}

TEST(Spelling, NearestIsWithinATypoAndIndependentOfOrder) {
  const std::vector<std::string> terms = {"upper-threshold", "lower-threshold", "quantity",
                                          "reference-value"};
  for (int rotation = 0; rotation < 4; ++rotation) {
    Nearest n("lower-treshold");
    for (int k = 0; k < 4; ++k) n.offer(terms[static_cast<size_t>((k + rotation) % 4)]);
    EXPECT_EQ(n.best(), "lower-threshold");
  }
  Nearest far("gain");
  for (const std::string& t : terms) far.offer(t);
  EXPECT_EQ(far.best(), "");  // nothing is a plausible typo of it
  Nearest tie("abcd");
  tie.offer("xbcd");
  tie.offer("abcx");
  EXPECT_EQ(tie.best(), "abcx");  // equally near: the lexically smaller
  Nearest short_name("to");
  short_name.offer("tp");
  EXPECT_EQ(short_name.best(), "");  // too short to guess
  Nearest compound("AngleConstraint");
  compound.offer("ForceConstraint");
  EXPECT_EQ(compound.best(), "");  // four edits in fifteen letters: another word
  Nearest property("pose");
  property.offer("Pose");
  EXPECT_EQ(property.best(), "");  // a class is no typo of a property
  Nearest itself("quantity");
  itself.offer("quantity");
  EXPECT_EQ(itself.best(), "");  // a name is no suggestion for itself
}

}  // namespace
}  // namespace mospec
