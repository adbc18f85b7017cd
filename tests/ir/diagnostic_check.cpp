// ir_diagnostic_check SOURCE_DIR CASE_DIR: runs one diagnostic case
// (tests/ir/diagnostic_cases.hpp) and prints what matched, what is missing and
// what was unexpected. Exit 0 when the diagnostics are exactly the expected
// ones, 1 when they differ, 2 on bad arguments.
#include <iostream>

#include "diagnostic_cases.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: ir_diagnostic_check SOURCE_DIR CASE_DIR\n";
    return 2;
  }
  const mospec::test::CaseResult r = mospec::test::check_case(argv[1], argv[2]);
  (r.ok ? std::cout : std::cerr) << r.report;
  return r.ok ? 0 : 1;
}
