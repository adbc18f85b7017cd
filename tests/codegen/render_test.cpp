// The generator's output: deterministic to the byte, constants that read back
// exactly, one commented block per IR step, atomic writes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>

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
    head.append(std::to_string(i)).append("] ").append(ir::to_string(st.kind)).append(" '");
    head.append(st.name).append("': ").append(st.iri).append(
        "\n  //     tests/codegen/programs.hpp:");
    head.append(std::to_string(st.where.line)).append(":5\n");
    const std::size_t found = cpp.find(head, at);
    ASSERT_NE(found, std::string::npos) << head;
    at = found + head.size();
  }
  EXPECT_NE(cpp.find("d.scalar[slot::time] = state.clock.t;"), std::string::npos);
  EXPECT_NE(cpp.find("rt::steps::pid(m.pid_height, d.pid[0], d.scalar[slot::height_err], "
                     "state.clock.dt, d.flag[slot::approach]);"),
            std::string::npos);
  const std::string hpp = file(render(p, &files), "controller.hpp");
  EXPECT_NE(hpp.find("inline constexpr std::size_t height_err = "), std::string::npos);
  EXPECT_NE(hpp.find("std::array<double, 13> scalar{};"), std::string::npos);
}

TEST(Codegen, TheArmIsRebuiltFromItsSegmentConstants) {
  SourceFiles files;
  const ir::Program p = testing::arm_program(files);
  const std::string cpp = file(render(p, &files), "controller.cpp");
  EXPECT_NE(cpp.find("rt::AchdModel arm_right_arm_model(const rt::Vec3& g_B) {"),
            std::string::npos);
  std::size_t segments = 0;
  for (std::size_t at = cpp.find("chain.add_segment("); at != std::string::npos;
       at = cpp.find("chain.add_segment(", at + 1)) {
    ++segments;
  }
  EXPECT_EQ(segments, 7u);
  EXPECT_NE(cpp.find("rt::steps::arm_solve(m.arm_right_arm_task, m.arm_right_arm, d.arm_right_arm, "
                     "d.ws_right_arm, command.arm_tau[0]);"),
            std::string::npos);
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

// Names that are no C++ identifier, or already taken, fall back to the type and slot.
TEST(Codegen, UnusableNamesFallBackToTheSlot) {
  SourceFiles files;
  ir::Program p = testing::small_program(files);
  p.data[0].name = "class";   // a keyword
  p.data[1].name = "height";  // the scalar named so later falls back
  const std::string hpp = file(render(p, &files), "controller.hpp");
  EXPECT_NE(hpp.find("inline constexpr std::size_t scalar_0 = 0;"), std::string::npos);
  EXPECT_NE(hpp.find("inline constexpr std::size_t height = 0;"), std::string::npos);
  EXPECT_NE(hpp.find("inline constexpr std::size_t scalar_1 = 1;"), std::string::npos);
}

TEST(Codegen, ABadReferenceIsAnErrorNamingTheStep) {
  SourceFiles files;
  ir::Program p = testing::small_program(files);
  p.steps[2].in[0] = 999;
  try {
    render(p, &files);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "codegen");
    EXPECT_NE(std::string(e.what()).find("reference to datum 999"), std::string::npos) << e.what();
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
