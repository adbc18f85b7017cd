// The generator's output: deterministic to the byte, constants that read back
// exactly, one commented block per IR step, atomic writes.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <set>

#include "codegen/codegen.hpp"
#include "programs.hpp"
#include "support/io.hpp"

namespace mospec::codegen {
namespace {

namespace fs = std::filesystem;

std::string file(const std::vector<GeneratedFile>& files, const std::string& path) {
  for (const GeneratedFile& f : files) {
    if (f.path == path) return f.content;
  }
  ADD_FAILURE() << "no " << path;
  return {};
}

TEST(Codegen, TheSameProgramGivesByteIdenticalFiles) {
  for (auto* make : {&testing::small_program, &testing::arm_program}) {
    SourceFiles files_a, files_b;
    const ir::Program a = make(files_a);
    const ir::Program b = make(files_b);
    ir::verify(a);
    const auto first = render(a, &files_a);
    const auto second = render(b, &files_b);
    ASSERT_EQ(first.size(), 3u);
    ASSERT_EQ(second.size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_EQ(first[i].path, second[i].path);
      EXPECT_EQ(first[i].content, second[i].content) << first[i].path;
    }
  }
}

TEST(Codegen, GeneratesTheThreeFilesOfTheProject) {
  SourceFiles files;
  const auto out = render(testing::small_program(files), &files);
  EXPECT_EQ(out[0].path, "CMakeLists.txt");
  EXPECT_EQ(out[1].path, "controller.hpp");
  EXPECT_EQ(out[2].path, "controller.cpp");
  const std::string cmake = file(out, "CMakeLists.txt");
  EXPECT_NE(cmake.find("find_package(mospec REQUIRED)"), std::string::npos);
  EXPECT_NE(cmake.find("add_library(mospec_controller SHARED controller.cpp)"), std::string::npos);
  EXPECT_NE(cmake.find("-Wall -Wextra -Werror"), std::string::npos);
}

// Every step is one block headed by its kind, name, IRI and file:line:col.
TEST(Codegen, EveryStepIsACommentedBlockInScheduleOrder) {
  SourceFiles files;
  const ir::Program p = testing::small_program(files);
  const std::string cpp = file(render(p, &files), "controller.cpp");
  std::size_t at = 0;
  for (std::size_t i = 0; i < p.steps.size(); ++i) {
    const ir::Step& st = p.steps[i];
    std::string head = "  // [";
    head.append(std::to_string(i)).append("] ").append(ir::kind_name(st)).append(" '");
    head.append(st.name).append("': ").append(st.iri).append(
        "\n  //     tests/codegen/programs.hpp:");
    head.append(std::to_string(st.where.line)).append(":5\n");
    const std::size_t found = cpp.find(head, at);
    ASSERT_NE(found, std::string::npos) << head;
    at = found + head.size();
  }
  EXPECT_NE(cpp.find("d.scalar[slot::v_time] = state.clock.t;"), std::string::npos);
  EXPECT_NE(cpp.find("rt::steps::pid(m.pid_pid_height, d.pid[0], d.scalar[slot::v_height_err], "
                     "state.clock.dt, d.flag[slot::v_approach]);"),
            std::string::npos);
  const std::string hpp = file(render(p, &files), "controller.hpp");
  EXPECT_NE(hpp.find("inline constexpr std::size_t v_height_err = "), std::string::npos);
  EXPECT_NE(hpp.find("std::array<double, 14> scalar{};"), std::string::npos);
}

TEST(Codegen, TheArmIsRebuiltFromItsSegmentConstants) {
  SourceFiles files;
  const ir::Program p = testing::arm_program(files);
  const std::string cpp = file(render(p, &files), "controller.cpp");
  EXPECT_NE(cpp.find("rt::AchdModel model_right_arm(const rt::Vec3& g_B, bool at_tip) {"),
            std::string::npos);
  std::size_t segments = 0;
  for (std::size_t at = cpp.find("chain.add_segment("); at != std::string::npos;
       at = cpp.find("chain.add_segment(", at + 1)) {
    ++segments;
  }
  EXPECT_EQ(segments, 7u);
  EXPECT_NE(cpp.find("rt::steps::arm_solve(m.task_right_arm, m.arm_right_arm, d.arm_right_arm, "
                     "d.ws_right_arm, command.arm_tau[0]);"),
            std::string::npos);
}

// The text is printf's "%.17g" (plus ".0" when that reads as an integer),
// whatever writes it: generated sources stay byte-identical.
TEST(Codegen, NumbersArePrintfsSeventeenDigits) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const std::uint64_t bits = rng();
    double v = 0;
    std::memcpy(&v, &bits, sizeof v);
    if (!std::isfinite(v)) continue;
    if (i % 2 == 0) v = std::ldexp(static_cast<double>(bits % 100000), -static_cast<int>(i % 20));
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    std::string expected = buf;
    if (expected.find_first_of(".e") == std::string::npos) expected += ".0";
    ASSERT_EQ(cpp_double(v), expected);
  }
}

TEST(Codegen, NumbersReadBackExactly) {
  for (double v : {0.1, 1.0 / 3.0, -0.0, 0.0, 1.0, -2.5e-7, 6.02214076e23, 1e300, 5e-324,
                   std::numeric_limits<double>::max()}) {
    const std::string s = cpp_double(v);
    const double back = std::strtod(s.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&back, &v, sizeof v), 0) << s;
    EXPECT_NE(s.find_first_of(".e"), std::string::npos) << s << " must read as a double";
  }
  EXPECT_EQ(cpp_double(1.0), "1.0");
  EXPECT_EQ(cpp_double(-0.0), "-0.0");
  EXPECT_EQ(cpp_double(std::numeric_limits<double>::infinity()),
            "std::numeric_limits<double>::infinity()");
  EXPECT_EQ(cpp_double(-std::numeric_limits<double>::infinity()),
            "-std::numeric_limits<double>::infinity()");
}

TEST(Codegen, StringsAreEscaped) {
  EXPECT_EQ(cpp_string("a\"b\\c"), R"("a\"b\\c")");
  EXPECT_EQ(cpp_string("line\nnext"), R"("line\012next")");
  EXPECT_EQ(cpp_string("?\?="), R"("\077\077=")");
}

TEST(Codegen, StringsHoldNoByteOutsideAscii) {
  // A lone U+202E (a bidi control) in a literal: the same bytes, escaped.
  EXPECT_EQ(cpp_string("a\xE2\x80\xAE"
                       "b"),
            R"("a\342\200\256b")");
}

TEST(Codegen, CommentsCannotEndSpliceOrHide) {
  EXPECT_EQ(comment_text("plain https://x/y#z (1) ?"), "plain https://x/y#z (1) ?");
  EXPECT_EQ(comment_text("a\nb\rc"), R"(a\x0Ab\x0Dc)");
  EXPECT_EQ(comment_text("ends with \\"), R"(ends with \x5C)");
  EXPECT_EQ(comment_text("?\?/"), R"(\x3F?/)");
  EXPECT_EQ(comment_text("?\?\?="), R"(\x3F\x3F?=)");
  EXPECT_EQ(comment_text("a*/b/*c"), R"(a\x2A/b\x2F*c)");
  EXPECT_EQ(comment_text("\xE2\x80\xAE"), R"(\u202E)");
  EXPECT_EQ(comment_text("caf\xC3\xA9 \xF0\x9F\x98\x80"), R"(caf\u00E9 \U0001F600)");
  EXPECT_EQ(comment_text("bad \xC3 \xFF \xE2\x80"), R"(bad \xC3 \xFF \xE2\x80)");
  EXPECT_EQ(comment_text("\xC0\xAF"), R"(\xC0\xAF)");          // overlong '/'
  EXPECT_EQ(comment_text("\xED\xA0\x80"), R"(\xED\xA0\x80)");  // a surrogate
}

// mangle() read backwards: the test's proof that it is injective.
std::optional<std::string> unmangle(std::string_view role, std::string_view id) {
  if (id.substr(0, role.size() + 1) != std::string(role) + "_") return std::nullopt;
  id.remove_prefix(role.size() + 1);
  std::string out;
  const auto hex = [&](std::size_t at) -> std::optional<char> {
    if (at + 2 > id.size()) return std::nullopt;
    return static_cast<char>(std::stoi(std::string(id.substr(at, 2)), nullptr, 16));
  };
  for (std::size_t i = 0; i < id.size();) {
    if (i == 0 && id[0] == 'x') {
      auto c = hex(1);
      if (!c) return std::nullopt;
      out.push_back(*c);
      i = 3;
    } else if (id[i] == '_' && i + 1 < id.size() && id[i + 1] == 'x') {
      auto c = hex(i + 2);
      if (!c) return std::nullopt;
      out.push_back(*c);
      i += 4;
    } else {
      out.push_back(id[i]);
      ++i;
    }
  }
  return out;
}

bool is_safe_identifier(const std::string& id) {
  if (id.empty() || !std::islower(static_cast<unsigned char>(id[0]))) return false;
  for (const char c : id) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return id.find("__") == std::string::npos;
}

TEST(Mangle, IsInjectiveAndGivesSafeIdentifiers) {
  std::vector<std::string> names{
      "",     "a",     "x",        "_",        "__",     "_x",           "x_",
      "x5F",  "_x5F",  "a_b",      "a__b",     "a_x",    "a_x5Fb",       "a-b",
      "a.b",  "a_",    "a_B",      "_Capital", "errno",  "assert",       "NULL",
      "EOF",  "stdin", "INFINITY", "unix",     "linux",  "class",        "int",
      "?\?/", "r",     "r_task",   "r_X_BR",   "9lives", "\xE2\x80\xAE", "a b",
      "x78",  "xx",    "_xx",      "a\nb"};
  std::set<std::string> ids;
  for (const std::string& n : names) {
    const std::string id = mangle("v", n);
    EXPECT_TRUE(is_safe_identifier(id)) << "'" << n << "' -> " << id;
    EXPECT_EQ(unmangle("v", id), n) << id;
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), names.size());
  // Every byte, alone and between letters.
  for (int b = 0; b < 256; ++b) {
    const std::string byte(1, static_cast<char>(b));
    std::string between = "a";
    between.append(byte).append("b");
    std::string last = "q";
    last.append(byte);
    for (const std::string& n : {byte, between, last}) {
      const std::string id = mangle("arm", n);
      EXPECT_TRUE(is_safe_identifier(id)) << b << " -> " << id;
      EXPECT_EQ(unmangle("arm", id), n) << id;
    }
  }
  EXPECT_EQ(mangle("v", "height_err"), "v_height_err");
  EXPECT_EQ(mangle("v", "errno"), "v_errno");
  EXPECT_EQ(mangle("v", "?\?/"), "v_x3F_x3F_x2F");
}

// Names, IRIs, units and file names that are hostile to C++: only mangled
// identifiers, escaped comments and escaped literals reach the files.
TEST(Codegen, HostileNamesReachTheFilesOnlyMangledOrEscaped) {
  SourceFiles files;
  const ir::Program p = testing::hostile_program(files);
  ir::verify(p);
  const auto out = render(p, &files);
  const std::vector<std::string> raw{"errno",    "assert", "NULL",  "EOF",    "stdin",
                                     "INFINITY", "unix",   "linux", "switch", "__x"};
  for (const GeneratedFile& f : out) {
    for (std::size_t i = 0; i < f.content.size(); ++i) {
      const auto u = static_cast<unsigned char>(f.content[i]);
      ASSERT_TRUE(u == '\n' || (u >= 0x20 && u < 0x7f))
          << f.path << ": byte " << int(u) << " at " << i;
    }
    EXPECT_EQ(f.content.find("??"), std::string::npos) << f.path;
    EXPECT_EQ(f.content.find("\n#error"), std::string::npos) << f.path;
    // Line by line: the code outside comments and string literals names no
    // model text as it is.
    std::size_t at = 0;
    while (at < f.content.size()) {
      std::size_t end = f.content.find('\n', at);
      if (end == std::string::npos) end = f.content.size();
      std::string line = f.content.substr(at, end - at);
      at = end + 1;
      EXPECT_TRUE(line.empty() || line.back() != '\\') << f.path << ": a line splice: " << line;
      std::string code;
      bool in_string = false;
      for (std::size_t k = 0; k < line.size(); ++k) {
        if (in_string) {
          if (line[k] == '\\')
            ++k;
          else if (line[k] == '"')
            in_string = false;
          continue;
        }
        if (line[k] == '"') {
          in_string = true;
          code.push_back(' ');
          continue;
        }
        if (line.compare(k, 2, "//") == 0 || (f.path == "CMakeLists.txt" && line[k] == '#')) {
          const std::string text = line.substr(k + 1);
          EXPECT_EQ(text.find("*/"), std::string::npos) << f.path << ": " << line;
          EXPECT_EQ(text.find("/*"), std::string::npos) << f.path << ": " << line;
          break;
        }
        code.push_back(line[k]);
      }
      for (const std::string& r : raw) {
        for (std::size_t hit = code.find(r); hit != std::string::npos;
             hit = code.find(r, hit + 1)) {
          const bool starts =
              hit == 0 ||
              !(std::isalnum(static_cast<unsigned char>(code[hit - 1])) || code[hit - 1] == '_');
          const std::size_t after = hit + r.size();
          const bool ends =
              after >= code.size() ||
              !(std::isalnum(static_cast<unsigned char>(code[after])) || code[after] == '_');
          EXPECT_FALSE(starts && ends) << f.path << ": '" << r << "' as a token in: " << line;
        }
      }
    }
  }
  const std::string hpp = file(out, "controller.hpp");
  const std::string cpp = file(out, "controller.cpp");
  EXPECT_NE(hpp.find("inline constexpr std::size_t v_errno = "), std::string::npos);
  EXPECT_NE(hpp.find("inline constexpr std::size_t v_x3F_x3F_x2F = "), std::string::npos);
  EXPECT_NE(hpp.find("rt::ConstraintEvaluator eval_xE2_x80_xAE;"), std::string::npos);
  // The two solvers that once collided (arm_r_task): distinct members now.
  EXPECT_NE(hpp.find("rt::AchdModel task_r;"), std::string::npos);
  EXPECT_NE(hpp.find("rt::AchdModel arm_r_task;"), std::string::npos);
  EXPECT_NE(cpp.find("rt::steps::arm_solve(m.task_r_task, m.arm_r_task, d.arm_r_task, "
                     "d.ws_r_task, command.arm_tau[1]);"),
            std::string::npos);
  // The comment of the step named U+202E, with its IRI's "*/", line break
  // and trailing backslash escaped.
  EXPECT_NE(
      cpp.find("  // [1] evaluate '\\u202E': https://mospec.example/tests/codegen/\\u202E\\x2A/"
               "\\x0A#error injected\\x5C\n"),
      std::string::npos);
}

// Two entities of one role with the same name: an error naming both, located.
TEST(Codegen, ANameCollisionIsAnErrorNamingBothEntities) {
  SourceFiles files;
  ir::Program p = testing::hostile_program(files);
  p.arms[1].name = p.arms[0].name;
  p.arms[1].iri = "https://mospec.example/tests/codegen/r-2";
  try {
    render(p, &files);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "codegen-name-collision");
    const std::string what = e.what();
    EXPECT_EQ(
        what.rfind("tests/codegen/programs.hpp:201:1: error: codegen: the arm solvers "
                   "'https://mospec.example/tests/codegen/r' (tests/codegen/programs.hpp:200:1) "
                   "and 'https://mospec.example/tests/codegen/r-2' share the name 'r', so both "
                   "would be the C++ 'arm_r'",
                   0),
        0u)
        << what;
  }
  SourceFiles files2;
  ir::Program q = testing::small_program(files2);
  q.data[1].name = q.data[0].name;
  try {
    render(q, &files2);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "codegen-name-collision");
    EXPECT_NE(std::string(e.what()).find("the data 'https://mospec.example/tests/codegen/time'"),
              std::string::npos)
        << e.what();
  }
}

// Codegen trusts a verified program: render() runs ir::verify first, so a bad
// program is refused with every problem, each naming its step and location.
TEST(Codegen, AnUnverifiedProgramIsRefusedWithEveryProblemLocated) {
  SourceFiles files;
  ir::Program p = testing::small_program(files);
  p.steps[2].in[0] = 999;
  p.steps[3].views = {9};
  try {
    render(p, &files);
    ADD_FAILURE() << "no error";
  } catch (const ir::VerifyError& e) {
    EXPECT_EQ(e.code(), "ir-invalid");
    ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
    EXPECT_NE(e.diagnostics()[0].message.find("'" + p.steps[2].name + "'"), std::string::npos);
    EXPECT_NE(e.diagnostics()[0].message.find("datum 999 (which does not exist)"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(e.diagnostics()[0].file, "tests/codegen/programs.hpp");
    EXPECT_EQ(e.diagnostics()[0].line, p.steps[2].where.line);
    EXPECT_NE(e.diagnostics()[1].message.find("view component 9 is out of range; expected 0..5"),
              std::string::npos)
        << e.what();
  }
}

TEST(Codegen, GenerateWritesTheProjectAndOverwritesItWhole) {
  const fs::path dir = fs::temp_directory_path() / ("mospec-codegen-" + std::to_string(getpid()));
  fs::remove_all(dir);
  SourceFiles files;
  const ir::Program p = testing::small_program(files);
  generate(p, (dir / "nested").string(), &files);
  for (const GeneratedFile& f : render(p, &files)) {
    EXPECT_EQ(read_file((dir / "nested" / f.path).string()), f.content);
  }
  write_output((dir / "nested" / "controller.cpp").string(), "stale");
  generate(p, (dir / "nested").string(), &files);
  EXPECT_EQ(read_file((dir / "nested" / "controller.cpp").string()),
            file(render(p, &files), "controller.cpp"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "nested")) ++entries;
  EXPECT_EQ(entries, 3u) << "no temporary files left behind";
  // A file where the directory should be: an io error naming the path.
  write_output((dir / "file").string(), "x");
  try {
    generate(p, (dir / "file" / "sub").string(), &files);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "io");
    EXPECT_NE(std::string(e.what()).find((dir / "file" / "sub").string()), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mospec::codegen
