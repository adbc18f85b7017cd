// The exit codes of a command's action (cli::run_guarded): bad input 2, an
// internal error (a bug) 3, distinct, each with one line on stderr.
#include <gtest/gtest.h>

#include <iostream>
#include <new>
#include <sstream>
#include <stdexcept>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {
namespace {

// Runs `action` through run_guarded with stderr captured.
std::pair<int, std::string> guarded(const Action& action) {
  std::ostringstream err;
  std::streambuf* saved = std::cerr.rdbuf(err.rdbuf());
  const int code = run_guarded(action);
  std::cerr.rdbuf(saved);
  return {code, err.str()};
}

TEST(ExitCodes, ActionsReturnTheirOwnCode) {
  EXPECT_EQ(guarded([] { return kExitFindings; }).first, 1);
  EXPECT_EQ(guarded([] { return kExitOk; }).first, 0);
}

TEST(ExitCodes, BadInputIsTwo) {
  const auto [code, err] = guarded([]() -> int { throw Error("usage", "the model is bad"); });
  EXPECT_EQ(code, kExitBadInput);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("the model is bad"), std::string::npos) << err;
  EXPECT_EQ(err.find("internal error"), std::string::npos) << err;
}

TEST(ExitCodes, OutOfMemoryIsTwo) {
  const auto [code, err] = guarded([]() -> int { throw std::bad_alloc(); });
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err, "mospec: error: out of memory\n");
}

TEST(ExitCodes, AnythingElseIsAnInternalErrorThree) {
  const auto [code, err] = guarded([]() -> int { throw std::logic_error("an invariant broke"); });
  EXPECT_EQ(code, kExitInternal);
  EXPECT_EQ(code, 3);
  EXPECT_EQ(err.rfind("mospec: internal error: an invariant broke (a bug in mospec", 0), 0u) << err;
}

// A diagnostic code known only at run time that the catalogue lacks is a bug
// in mospec (src/support/diagnostic_codes.hpp), not bad input.
TEST(ExitCodes, ACodeOutsideTheCatalogueIsAnInternalError) {
  const auto [code, err] = guarded([]() -> int {
    const std::string computed = "no-such-code";
    throw Error(computed, "the model is bad");
  });
  EXPECT_EQ(code, kExitInternal);
  EXPECT_EQ(err.rfind("mospec: internal error: the diagnostic code 'no-such-code' is not in the "
                      "catalogue",
                      0),
            0u)
      << err;
}

}  // namespace
}  // namespace mospec::cli
