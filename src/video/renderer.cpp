#include "video/renderer.hpp"

#include <GL/osmesa.h>
#include <dlfcn.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "support/diagnostics.hpp"

// Under LeakSanitizer (the asan preset), Mesa's own 480 bytes per OSMesa
// context (allocated in OSMesaMakeCurrent, never freed by
// OSMesaDestroyContext) are not ours to fix; allocations made elsewhere are
// still reported. Never called in other builds.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}

namespace mospec::video {

namespace {

constexpr int kMinSide = 16;
constexpr int kMaxSide = 4096;

// OSMesa, loaded when the first video is rendered rather than linked: it
// pulls in LLVM (llvmpipe), whose loading would add tens of milliseconds to
// the start of every `mospec run`, `sim` and trial. RTLD_GLOBAL, because
// MuJoCo looks OpenGL's functions up through OSMesaGetProcAddress itself.
struct OsMesa {
  decltype(&::OSMesaCreateContextExt) create = nullptr;
  decltype(&::OSMesaMakeCurrent) make_current = nullptr;
  decltype(&::OSMesaDestroyContext) destroy = nullptr;
};

const OsMesa& osmesa() {
  static const OsMesa api = [] {
    constexpr const char* kLibrary = "libOSMesa.so.8";
    void* lib = ::dlopen(kLibrary, RTLD_NOW | RTLD_GLOBAL);
    if (lib == nullptr) {
      const char* why = ::dlerror();
      throw Error("video", std::string("--video renders with OSMesa, and ") + kLibrary +
                               " cannot be loaded (" + (why != nullptr ? why : "unknown reason") +
                               "): install Debian's libosmesa6 package (scripts/install-deps)");
    }
    OsMesa f;
    f.create = reinterpret_cast<decltype(f.create)>(::dlsym(lib, "OSMesaCreateContextExt"));
    f.make_current = reinterpret_cast<decltype(f.make_current)>(::dlsym(lib, "OSMesaMakeCurrent"));
    f.destroy = reinterpret_cast<decltype(f.destroy)>(::dlsym(lib, "OSMesaDestroyContext"));
    if (f.create == nullptr || f.make_current == nullptr || f.destroy == nullptr) {
      throw Error("video", std::string(kLibrary) + " lacks the OSMesa functions MuJoCo needs");
    }
    return f;
  }();
  return api;
}

// The world's models have no lights of their own: a sun high above the
// scene, slightly from the camera's side, casting shadows, beside MuJoCo's
// headlight.
void add_sun(mjvScene& scene, const CameraView& view) {
  if (scene.nlight >= mjMAXLIGHT) return;
  mjvLight& l = scene.lights[scene.nlight++];
  l = mjvLight{};
  const double az = view.azimuth_deg * std::numbers::pi / 180;
  const float dir[3] = {static_cast<float>(0.4 * std::cos(az)),
                        static_cast<float>(0.4 * std::sin(az) + 0.3), -1.0f};
  const float n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  for (int i = 0; i < 3; ++i) {
    l.dir[i] = dir[i] / n;
    l.pos[i] = static_cast<float>(view.lookat[static_cast<size_t>(i)]) - 5.0f * l.dir[i];
    l.ambient[i] = 0.1f;
    l.diffuse[i] = 0.6f;
    l.specular[i] = 0.2f;
  }
  l.attenuation[0] = 1.0f;
  l.cutoff = 180.0f;
  l.directional = 1;
  l.castshadow = 1;
}

using Box = std::array<std::array<double, 3>, 2>;  // lower and upper corner

// The world-aligned box around geom g: exact for boxes, its bounding sphere
// for the other shapes (the robot's small parts).
Box geom_box(const mjModel* m, const mjData* d, int g) {
  const mjtNum* R = d->geom_xmat + 9 * g;  // row-major, geom to world
  const mjtNum* size = m->geom_size + 3 * g;
  Box b{};
  for (size_t i = 0; i < 3; ++i) {
    double half = m->geom_rbound[g];
    if (m->geom_type[g] == mjGEOM_BOX) {
      half = 0.0;
      for (size_t j = 0; j < 3; ++j) half += std::abs(R[3 * i + j]) * size[j];
    }
    const double c = d->geom_xpos[3 * static_cast<size_t>(g) + i];
    b[0][i] = c - half;
    b[1][i] = c + half;
  }
  return b;
}

void grow(Box& b, const Box& by) {
  for (size_t i = 0; i < 3; ++i) {
    b[0][i] = std::min(b[0][i], by[0][i]);
    b[1][i] = std::max(b[1][i], by[1][i]);
  }
}

}  // namespace

CameraView frame_geoms(const mjModel* m, const mjData* d, int focus_root, double context,
                       double azimuth_deg, double elevation_deg, double aspect) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Box empty{{{inf, inf, inf}, {-inf, -inf, -inf}}};
  auto in_focus = [&](int g) {
    return focus_root < 0 || m->body_rootid[m->geom_bodyid[g]] == focus_root;
  };
  Box focus = empty;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_PLANE && in_focus(g)) grow(focus, geom_box(m, d, g));
  }
  if (!(focus[0][0] <= focus[1][0])) focus = Box{};  // nothing to focus on: the origin
  // The surroundings: what other geoms have within `context` times the focus's
  // largest side of it.
  double side = 0.0;
  for (size_t i = 0; i < 3; ++i) side = std::max(side, focus[1][i] - focus[0][i]);
  Box near = focus;
  for (size_t i = 0; i < 3; ++i) {
    near[0][i] -= context * side;
    near[1][i] += context * side;
  }
  Box lo_hi = focus;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] == mjGEOM_PLANE || in_focus(g)) continue;
    Box b = geom_box(m, d, g);
    bool overlaps = true;
    for (size_t i = 0; i < 3; ++i) {
      b[0][i] = std::max(b[0][i], near[0][i]);
      b[1][i] = std::min(b[1][i], near[1][i]);
      overlaps = overlaps && b[0][i] <= b[1][i];
    }
    if (overlaps) grow(lo_hi, b);
  }
  const std::array<double, 3>& lo = lo_hi[0];
  const std::array<double, 3>& hi = lo_hi[1];
  CameraView v;
  v.azimuth_deg = azimuth_deg;
  v.elevation_deg = elevation_deg;
  for (size_t i = 0; i < 3; ++i) v.lookat[i] = (lo[i] + hi[i]) / 2;
  // The camera's axes (mjvCamera's convention): forward from azimuth and
  // elevation, right horizontal, up completing the frame.
  const double az = azimuth_deg * std::numbers::pi / 180;
  const double el = elevation_deg * std::numbers::pi / 180;
  const std::array<double, 3> f{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                std::sin(el)};
  const std::array<double, 3> r{std::sin(az), -std::cos(az), 0.0};
  const std::array<double, 3> u{r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2],
                                r[0] * f[1] - r[1] * f[0]};
  const double tan_v = std::tan(m->vis.global.fovy / 2 * std::numbers::pi / 180);
  const double tan_h = aspect * tan_v;
  // Every corner of the box inside the frustum, with a 5% margin: a corner p
  // (from lookat) is seen at depth distance + p.f, offset p.r and p.u.
  double distance = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    std::array<double, 3> p{};
    for (size_t i = 0; i < 3; ++i) p[i] = ((corner >> i) & 1 ? hi[i] : lo[i]) - v.lookat[i];
    auto dot = [&p](const std::array<double, 3>& a) {
      return p[0] * a[0] + p[1] * a[1] + p[2] * a[2];
    };
    const double depth = dot(f);
    distance = std::max(distance, 1.05 * std::abs(dot(r)) / tan_h - depth);
    distance = std::max(distance, 1.05 * std::abs(dot(u)) / tan_v - depth);
  }
  v.distance = std::max(distance, 0.1);
  return v;
}

struct Renderer::Impl {
  OSMesaContext gl = nullptr;
  std::vector<unsigned char> window;  // the OSMesa colour buffer (MuJoCo draws offscreen)
  mjModel* model = nullptr;           // a copy sized for the offscreen buffer
  mjData* data = nullptr;             // the state drawn: a copy of the caller's
  mjvScene scene{};
  mjvOption option{};
  mjvCamera camera{};
  mjrContext context{};
  bool scene_made = false, context_made = false;
  FrameSize size;

  ~Impl() {
    // MuJoCo frees its GL objects in the context they belong to.
    if (gl != nullptr && !window.empty()) {
      osmesa().make_current(gl, window.data(), GL_UNSIGNED_BYTE, size.width, size.height);
    }
    if (context_made) mjr_freeContext(&context);
    if (scene_made) mjv_freeScene(&scene);
    if (data != nullptr) mj_deleteData(data);
    if (model != nullptr) mj_deleteModel(model);
    if (gl != nullptr) {
      // Released first: a context destroyed while current leaks its framebuffer.
      osmesa().make_current(nullptr, nullptr, 0, 0, 0);
      osmesa().destroy(gl);
    }
  }

  void make_current() {
    if (!osmesa().make_current(gl, window.data(), GL_UNSIGNED_BYTE, size.width, size.height)) {
      throw Error("video", "the OSMesa context cannot be made current (libosmesa6)");
    }
  }
};

Renderer::Renderer(const mjModel* model, FrameSize size) : size_(size), impl_(new Impl) {
  if (size.width < kMinSide || size.width > kMaxSide || size.height < kMinSide ||
      size.height > kMaxSide) {
    throw Error("video", "a frame of " + std::to_string(size.width) + "x" +
                             std::to_string(size.height) + " pixels: each side must be in [" +
                             std::to_string(kMinSide) + ", " + std::to_string(kMaxSide) + "]");
  }
  Impl& s = *impl_;
  s.gl = osmesa().create(OSMESA_RGBA, 24, 8, 8, nullptr);
  if (s.gl == nullptr) {
    throw Error("video",
                "OSMesa cannot create an OpenGL context (is libosmesa6 installed? "
                "scripts/install-deps installs it)");
  }
  s.size = size;
  s.window.assign(static_cast<size_t>(size.width) * static_cast<size_t>(size.height) * 4, 0);
  s.make_current();
  s.model = mj_copyModel(nullptr, model);
  s.data = mj_makeData(s.model);
  if (s.model == nullptr || s.data == nullptr) throw Error("video", "MuJoCo is out of memory");
  // MuJoCo renders into its offscreen framebuffer, sized by the model.
  s.model->vis.global.offwidth = size.width;
  s.model->vis.global.offheight = size.height;
  // Software rendering: a 1024² shadow map (MuJoCo's default is 4096²) and
  // no multisampling (4x) halve the time per frame; at 640x480 the edges
  // stay acceptable.
  s.model->vis.quality.shadowsize = 1024;
  s.model->vis.quality.offsamples = 0;
  // A brighter headlight than MuJoCo's default: the world has no lights.
  for (int i = 0; i < 3; ++i) {
    s.model->vis.headlight.ambient[i] = 0.3f;
    s.model->vis.headlight.diffuse[i] = 0.4f;
  }
  mjv_defaultOption(&s.option);
  mjv_defaultCamera(&s.camera);
  s.camera.type = mjCAMERA_FREE;
  mjv_defaultScene(&s.scene);
  mjv_makeScene(s.model, &s.scene, 2000);
  s.scene_made = true;
  mjr_defaultContext(&s.context);
  mjr_makeContext(s.model, &s.context, mjFONTSCALE_100);
  s.context_made = true;
  mjr_setBuffer(mjFB_OFFSCREEN, &s.context);
  if (s.context.currentBuffer != mjFB_OFFSCREEN) {
    throw Error("video", "MuJoCo's offscreen framebuffer is not available in the OSMesa context");
  }
}

Renderer::~Renderer() = default;

void Renderer::render(const mjData* data, const CameraView& view, std::span<std::uint8_t> rgb) {
  const size_t w = static_cast<size_t>(size_.width), h = static_cast<size_t>(size_.height);
  if (rgb.size() != w * h * 3) {
    throw Error("video", "a frame buffer of " + std::to_string(rgb.size()) + " bytes for " +
                             std::to_string(w) + "x" + std::to_string(h) + " RGB pixels (" +
                             std::to_string(w * h * 3) + " expected)");
  }
  Impl& s = *impl_;
  s.make_current();
  mjr_setBuffer(mjFB_OFFSCREEN, &s.context);
  mj_copyData(s.data, s.model, data);
  for (size_t i = 0; i < 3; ++i) s.camera.lookat[i] = view.lookat[i];
  s.camera.distance = view.distance;
  s.camera.azimuth = view.azimuth_deg;
  s.camera.elevation = view.elevation_deg;
  mjv_updateScene(s.model, s.data, &s.option, nullptr, &s.camera, mjCAT_ALL, &s.scene);
  add_sun(s.scene, view);
  const mjrRect viewport{0, 0, size_.width, size_.height};
  mjr_render(viewport, &s.scene, &s.context);
  mjr_readPixels(rgb.data(), nullptr, viewport, &s.context);
  // OpenGL's rows run bottom-up; a video's top-down.
  std::vector<std::uint8_t>& row = scratch_row_;
  row.resize(w * 3);
  for (size_t y = 0; y < h / 2; ++y) {
    std::uint8_t* a = rgb.data() + y * w * 3;
    std::uint8_t* b = rgb.data() + (h - 1 - y) * w * 3;
    std::copy_n(a, w * 3, row.data());
    std::copy_n(b, w * 3, a);
    std::copy_n(row.data(), w * 3, b);
  }
}

}  // namespace mospec::video
