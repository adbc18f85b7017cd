#include "plot/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "support/diagnostics.hpp"

extern char** environ;

namespace mospec::plot {

namespace {

std::string system_error(std::string_view what, int error) {
  std::string message(what);
  message.append(": ").append(std::strerror(error));
  return message;
}

std::vector<char*> c_argv(const std::vector<std::string>& argv) {
  std::vector<char*> out;
  out.reserve(argv.size() + 1);
  for (const std::string& a : argv) out.push_back(const_cast<char*>(a.c_str()));
  out.push_back(nullptr);
  return out;
}

ChildExit decode(pid_t pid, int status) {
  ChildExit e;
  e.pid = pid;
  if (WIFEXITED(status)) {
    e.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    e.signal = WTERMSIG(status);
  }
  return e;
}

ChildExit wait_for(pid_t pid) {
  int status = 0;
  for (;;) {
    const pid_t got = ::waitpid(pid, &status, 0);
    if (got == pid) return decode(pid, status);
    if (got < 0 && errno != EINTR) throw Error("io", system_error("waitpid", errno));
  }
}

// Owns a file descriptor.
struct Fd {
  int fd = -1;
  explicit Fd(int f = -1) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

// posix_spawn_file_actions_t with its destroy.
struct FileActions {
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&actions); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
  ~FileActions() { posix_spawn_file_actions_destroy(&actions); }
};

}  // namespace

std::string ChildExit::describe() const {
  if (exit_code >= 0) return "exited " + std::to_string(exit_code);
  std::string out = "killed by signal ";
  out.append(std::to_string(signal));
  if (const char* name = strsignal(signal)) out.append(" (").append(name).append(")");
  return out;
}

CapturedRun run_captured(const std::vector<std::string>& argv, std::string_view input,
                         const std::string& dir) {
  // The child's output goes to an anonymous temporary file, not a pipe, so a
  // chatty child can never block while we are still writing its stdin.
  std::FILE* out_file = std::tmpfile();
  if (out_file == nullptr) throw Error("io", system_error("cannot create a temporary file", errno));
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{out_file};
  int in_pipe[2];
  if (::pipe2(in_pipe, O_CLOEXEC) != 0) throw Error("io", system_error("pipe", errno));
  Fd in_read(in_pipe[0]), in_write(in_pipe[1]);

  FileActions fa;
  posix_spawn_file_actions_adddup2(&fa.actions, in_read.fd, STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&fa.actions, ::fileno(out_file), STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&fa.actions, ::fileno(out_file), STDERR_FILENO);
  if (!dir.empty()) posix_spawn_file_actions_addchdir_np(&fa.actions, dir.c_str());
  std::vector<char*> args = c_argv(argv);
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, args[0], &fa.actions, nullptr, args.data(), environ);
  in_read.reset();
  if (spawned != 0) {
    std::string message = "cannot run '";
    message.append(argv[0]).append("'");
    throw Error("not-found", system_error(message, spawned));
  }

  // A child that exits before reading all of its input must not kill us with
  // SIGPIPE: ignore it while writing (EPIPE is then an ordinary error).
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  size_t written = 0;
  while (written < input.size()) {
    const ssize_t n = ::write(in_write.fd, input.data() + written, input.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child stopped reading; its exit status tells why
    written += static_cast<size_t>(n);
  }
  in_write.reset();
  ::sigaction(SIGPIPE, &previous, nullptr);

  CapturedRun result;
  result.exit = wait_for(pid);
  std::rewind(out_file);
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, out_file)) > 0) result.output.append(buffer, n);
  return result;
}

pid_t spawn_logged(const std::vector<std::string>& argv, const std::string& log_path) {
  Fd log(::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644));
  if (log.fd < 0) {
    std::string message = "cannot write '";
    message.append(log_path).append("'");
    throw Error("io", system_error(message, errno));
  }
  FileActions fa;
  posix_spawn_file_actions_addopen(&fa.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&fa.actions, log.fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&fa.actions, log.fd, STDERR_FILENO);
  std::vector<char*> args = c_argv(argv);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, args[0], &fa.actions, nullptr, args.data(), environ);
  if (spawned != 0) {
    std::string message = "cannot run '";
    message.append(argv[0]).append("'");
    throw Error("io", system_error(message, spawned));
  }
  return pid;
}

ChildExit wait_any_child() {
  int status = 0;
  for (;;) {
    const pid_t got = ::waitpid(-1, &status, 0);
    if (got > 0) return decode(got, status);
    if (errno != EINTR) throw Error("io", system_error("waitpid", errno));
  }
}

std::string self_executable() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("io", system_error("cannot resolve /proc/self/exe", ec.value()));
  return p.string();
}

}  // namespace mospec::plot
