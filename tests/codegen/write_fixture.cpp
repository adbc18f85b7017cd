// codegen_write_fixture small|arm|empty|hostile|operators DIR: generates the project of one of the
// hand-built test programs (programs.hpp) into DIR, for build_test.sh.
#include <iostream>

#include "codegen/codegen.hpp"
#include "programs.hpp"

int main(int argc, char** argv) {
  using namespace mospec;
  if (argc != 3) {
    std::cerr << "usage: codegen_write_fixture small|arm|empty|hostile|operators DIR\n";
    return 2;
  }
  try {
    SourceFiles files;
    const std::string which = argv[1];
    const ir::Program program = which == "arm"         ? codegen::testing::arm_program(files)
                                : which == "empty"     ? codegen::testing::empty_program(files)
                                : which == "hostile"   ? codegen::testing::hostile_program(files)
                                : which == "operators" ? codegen::testing::operators_program(files)
                                                       : codegen::testing::small_program(files);
    ir::verify(program);
    codegen::generate(program, argv[2], &files);
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return 1;
  }
  return 0;
}
