#include "video/encoder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "support/diagnostics.hpp"

extern char** environ;

namespace mospec::video {

namespace fs = std::filesystem;

namespace {

Error video_error(const std::string& message) {
  return Error("video", message);
}

// How ffmpeg ended, for a message.
std::string describe_status(int status) {
  if (WIFEXITED(status)) return "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "ffmpeg was killed by signal " + std::to_string(WTERMSIG(status));
  return "ffmpeg ended abnormally";
}

// The encoder's options after the raw input: H.264 in MP4, or a GIF with one
// 256-colour palette made from the first frame (the scene's colours do not
// change; a whole-video palette would hold every frame in memory, a palette
// per frame would defeat the GIF's frame-to-frame reuse and triple its size),
// each frame storing only the rectangle that changed.
std::vector<std::string> output_options(VideoFormat format) {
  if (format == VideoFormat::Mp4) {
    return {"-c:v",     "libx264", "-preset",   "medium",     "-crf", "23",
            "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f",   "mp4"};
  }
  return {"-vf",
          "split[a][b];[a]trim=end_frame=1,palettegen[p];"
          "[b][p]paletteuse=dither=bayer:bayer_scale=5:diff_mode=rectangle",
          "-loop",
          "0",
          "-f",
          "gif"};
}

// Blocks SIGPIPE in this thread while it lives: a write to a pipe whose reader
// died fails with EPIPE instead of killing mospec; a SIGPIPE raised meanwhile
// is consumed before the mask is restored.
class NoSigpipe {
 public:
  NoSigpipe() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~NoSigpipe() {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_, nullptr, &zero) > 0) {
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  NoSigpipe(const NoSigpipe&) = delete;
  NoSigpipe& operator=(const NoSigpipe&) = delete;

 private:
  sigset_t pipe_, old_;
};

}  // namespace

VideoFormat video_format(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".mp4") return VideoFormat::Mp4;
  if (ext == ".gif") return VideoFormat::Gif;
  throw video_error(
      "--video '" + path + "': " +
      (ext.empty() ? "the file name has no extension" : "unknown video format '" + ext + "'") +
      "; name the file .mp4 (H.264) or .gif");
}

std::string ffmpeg_program() {
  const char* p = std::getenv("MOSPEC_FFMPEG");
  return p != nullptr && *p != '\0' ? p : "ffmpeg";
}

Encoder::Encoder(const std::string& path, FrameSize size, int fps) : path_(path), size_(size) {
  const VideoFormat format = video_format(path);
  if (size.width % 2 != 0 || size.height % 2 != 0) {
    throw video_error("--video-size " + std::to_string(size.width) + "x" +
                      std::to_string(size.height) +
                      ": both sides must be even (H.264's colour subsampling)");
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
    throw video_error("cannot write the video '" + path + "': it is a directory");
  }
  // The temporary beside the target (the rename stays on one file system),
  // created exclusively under an unpredictable name.
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp.XXXXXX");
  std::string tmpl = (dir / name).string();
  const int fd = ::mkostemp(tmpl.data(), O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) {
    throw video_error("cannot write the video '" + path + "': " + std::strerror(errno) +
                      " (its directory '" + dir.string() + "' must exist and be writable)");
  }
  const mode_t mask = ::umask(022);
  ::umask(mask);
  const bool chmod_ok = ::fchmod(fd, 0666 & ~mask) == 0;
  ::close(fd);
  temporary_ = tmpl;
  if (!chmod_ok) {
    const int err = errno;
    ::unlink(temporary_.c_str());
    throw video_error("cannot write the video '" + path + "': " + std::strerror(err));
  }

  const std::string program = ffmpeg_program();
  std::vector<std::string> args = {
      program,       "-hide_banner",
      "-loglevel",   "error",
      "-nostdin",    "-y",
      "-f",          "rawvideo",
      "-pix_fmt",    "rgb24",
      "-video_size", std::to_string(size.width) + "x" + std::to_string(size.height),
      "-framerate",  std::to_string(fps),
      "-i",          "pipe:0"};
  for (std::string& o : output_options(format)) args.push_back(std::move(o));
  // "file:" so that ffmpeg reads no protocol or option out of the path.
  args.push_back("file:" + temporary_);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    const int err = errno;
    ::unlink(temporary_.c_str());
    throw video_error("cannot start ffmpeg: " + std::string(std::strerror(err)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, pipe_signal;
  sigemptyset(&none);
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &pipe_signal);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, program.c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    ::unlink(temporary_.c_str());
    throw video_error("--video needs ffmpeg, and '" + program + "' cannot be started (" +
                      std::strerror(rc) +
                      "): install Debian's ffmpeg package (scripts/install-deps) or set "
                      "MOSPEC_FFMPEG to its path");
  }
  child_ = pid;
  pipe_ = fds[1];
}

Encoder::~Encoder() {
  abandon();
}

int Encoder::wait_child() noexcept {
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0) {
    if (errno != EINTR) {
      status = -1;
      break;
    }
  }
  child_ = -1;
  return status;
}

void Encoder::abandon() noexcept {
  if (pipe_ >= 0) {
    ::close(pipe_);
    pipe_ = -1;
  }
  if (child_ > 0) {
    ::kill(child_, SIGKILL);
    (void)wait_child();
  }
  if (!finished_ && !temporary_.empty()) {
    ::unlink(temporary_.c_str());
    temporary_.clear();
  }
}

void Encoder::write(std::span<const std::uint8_t> rgb) {
  const size_t expected = static_cast<size_t>(size_.width) * static_cast<size_t>(size_.height) * 3;
  if (rgb.size() != expected) {
    throw video_error("a frame of " + std::to_string(rgb.size()) + " bytes (" +
                      std::to_string(expected) + " expected)");
  }
  if (pipe_ < 0) throw video_error("the video '" + path_ + "' is already closed");
  NoSigpipe guard;
  const std::uint8_t* p = rgb.data();
  size_t left = rgb.size();
  while (left > 0) {
    const ssize_t n = ::write(pipe_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(pipe_);
      pipe_ = -1;
      const std::string how =
          err == EPIPE ? describe_status(wait_child()) : std::string(std::strerror(err));
      abandon();
      throw video_error("encoding the video '" + path_ + "' failed: " + how +
                        " (its message is above); nothing was written");
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  ++frames_;
}

void Encoder::finish() {
  if (pipe_ < 0) throw video_error("the video '" + path_ + "' is already closed");
  ::close(pipe_);
  pipe_ = -1;
  const int status = wait_child();
  if (!(status >= 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    abandon();
    throw video_error("encoding the video '" + path_ + "' failed: " + describe_status(status) +
                      " (its message is above); nothing was written");
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    abandon();
    throw video_error("cannot write the video '" + path_ + "': " + std::strerror(err));
  }
  finished_ = true;
}

}  // namespace mospec::video
