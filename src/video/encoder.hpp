// Encoding frames into a video file through Debian's ffmpeg: raw RGB frames
// are piped to an `ffmpeg` process (started with posix_spawn, no shell; its
// argument vector is built here, so the output path is never parsed by a
// shell or by ffmpeg's protocol syntax). The video goes to a temporary file
// beside the target, which is renamed over it only when ffmpeg exits with
// status 0: a failed or abandoned encoding leaves no half-written video.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <span>
#include <string>

#include "video/renderer.hpp"

namespace mospec::video {

enum class VideoFormat {
  Mp4,  // H.264 (libx264), yuv420p: plays everywhere
  Gif,  // 256 colours (the first frame's), looping
};

// The format a file name asks for by its extension (.mp4 or .gif, any case).
// Throws mospec::Error("video") for any other, naming the accepted ones.
VideoFormat video_format(const std::string& path);

// The ffmpeg binary: $MOSPEC_FFMPEG when set (a path), else `ffmpeg` on PATH.
std::string ffmpeg_program();

class Encoder {
 public:
  // Creates the temporary file beside `path` and starts ffmpeg writing to it,
  // `fps` frames per second of `size`. Throws mospec::Error("video") when the
  // extension is unknown, a side is odd (H.264's colour subsampling), `path`
  // is a directory, the temporary cannot be created (the message names the
  // directory and the reason), or ffmpeg cannot be started (the message says
  // to install Debian's ffmpeg package or set MOSPEC_FFMPEG).
  Encoder(const std::string& path, FrameSize size, int fps);
  // Without finish(): stops ffmpeg and removes the temporary file.
  ~Encoder();
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  // Sends one frame: width * height * 3 bytes, RGB, top row first. Throws
  // mospec::Error("video") when ffmpeg has stopped reading (it failed).
  void write(std::span<const std::uint8_t> rgb);
  // Closes the stream, waits for ffmpeg and renames the temporary over the
  // target. Throws mospec::Error("video") when ffmpeg failed (its exit status;
  // its own message precedes on standard error) or the rename fails; the
  // temporary is removed then.
  void finish();

  std::uint64_t frames() const noexcept { return frames_; }

 private:
  void abandon() noexcept;
  int wait_child() noexcept;  // ffmpeg's wait status

  std::string path_, temporary_;
  FrameSize size_;
  pid_t child_ = -1;
  int pipe_ = -1;  // write end of ffmpeg's standard input
  std::uint64_t frames_ = 0;
  bool finished_ = false;
};

}  // namespace mospec::video
