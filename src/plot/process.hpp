// Child processes without a shell: argv goes to exec as is, so no path or
// title a user passes is ever interpreted. Used to drive gnuplot (a script on
// its stdin) and to run `mospec run` trials in parallel.
#pragma once

#include <sys/types.h>

#include <string>
#include <string_view>
#include <vector>

namespace mospec::plot {

// How a child ended: exit_code >= 0 when it exited, else signal > 0.
struct ChildExit {
  pid_t pid = -1;
  int exit_code = -1;
  int signal = 0;
  bool ok() const { return exit_code == 0; }
  std::string describe() const;  // "exited 0", "killed by signal 11 (Segmentation fault)"
};

struct CapturedRun {
  ChildExit exit;
  std::string output;  // the child's stdout and stderr, interleaved
};

// Runs argv (argv[0] searched on PATH when it has no '/') with `input` written
// to its stdin, in working directory `dir` (empty: ours), and waits for it.
// Throws mospec::Error code "not-found" when argv[0] cannot be executed (the
// message names it and the system's reason), "io" on pipe/temp-file failure.
CapturedRun run_captured(const std::vector<std::string>& argv, std::string_view input,
                         const std::string& dir = {});

// Starts argv[0] (an absolute or relative path, not searched) with stdin from
// /dev/null and stdout and stderr appended to `log_path` (created/truncated; a
// symbolic link there is refused, not followed).
// Throws mospec::Error code "io" when the log cannot be opened or the child
// cannot be started.
pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log_path);

// Waits for any child of this process to end (retrying on EINTR).
ChildExit wait_any_child();

// The absolute path of the running executable (/proc/self/exe).
std::string self_executable();

}  // namespace mospec::plot
