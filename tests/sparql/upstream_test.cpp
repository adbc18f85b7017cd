#include <gtest/gtest.h>
TEST(SparqlUpstream, Placeholder) {}
