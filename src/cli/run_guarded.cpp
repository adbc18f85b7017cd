#include <exception>
#include <iostream>
#include <new>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {

int run_guarded(const Action& action) {
  try {
    return action();
  } catch (const mospec::Error& e) {
    std::cerr << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    // The machine's limit, not a bug: the input limits bound what a model may
    // ask for, and this is what is left.
    std::cerr << "mospec: error: out of memory\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "mospec: internal error: " << e.what()
              << " (a bug in mospec, not in the input; please report it with the input)\n";
    return kExitInternal;
  }
}

}  // namespace mospec::cli
