// The diagnostic catalogue (src/support/diagnostic_codes.hpp): each entry is
// emitted somewhere in src/, each one input can trigger has a test that
// triggers it and checks its code, and docs/diagnostics.md is the table
// rendered.
#include "support/diagnostic_codes.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "source_tree.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace fs = std::filesystem;
using mospec::CodeEntry;
using mospec::DiagnosticCode;
using mospec::kDiagnosticCodes;

namespace {

const fs::path kSource = MOSPEC_SOURCE_DIR;

struct File {
  std::string path;  // relative to the source tree
  std::string text;
};

std::vector<File> files_under(const fs::path& dir, const std::vector<std::string>& suffixes) {
  std::vector<File> out;
  for (const auto& e : fs::recursive_directory_iterator(kSource / dir)) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    for (const std::string& s : suffixes) {
      if (name.ends_with(s)) {
        out.push_back({fs::relative(e.path(), kSource).string(), mospec::test::slurp(e.path())});
        break;
      }
    }
  }
  return out;
}

// open + code + close, built by appending (GCC 12's -Wrestrict misfires on
// "literal" + std::string).
std::string wrapped(std::string_view open, std::string_view code, std::string_view close) {
  std::string out(open);
  out.append(code).append(close);
  return out;
}
std::string quoted(std::string_view code) {
  return wrapped("\"", code, "\"");
}

// Whether `text` spells `code` as a string literal where a test checks a code.
// A one-word code ("io", "build") is also an ordinary word, so it counts only on
// a line that names a code (`EXPECT_EQ(e.code(), "io")`); a longer one counts
// anywhere (a row of a table of cases the test checks one by one).
bool spelled_as_a_code(const std::string& text, std::string_view code) {
  const std::string literal = quoted(code);
  const bool one_word = code.find_first_of("- ") == std::string_view::npos;
  for (size_t at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1)) {
    if (!one_word) return true;
    const size_t begin = text.rfind('\n', at) + 1;  // npos + 1 == 0
    const size_t end = text.find('\n', at);
    if (text.substr(begin, end - begin).find("code") != std::string::npos) return true;
  }
  return false;
}

// The test that triggers each code and checks it, by the first that does:
//  - a diagnostic case (tests/ir/diagnostics/<case>/expected.txt) expecting
//    `error[CODE]`, `warning[CODE]` or `note[CODE]`;
//  - a C++ test that reads a diagnostic's code (`code()` or `.code`) and
//    spells CODE as a string literal;
//  - a shell test run with MOSPEC_DIAGNOSTIC_CODES=1 that expects `[CODE]:`.
std::map<std::string, std::string, std::less<>> tests_of_codes() {
  std::map<std::string, std::string, std::less<>> found;
  for (const File& f : files_under("tests/ir/diagnostics", {"expected.txt"})) {
    for (const CodeEntry& e : kDiagnosticCodes) {
      const std::string tag = wrapped("[", e.code, "]:");
      for (const char* sev : {"error", "warning", "note"}) {
        if (f.text.find(sev + tag) != std::string::npos)
          found.try_emplace(std::string(e.code), f.path);
      }
    }
  }
  for (const File& f : files_under("tests", {".cpp"})) {
    if (f.path.ends_with("diagnostic_codes_test.cpp")) continue;  // this file names them all
    if (f.text.find("code()") == std::string::npos && f.text.find(".code") == std::string::npos)
      continue;
    for (const CodeEntry& e : kDiagnosticCodes) {
      if (spelled_as_a_code(f.text, e.code)) found.try_emplace(std::string(e.code), f.path);
    }
  }
  // A shell test that has mospec write codes (MOSPEC_DIAGNOSTIC_CODES=1,
  // "error[CODE]: message") and expects one.
  for (const File& f : files_under("tests", {".sh"})) {
    if (f.text.find("MOSPEC_DIAGNOSTIC_CODES=1") == std::string::npos) continue;
    for (const CodeEntry& e : kDiagnosticCodes) {
      // Written out, or as a regular expression (`expect`'s pattern).
      const std::string tag = wrapped("[", e.code, "]:");
      const std::string pattern = wrapped("\\[", e.code, "\\]:");
      if (f.text.find(tag) != std::string::npos || f.text.find(pattern) != std::string::npos)
        found.try_emplace(std::string(e.code), f.path);
    }
  }
  return found;
}

TEST(DiagnosticCodes, EntriesAreUniqueAndSaySomethingOnOneLine) {
  std::set<std::string_view> seen;
  for (const CodeEntry& e : kDiagnosticCodes) {
    EXPECT_TRUE(seen.insert(e.code).second) << "[" << e.code << "] is listed twice";
    EXPECT_FALSE(e.meaning.empty()) << e.code;
    EXPECT_FALSE(e.stage.empty()) << e.code;
    EXPECT_EQ(e.meaning.find('\n'), std::string_view::npos) << e.code;
    EXPECT_EQ(e.meaning.find('|'), std::string_view::npos) << e.code << " (breaks the table)";
  }
  // Each stage is one group (one section of docs/diagnostics.md).
  std::set<std::string_view> stages;
  for (size_t i = 0; i < std::size(kDiagnosticCodes); ++i) {
    const std::string_view stage = kDiagnosticCodes[i].stage;
    if (i == 0 || kDiagnosticCodes[i - 1].stage != stage) {
      EXPECT_TRUE(stages.insert(stage).second)
          << "stage " << stage << " is split; [" << kDiagnosticCodes[i].code << "] belongs with it";
    }
  }
}

TEST(DiagnosticCodes, ACodeKnownOnlyAtRunTimeIsLookedUp) {
  const DiagnosticCode known = std::string("dropped-key");
  EXPECT_EQ(known.name(), "dropped-key");
  EXPECT_EQ(known.entry().severity, mospec::Severity::Warning);
  EXPECT_EQ(known, DiagnosticCode("dropped-key"));
  EXPECT_FALSE(known == DiagnosticCode("dropped-id"));
  EXPECT_EQ(DiagnosticCode::find("no-such-code"), nullptr);
  // A code the catalogue lacks is a bug in mospec, not in the input: it is
  // not a mospec::Error (exit 2) but an internal error (exit 3).
  try {
    mospec::Error e(std::string("no-such-code"), "message");
    FAIL() << "an unknown code was accepted";
  } catch (const mospec::Error&) {
    FAIL() << "an unknown code was taken for bad input";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'no-such-code' is not in the catalogue"),
              std::string::npos)
        << e.what();
  }
  // A default-made diagnostic has no code yet (and reads as empty).
  const mospec::Diagnostic d;
  EXPECT_TRUE(d.code.empty());
  EXPECT_EQ(std::string(d.code), "");
}

// Every entry is emitted: its code is spelled in src/ outside the catalogue
// (an entry nothing reports is stale; a code reported but not listed does not
// compile, or is an internal error when it is only known at run time).
TEST(DiagnosticCodes, EveryEntryHasAnEmissionSite) {
  std::vector<File> sources = files_under("src", {".cpp", ".hpp"});
  std::erase_if(sources, [](const File& f) { return f.path.ends_with("diagnostic_codes.hpp"); });
  for (const CodeEntry& e : kDiagnosticCodes) {
    const bool emitted = std::any_of(sources.begin(), sources.end(), [&](const File& f) {
      return f.text.find(quoted(e.code)) != std::string::npos;
    });
    EXPECT_TRUE(emitted) << "[" << e.code << "] is in the catalogue, but nothing in src/ spells it";
  }
}

// A test per entry: each code input can trigger has a test that triggers it
// and checks the code; an `internal` one (no input reaches it) needs none.
TEST(DiagnosticCodes, EveryEntryHasATest) {
  const auto found = tests_of_codes();
  std::string missing;
  size_t covered = 0;
  for (const CodeEntry& e : kDiagnosticCodes) {
    const bool has = found.find(e.code) != found.end();
    if (e.internal) {
      EXPECT_FALSE(has) << "[" << e.code << "] is marked internal, but "
                        << found.find(e.code)->second << " triggers it; it is not internal";
      continue;
    }
    if (has) {
      ++covered;
    } else {
      missing += wrapped("  [", e.code, "] (");
      missing.append(e.stage).append(")\n");
    }
  }
  EXPECT_TRUE(missing.empty()) << "no test triggers these codes and checks them (a diagnostic "
                                  "case under tests/ir/diagnostics/, or a test that compares "
                                  "the code; docs/testing.md):\n"
                               << missing;
  RecordProperty("covered", static_cast<int>(covered));
}

// Every code a diagnostic case expects is in the catalogue (a misspelt code
// would match nothing and the case could never pass).
TEST(DiagnosticCodes, DiagnosticCasesExpectCataloguedCodes) {
  for (const File& f : files_under("tests/ir/diagnostics", {"expected.txt"})) {
    for (const std::string_view severity : {": error[", ": warning[", ": note["}) {
      for (size_t at = f.text.find(severity); at != std::string::npos;
           at = f.text.find(severity, at + 1)) {
        const size_t open = at + severity.size();
        const size_t close = f.text.find("]:", open);
        if (close == std::string::npos) continue;
        const std::string code = f.text.substr(open, close - open);
        EXPECT_NE(DiagnosticCode::find(code), nullptr)
            << f.path << " expects [" << code << "], which is not in the catalogue";
      }
    }
  }
}

std::string render_markdown() {
  std::string out =
      "# Diagnostics\n\n"
      "Every diagnostic mospec reports has a stable code, listed here with the\n"
      "severity it is reported with and what it means. This page is the catalogue\n"
      "(`src/support/diagnostic_codes.hpp`) rendered: `support_diagnostic_codes_test`\n"
      "fails when the two differ, and writes the page it expects into its working\n"
      "directory. A code that is not in the catalogue does not compile.\n\n"
      "Messages do not show the code; `MOSPEC_DIAGNOSTIC_CODES=1` in the environment\n"
      "writes it after the severity, `FILE:LINE:COL: error[CODE]: message`, as the\n"
      "tests do (docs/testing.md), and `mospec explain CODE` prints its entry.\n"
      "`--run-diverging` reports `loop-sign` and `unstable-loop` as warnings and runs\n"
      "anyway.\n\n"
      "The JSON-LD codes are the\n"
      "[JSON-LD 1.1 API](https://www.w3.org/TR/json-ld11-api/#jsonlderrorcode)'s own.\n"
      "An *internal* code is one no input reaches: when it is reported, it is a bug\n"
      "in mospec or the machine failing under it (a missing program, a broken install).\n";
  std::string_view stage;
  for (const CodeEntry& e : kDiagnosticCodes) {
    if (e.stage != stage) {
      stage = e.stage;
      out.append("\n## ").append(stage).append(
          "\n\n| code | severity | meaning |\n|---|---|---|\n");
    }
    out.append("| `").append(e.code).append("` | ").append(mospec::to_string(e.severity));
    out.append(e.internal ? ", internal" : "").append(" | ").append(e.meaning).append(" |\n");
  }
  return out;
}

TEST(DiagnosticCodes, TheDocsListTheCatalogue) {
  const std::string expected = render_markdown();
  const std::string actual = mospec::test::slurp(kSource / "docs/diagnostics.md");
  if (actual != expected) {
    const fs::path written = fs::current_path() / "diagnostics.md";
    mospec::write_output(written.string(), expected);
    ADD_FAILURE() << "docs/diagnostics.md is not the catalogue rendered; the rendered page is "
                  << written << " (copy it over docs/diagnostics.md)";
  }
}

}  // namespace
