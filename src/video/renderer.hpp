// MuJoCo's own renderer, offscreen and headless: an OSMesa (software OpenGL)
// context made current on a buffer in memory, MuJoCo's offscreen framebuffer
// inside it, and no display, window or GPU. Frames are deterministic: the
// same state seen from the same view gives the same pixels.
//
// The renderer owns copies of the model (with its offscreen size) and of the
// state it draws, so rendering never writes to the simulated world.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

struct mjModel_;
struct mjData_;

namespace mospec::video {

// A frame's size in pixels.
struct FrameSize {
  int width = 640;
  int height = 480;
};

// A free camera: the point it looks at (in W [m]), its distance from it [m],
// and the direction it looks from: azimuth about +z from +x, elevation above
// the horizon (negative: looking down) [deg], as mjvCamera has them.
struct CameraView {
  std::array<double, 3> lookat{0.0, 0.0, 0.0};
  double distance = 1.0;
  double azimuth_deg = 0.0;
  double elevation_deg = 0.0;
};

// The view from (azimuth_deg, elevation_deg) that frames, at `data`'s
// current pose, the geoms of the kinematic tree rooted at `focus_root` (a
// body id: the robot; -1: every body) and the part of every other geom
// (the table) within `context` times the focus's size around it; planes (the
// floor) have no extent and are left out. It looks at the centre of that
// box, from the nearest distance at which all of the box's corners are
// inside a frame of `aspect` (width / height) under the model's vertical
// field of view (vis.global.fovy), with a 5% margin.
CameraView frame_geoms(const mjModel_* model, const mjData_* data, int focus_root, double context,
                       double azimuth_deg, double elevation_deg, double aspect);

class Renderer {
 public:
  // Creates the OSMesa context and MuJoCo's rendering context for `model`
  // (which must outlive the Renderer) at `size`. Throws mospec::Error
  // ("video") when the size is outside [16, 4096] or OSMesa or MuJoCo's
  // offscreen buffer cannot be created.
  Renderer(const mjModel_* model, FrameSize size);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  FrameSize size() const noexcept { return size_; }

  // Draws the state `data` (of the model given at construction) seen from
  // `view` into `rgb`: width * height * 3 bytes, RGB, the top row first.
  // Throws mospec::Error("video") when `rgb` has another size.
  void render(const mjData_* data, const CameraView& view, std::span<std::uint8_t> rgb);

 private:
  struct Impl;
  FrameSize size_;
  std::unique_ptr<Impl> impl_;
  std::vector<std::uint8_t> scratch_row_;
};

}  // namespace mospec::video
