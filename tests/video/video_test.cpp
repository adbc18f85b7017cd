// The video's frames (src/video): MuJoCo rendering offscreen in an OSMesa
// context. Frames are sampled at 30 per simulated second, are the same for
// the same run, show something (not a blank image), change as the robot
// moves, and rendering leaves the simulated world untouched.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "sim_test_util.hpp"
#include "support/diagnostics.hpp"
#include "video/encoder.hpp"
#include "video/recorder.hpp"
#include "video/renderer.hpp"

namespace mospec::video {
namespace {

using Frame = std::vector<std::uint8_t>;

constexpr FrameSize kSmall{160, 120};

// The frames of `seconds` of the default world, the base pushed forward and
// turned while the arms hold themselves up; `world_out` gets the final qpos.
std::vector<Frame> film(const runtime::Chain& arm, double seconds,
                        std::vector<double>* qpos_out = nullptr, bool render = true,
                        Camera camera = Camera::Corner) {
  const sim::WorldConfig c = sim::testing::test_world();
  sim::World world(c, arm);
  sim::GravityCompensation arms(arm, sim::testing::mounts(c));
  sim::PlatformWrenchDriver drives(c.drives);
  drives.F_p = runtime::Vec3(60, 0, 6);
  std::vector<Frame> frames;
  VideoOptions options;
  options.size = kSmall;
  options.camera = camera;
  std::unique_ptr<FrameSampler> sampler;
  if (render) {
    sampler = std::make_unique<FrameSampler>(world, options);
    sampler->on_frame([&frames](const Frame& f) { frames.push_back(f); });
    sampler->observe(world);
  }
  const int ticks = static_cast<int>(seconds / c.control_period + 0.5);
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  for (int k = 0; k < ticks; ++k) {
    world.read(s);
    arms.compute(s, cmd);
    drives.compute(s, cmd);
    world.write(cmd);
    world.step();
    if (sampler) sampler->observe(world);
  }
  if (qpos_out != nullptr) {
    const mjModel* m = world.mj_model();
    qpos_out->assign(world.mj_data()->qpos, world.mj_data()->qpos + m->nq);
  }
  return frames;
}

// The variance of the frame's grey levels (0..255).
double grey_variance(const Frame& f) {
  double sum = 0, sum2 = 0;
  const size_t n = f.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    const double y = (f[3 * i] + f[3 * i + 1] + f[3 * i + 2]) / 3.0;
    sum += y;
    sum2 += y * y;
  }
  const double mean = sum / static_cast<double>(n);
  return sum2 / static_cast<double>(n) - mean * mean;
}

// The fraction of pixels that differ between two frames by more than a few
// grey levels.
double changed_fraction(const Frame& a, const Frame& b) {
  size_t changed = 0;
  for (size_t i = 0; i < a.size(); i += 3) {
    int d = 0;
    for (size_t k = 0; k < 3; ++k) d += std::abs(int{a[i + k]} - int{b[i + k]});
    changed += d > 12 ? 1 : 0;
  }
  return static_cast<double>(changed) / static_cast<double>(a.size() / 3);
}

TEST(Video, ThirtyFramesPerSimulatedSecondFromTheInitialState) {
  NEED_GEN3();
  const std::vector<Frame> frames = film(arm_chain, 1.0);
  // t = 0, 1/30, …, 30/30.
  ASSERT_EQ(frames.size(), 31u);
  for (const Frame& f : frames) EXPECT_EQ(f.size(), 160u * 120u * 3u);
}

TEST(Video, TheSameRunGivesTheSameFrames) {
  NEED_GEN3();
  const std::vector<Frame> a = film(arm_chain, 0.5);
  const std::vector<Frame> b = film(arm_chain, 0.5);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k] == b[k]) << "frame " << k << " differs";
}

TEST(Video, FramesAreNotBlankAndFollowTheRobot) {
  NEED_GEN3();
  const std::vector<Frame> frames = film(arm_chain, 1.0);
  ASSERT_GE(frames.size(), 2u);
  // The robot and the table on the floor: far from one flat colour.
  EXPECT_GT(grey_variance(frames.front()), 100.0);
  EXPECT_GT(grey_variance(frames.back()), 100.0);
  // The base drove and turned for a second: much of the picture changed.
  EXPECT_GT(changed_fraction(frames.front(), frames.back()), 0.02);
}

TEST(Video, TheTopCameraSeesTheRobotFromAbove) {
  NEED_GEN3();
  const std::vector<Frame> top = film(arm_chain, 1.0, nullptr, true, Camera::Top);
  const std::vector<Frame> corner = film(arm_chain, 0.0);
  ASSERT_EQ(top.size(), 31u);
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_GT(grey_variance(top.front()), 100.0);
  EXPECT_GT(changed_fraction(top.front(), corner.front()), 0.2) << "another view";
  EXPECT_GT(changed_fraction(top.front(), top.back()), 0.02) << "the base drove and turned";
  Camera c = Camera::Corner;
  EXPECT_TRUE(parse_camera("top", c));
  EXPECT_EQ(c, Camera::Top);
  EXPECT_STREQ(camera_name(c), "top");
  EXPECT_FALSE(parse_camera("side", c));
}

TEST(Video, RenderingLeavesTheWorldAlone) {
  NEED_GEN3();
  std::vector<double> rendered, plain;
  (void)film(arm_chain, 0.3, &rendered, true);
  (void)film(arm_chain, 0.3, &plain, false);
  ASSERT_EQ(rendered.size(), plain.size());
  EXPECT_EQ(std::memcmp(rendered.data(), plain.data(), rendered.size() * sizeof(double)), 0);
}

TEST(Video, TheCameraFramesTheRobotAndTheTable) {
  NEED_GEN3();
  const sim::World world(sim::testing::test_world(), arm_chain);
  const mjModel* m = world.mj_model();
  const int robot = m->body_rootid[mj_name2id(m, mjOBJ_BODY, "platform")];
  const CameraView all = frame_geoms(m, world.mj_data(), -1, 0.0, 30.0, -30.0, 4.0 / 3.0);
  const CameraView v = frame_geoms(m, world.mj_data(), robot, 0.5, 30.0, -30.0, 4.0 / 3.0);
  // Between the robot (x < 0) and the table (0 < x < depth), above the floor,
  // from a few metres; closer when only the table's part near the robot counts.
  const sim::WorldConfig c = sim::testing::test_world();
  for (const CameraView& view : {all, v}) {
    EXPECT_GT(view.lookat[0], world.layout().base_x);
    EXPECT_LT(view.lookat[0], c.table.depth);
    EXPECT_GT(view.lookat[2], 0.0);
    EXPECT_GT(view.distance, 1.0);
    EXPECT_LT(view.distance, 10.0);
  }
  EXPECT_LT(v.distance, all.distance);
  EXPECT_LT(v.lookat[0], all.lookat[0]) << "nearer the robot";
}

TEST(Video, RefusesAnImpossibleFrameSize) {
  NEED_GEN3();
  const sim::World world(sim::testing::test_world(), arm_chain);
  try {
    Renderer r(world.mj_model(), {8, 5000});
    FAIL() << "a frame of 8x5000 was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "video");
    EXPECT_NE(std::string(e.what()).find("each side must be in [16, 4096]"), std::string::npos)
        << e.what();
  }
}

TEST(Video, KnowsItsFormatsByExtension) {
  EXPECT_EQ(video_format("a/run.mp4"), VideoFormat::Mp4);
  EXPECT_EQ(video_format("RUN.GIF"), VideoFormat::Gif);
  for (const char* bad : {"run.avi", "run", "mp4", "run.mp4.txt"}) {
    try {
      (void)video_format(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("name the file .mp4 (H.264) or .gif"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace mospec::video
