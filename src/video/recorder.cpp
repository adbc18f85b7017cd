#include "video/recorder.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>

namespace mospec::video {

namespace {

// Azimuth and elevation [deg] (mjvCamera's): the direction the camera looks.
struct Direction {
  double azimuth_deg, elevation_deg;
};

Direction direction(Camera camera) {
  switch (camera) {
    case Camera::Top:
      // Straight down, the table's edge across the frame (x up the picture);
      // 89.9 keeps the camera's horizontal axis defined.
      return {0.0, -89.9};
    case Camera::Corner:
      break;
  }
  return {30.0, -30.0};
}

}  // namespace

const char* camera_name(Camera camera) noexcept {
  return camera == Camera::Top ? "top" : "corner";
}

bool parse_camera(const std::string& name, Camera& camera) noexcept {
  for (Camera c : {Camera::Corner, Camera::Top}) {
    if (name == camera_name(c)) {
      camera = c;
      return true;
    }
  }
  return false;
}

FrameSampler::FrameSampler(const sim::World& world, const VideoOptions& options)
    : options_(options),
      renderer_(world.mj_model(), options.size),
      rgb_(static_cast<size_t>(options.size.width) * static_cast<size_t>(options.size.height) * 3) {
  const mjModel* m = world.mj_model();
  const int platform = mj_name2id(m, mjOBJ_BODY, "platform");
  if (platform >= 0) robot_root_ = m->body_rootid[platform];
}

void FrameSampler::observe(const sim::World& world) {
  // A frame is due when the world's time reaches k / fps (to within a
  // nanosecond, so the float sum of the physics steps does not skip one).
  const double t = world.time();
  if (t + 1e-9 < static_cast<double>(next_) / options_.fps) return;
  const auto start = std::chrono::steady_clock::now();
  const double aspect = static_cast<double>(options_.size.width) / options_.size.height;
  const Direction from = direction(options_.camera);
  CameraView view = frame_geoms(world.mj_model(), world.mj_data(), robot_root_, options_.context,
                                from.azimuth_deg, from.elevation_deg, aspect);
  distance_ = std::max(distance_, view.distance);
  view.distance = distance_;
  renderer_.render(world.mj_data(), view, rgb_);
  // A world stepping slower than the frame rate shows its state in every
  // frame it reached.
  while (t + 1e-9 >= static_cast<double>(next_) / options_.fps) {
    ++next_;
    if (on_frame_) on_frame_(rgb_);
  }
  busy_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Recorder::Recorder(const sim::World& world, const std::string& path, const VideoOptions& options)
    : encoder_(path, options.size, options.fps), sampler_(world, options) {
  sampler_.on_frame([this](const std::vector<std::uint8_t>& rgb) { encoder_.write(rgb); });
}

void Recorder::finish() {
  const auto start = std::chrono::steady_clock::now();
  encoder_.finish();
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace mospec::video
