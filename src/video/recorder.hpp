// `mospec run --video FILE`: a video of the simulated run, sampled from the
// simulation's time (not the wall clock) at a fixed frame rate, rendered by
// MuJoCo offscreen (video/renderer.hpp) between control ticks and encoded by
// ffmpeg (video/encoder.hpp).
//
// Frame k shows the world as it is after the first tick that reaches
// t = k / fps (frame 0 is the initial state), so a run of D seconds has
// floor(D * fps) + 1 frames and the same run gives the same frames.
//
// The camera looks from a fixed direction (VideoOptions::camera) at the robot and the
// table around it: at each frame, at the centre of the box around the robot
// (the bodies of the platform's tree, sim/mjcf.hpp) and the nearby part of
// the table (video::frame_geoms), from the distance that fits them; the
// distance never shrinks during a run, so the view follows the robot without
// pumping.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/run.hpp"
#include "sim/world.hpp"
#include "video/encoder.hpp"
#include "video/renderer.hpp"

namespace mospec::video {

// The cameras `--video-camera` names: the direction the free camera looks
// from (W: x into the table, y left, z up).
enum class Camera {
  Corner,  // from behind the robot's right, 30 deg down: the arms, the table's edge and top
  Top,     // straight down: the base turning to the edge, the contacts sliding along it
};

// "corner" / "top", and back; parse_camera returns false for other names.
const char* camera_name(Camera camera) noexcept;
bool parse_camera(const std::string& name, Camera& camera) noexcept;

struct VideoOptions {
  FrameSize size{640, 480};
  int fps = 30;
  Camera camera = Camera::Corner;
  // How much of the table is framed around the robot, in robot sizes.
  double context = 0.5;
};

// Renders the world's frames at `options.fps` of simulated time. Usable
// without an encoder (tests read the frames: frame()).
class FrameSampler final : public sim::StepObserver {
 public:
  FrameSampler(const sim::World& world, const VideoOptions& options);
  // Renders every frame whose time the world has reached since the last call
  // and hands each to `on_frame` (when set).
  void observe(const sim::World& world) override;

  // The most recent frame (RGB, top row first); black before the first.
  const std::vector<std::uint8_t>& frame() const noexcept { return rgb_; }
  std::uint64_t frames() const noexcept { return next_; }
  // Wall time spent in observe(): rendering and on_frame [s].
  double busy_seconds() const noexcept { return busy_seconds_; }

  // Called with every frame rendered (e.g. Encoder::write).
  void on_frame(std::function<void(const std::vector<std::uint8_t>&)> f) {
    on_frame_ = std::move(f);
  }

 private:
  VideoOptions options_;
  Renderer renderer_;
  std::vector<std::uint8_t> rgb_;
  int robot_root_ = -1;  // the platform's tree (MuJoCo body id); -1: frame everything
  double distance_ = 0.0;
  std::uint64_t next_ = 0;  // the index of the next frame to render
  double busy_seconds_ = 0.0;
  std::function<void(const std::vector<std::uint8_t>&)> on_frame_;
};

// A FrameSampler feeding an Encoder: the whole of `--video FILE`. The
// constructor starts ffmpeg (and so fails, before the run, on a bad path,
// format or a missing ffmpeg); finish() completes the file.
class Recorder final : public sim::StepObserver {
 public:
  Recorder(const sim::World& world, const std::string& path, const VideoOptions& options);
  void observe(const sim::World& world) override { sampler_.observe(world); }
  void finish();

  std::uint64_t frames() const noexcept { return sampler_.frames(); }
  // Wall time spent rendering and encoding [s].
  double seconds() const noexcept { return seconds_ + sampler_.busy_seconds(); }

 private:
  Encoder encoder_;
  FrameSampler sampler_;
  double seconds_ = 0.0;  // in finish(): ffmpeg completing the file
};

}  // namespace mospec::video
