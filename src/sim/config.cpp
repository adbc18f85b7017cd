#include "sim/config.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <span>

#include "json/json.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"
#include "vocab/metamodels.hpp"

#ifndef MOSPEC_DEFAULT_BASE_MODEL
#define MOSPEC_DEFAULT_BASE_MODEL "robots/kelo-base.jsonld"
#endif
#ifndef MOSPEC_DEFAULT_ROBOT_MODEL
#define MOSPEC_DEFAULT_ROBOT_MODEL "robots/kinova-gen3.jsonld"
#endif

namespace mospec::sim {

std::string_view to_string(BaseFidelity b) {
  switch (b) {
    case BaseFidelity::Wheeled:
      return "wheeled";
    case BaseFidelity::Planar:
      return "planar";
    case BaseFidelity::Fixed:
      return "fixed";
  }
  return "wheeled";
}

std::optional<BaseFidelity> parse_base_fidelity(std::string_view s) {
  if (s == "wheeled") return BaseFidelity::Wheeled;
  if (s == "planar") return BaseFidelity::Planar;
  if (s == "fixed") return BaseFidelity::Fixed;
  return {};
}

namespace {

runtime::Pose pose_from_cosines(const runtime::Vec3& x, const runtime::Vec3& y,
                                const runtime::Vec3& z, const runtime::Vec3& p) {
  runtime::Pose X;
  X.R.col(0) = x;
  X.R.col(1) = y;
  X.R.col(2) = z;
  // The published cosines have 9 digits: re-orthonormalise.
  Eigen::JacobiSVD<runtime::Mat3> svd(X.R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  X.R = svd.matrixU() * svd.matrixV().transpose();
  X.p = p;
  return X;
}

}  // namespace

WorldConfig default_world() {
  WorldConfig c;
  c.robot.model = MOSPEC_DEFAULT_ROBOT_MODEL;
  c.robot.chain_iri = vocab::robots::kinova_gen3_chain;
  c.base_model.model = MOSPEC_DEFAULT_BASE_MODEL;
  c.base_model.configuration = vocab::robots::kelo_base;
  // The description's contexts (under vocab::kMetamodels)
  // resolve to mospec's own metamodels unless the world file maps them.

  // Mount poses of the arms' base frames in the platform frame. Source: the
  // authors' models, motion-spec-ral models/01-right-arm/00-misc.json
  // (pose-rightarm-platform-shoulder) and models/02-left-arm/00-misc.json
  // (pose-leftarm-platform-shoulder); direction-cosine-x/y/z are the columns
  // of R_PB (the shoulder's axes seen by the platform), as the authors'
  // gravity vectors in models/00-common/01-world-model.json confirm.
  c.arms.resize(2);
  c.arms[robot::kRightArm].name = "right";
  // The right arm is the world's `robot` itself: its chain binds by the
  // robot's `chain` (arm_chain), whatever IRI a world file gives it.
  c.arms[robot::kRightArm].X_PB =
      pose_from_cosines({0.130526192, 0.0, 0.991444861}, {-0.701057385, -0.707106781, 0.0922959556},
                        {0.701057385, -0.707106781, -0.0922959556}, {0.0, -0.1, 0.1});
  // The left arm is the same Gen3 description (read from `robot`); the task
  // models name its chain by the left twin's IRI (models/left-arm/robot.jsonld).
  c.arms[robot::kLeftArm].name = "left";
  c.arms[robot::kLeftArm].chain_iri = vocab::robots::kinova_gen3_left_chain;
  c.arms[robot::kLeftArm].X_PB =
      pose_from_cosines({0.130526192, 0.0, 0.991444861}, {0.701057385, -0.707106781, -0.0922959556},
                        {0.701057385, 0.707106781, -0.0922959556}, {0.0, 0.1, 0.1});

  // The "whisker" pose: the end-effector centres ahead of the platform at
  // (0.6, -0.25, 0.35) m (right) and (0.6, 0.25, 0.35) m (left) in P, the
  // flange's z axis along x_P, elbows up (found by damped least-squares IK on
  // the Gen3 chain; 4 decimals, so the centres agree to about 1 mm).
  c.arms[robot::kRightArm].q0 = {-0.1989, 1.7282, -0.9470, -2.1654, -0.3097, 0.4927, 0.0};
  c.arms[robot::kLeftArm].q0 = {0.0984, 1.7898, 0.9763, -2.1188, 0.3954, 0.4859, 0.0341};
  return c;
}

const std::string& arm_chain(const WorldConfig& config, std::size_t arm) {
  const ArmSetup& a = config.arms[arm];
  return a.chain_iri.empty() ? config.robot.chain_iri : a.chain_iri;
}

const ArmActuation& arm_actuation(const WorldConfig& config, std::size_t arm) {
  const ArmSetup& a = config.arms[arm];
  return a.actuation ? *a.actuation : config.actuation;
}

RobotModelSource arm_source(const WorldConfig& config, std::size_t arm) {
  const ArmSetup& a = config.arms[arm];
  return a.robot.model.empty() ? config.robot : a.robot;
}

void actuation_from_chains(WorldConfig& config, std::span<const runtime::Chain> chains) {
  if (config.actuation_stated) return;
  for (size_t k = 0; k < config.arms.size() && k < chains.size(); ++k) {
    ArmSetup& arm = config.arms[k];
    const runtime::Chain& chain = chains[k];
    if (arm.actuation || chain.size() == 0) continue;
    ArmActuation a;
    a.effort_limit.clear();
    a.lower.clear();
    a.upper.clear();
    bool efforts = true;
    for (int i = 0; i < chain.size(); ++i) {
      const runtime::JointLimits& l = chain.segment(i).limits;
      efforts = efforts && std::isfinite(l.effort) && l.effort > 0;
      a.effort_limit.push_back(l.effort);
      const bool bounded = std::isfinite(l.lower) && std::isfinite(l.upper) && l.lower < l.upper;
      a.lower.push_back(bounded ? l.lower : -1e9);
      a.upper.push_back(bounded ? l.upper : 1e9);
    }
    if (efforts) arm.actuation = std::move(a);
  }
}

robot::RobotShape robot_shape(const WorldConfig& config, const std::vector<int>& joints) {
  robot::RobotShape shape;
  shape.drives = static_cast<int>(config.drives.geometry.p_PoAi_P.size());
  for (std::size_t k = 0; k < config.arms.size(); ++k) {
    shape.arms.push_back({config.arms[k].name, k < joints.size() ? joints[k] : 0});
  }
  return shape;
}

namespace {

// The accepted ranges of a world file's numbers (docs/simulation.md): wide
// enough for any plausible robot and table, narrow enough that a typo (or a
// hostile file) cannot make the simulation run forever or go unstable.
constexpr double kMinControlPeriod = 1e-5;  // [s]: 100 kHz
constexpr double kMaxControlPeriod = 1.0;   // [s]
constexpr double kMaxLength = 100.0;        // [m]: sizes, positions, offsets
// [rad]: joint and heading angles. One turn: a bare 20 meant as degrees is
// refused (with the way to write degrees) rather than read as 20 rad.
constexpr double kMaxAngle = 6.283185307179586;
constexpr double kMaxMass = 1e4;       // [kg]
constexpr double kMaxTorque = 1e4;     // [N·m]: effort and hub torque limits
constexpr double kMaxDamping = 1e3;    // [N·m·s/rad]
constexpr double kMaxFriction = 10.0;  // Coulomb coefficients

// A number as a message quotes it: the shortest form that reads back the same.
std::string shortest(double x) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : exact_number(x);
}

// Reads one JSON world file; every error names file:line:col.
class Reader {
 public:
  Reader(std::string file, bool check_files) : file_(std::move(file)), check_files_(check_files) {}

  [[noreturn]] void fail(const json::Value& v, const std::string& message) const {
    const SourceLoc l = v.location();
    throw Error("invalid-world", message, file_, l.line, l.column);
  }

  const json::Object& object(const json::Value& v, std::string_view what,
                             std::initializer_list<std::string_view> keys) const {
    if (!v.is_object()) fail(v, std::string(what) + ": expected an object");
    const json::Object& o = v.as_object();
    for (size_t i = 0; i < o.size(); ++i) {
      bool known = false;
      for (std::string_view k : keys) known = known || o.key(i) == k;
      if (!known) {
        std::string list;
        for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
        const SourceLoc l = o.key_location(i);
        throw Error("invalid-world",
                    std::string(what) + ": unknown key '" + std::string(o.key(i)) +
                        "' (expected one of: " + list + ")",
                    file_, l.line, l.column);
      }
    }
    return o;
  }

  double number(const json::Value& v, std::string_view what) const {
    if (!v.is_number()) fail(v, std::string(what) + ": expected a number");
    if (!std::isfinite(v.as_number())) {
      fail(v, std::string(what) + ": " + shortest(v.as_number()) + " is not a finite number");
    }
    return v.as_number();
  }

  // A value of a key whose SI unit is `unit`: a bare number is in that unit;
  // an angle (rad) or a length (m) may also be a string "NUMBER UNIT" in
  // another unit of its kind (docs/simulation.md, "Units"): "20 deg", "5 cm".
  double quantity(const json::Value& v, std::string_view what, std::string_view unit) const {
    struct Scale {
      std::string_view name;
      double factor;  // to the SI unit
    };
    static constexpr Scale kAngles[] = {{"rad", 1.0}, {"deg", 3.141592653589793 / 180.0}};
    static constexpr Scale kLengths[] = {{"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}};
    const std::span<const Scale> scales = unit == "rad" ? std::span<const Scale>(kAngles)
                                          : unit == "m" ? std::span<const Scale>(kLengths)
                                                        : std::span<const Scale>();
    if (!v.is_string() || scales.empty()) {
      if (!v.is_number()) {
        std::string forms;
        for (const Scale& s : scales)
          forms += std::string(forms.empty() ? "" : ", ") + "\"1 " + std::string(s.name) + "\"";
        fail(v,
             std::string(what) + ": expected a number" +
                 (scales.empty() ? std::string()
                                 : " [" + std::string(unit) +
                                       "] or a string of a number and its unit (" + forms + ")"));
      }
      return number(v, what);
    }
    const std::string_view text = v.as_string();
    const size_t space = text.find(' ');
    const std::string_view digits = text.substr(0, space);
    const std::string_view name =
        space == std::string_view::npos ? std::string_view() : text.substr(space + 1);
    double x = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
    const Scale* scale = nullptr;
    for (const Scale& s : scales) {
      if (s.name == name) scale = &s;
    }
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() ||
        !std::isfinite(x) || scale == nullptr) {
      std::string names;
      for (const Scale& s : scales) names += (names.empty() ? "" : ", ") + std::string(s.name);
      fail(v, std::string(what) + ": '" + escaped_bytes(text) +
                  "' is not a number and its unit, one space apart, the unit one of " + names +
                  " (e.g. \"" + (unit == "rad" ? "20 deg" : "5 cm") + "\")");
    }
    return x * scale->factor;
  }

  // A number in [lo, hi], or (lo, hi] with `lo_open`; the message names the
  // key, the value and the accepted range with its unit.
  double in_range(const json::Value& v, std::string_view what, double lo, double hi,
                  std::string_view unit, bool lo_open = false) const {
    const double x = quantity(v, what, unit);
    if (x < lo || (lo_open && x == lo) || x > hi) {
      // A bare angle beyond a turn is most likely degrees written as a number.
      const bool degrees = unit == "rad" && v.is_number() && hi == kMaxAngle;
      fail(v, std::string(what) + ": " +
                  (v.is_string() ? "'" + escaped_bytes(v.as_string()) + "' (" + shortest(x) + ")"
                                 : shortest(x)) +
                  " is outside the accepted range " + (lo_open ? "(" : "[") + shortest(lo) + ", " +
                  shortest(hi) + "]" + (unit.empty() ? "" : " ") + std::string(unit) +
                  (degrees ? "; a bare number is in radians, an angle in degrees is written as "
                             "such: \"" +
                                 shortest(x) + " deg\""
                           : ""));
    }
    return x;
  }

  double non_negative(const json::Value& v, std::string_view what, double hi,
                      std::string_view unit) const {
    return in_range(v, what, 0.0, hi, unit);
  }

  double positive(const json::Value& v, std::string_view what, double hi,
                  std::string_view unit) const {
    return in_range(v, what, 0.0, hi, unit, true);
  }

  bool boolean(const json::Value& v, std::string_view what) const {
    if (!v.is_bool()) fail(v, std::string(what) + ": expected true or false");
    return v.as_bool();
  }

  std::string_view string(const json::Value& v, std::string_view what) const {
    if (!v.is_string()) fail(v, std::string(what) + ": expected a string");
    return v.as_string();
  }

  // N numbers, each in [lo, hi] (or (lo, hi] with `lo_open`).
  template <size_t N>
  std::array<double, N> numbers(const json::Value& v, std::string_view what, double lo, double hi,
                                std::string_view unit, bool lo_open = false) const {
    if (!v.is_array() || v.as_array().size() != N) {
      fail(v, std::string(what) + ": expected an array of " + std::to_string(N) + " numbers");
    }
    std::array<double, N> out{};
    for (size_t i = 0; i < N; ++i) {
      out[i] = in_range(v.as_array()[i], std::string(what) + "[" + std::to_string(i) + "]", lo, hi,
                        unit, lo_open);
    }
    return out;
  }

  // 1 to kMaxJoints numbers, each in [lo, hi] (or (lo, hi] with `lo_open`).
  std::vector<double> joint_numbers(const json::Value& v, const std::string& what, double lo,
                                    double hi, std::string_view unit, bool lo_open = false) const {
    constexpr size_t kMaxJoints = 64;
    if (!v.is_array() || v.as_array().empty() || v.as_array().size() > kMaxJoints) {
      fail(v, what + ": expected an array of 1 to " + std::to_string(kMaxJoints) +
                  " numbers, one per joint");
    }
    std::vector<double> out;
    for (size_t i = 0; i < v.as_array().size(); ++i) {
      out.push_back(
          in_range(v.as_array()[i], what + "[" + std::to_string(i) + "]", lo, hi, unit, lo_open));
    }
    return out;
  }

  Place where(const json::Value& v) const {
    const SourceLoc l = v.location();
    return {file_, l.line, l.column};
  }

  std::string path(const std::string& p) const {
    std::filesystem::path fp(p);
    if (fp.is_absolute()) return p;
    return (std::filesystem::path(file_).parent_path() / fp).lexically_normal().string();
  }

  // A file or directory the world file names for loading (the robot model, a
  // robot.map directory). World files come with downloaded model bundles, so
  // what they name must stay inside the model tree (the world file's own
  // directory, the current directory) or mospec's robot descriptions and metamodels, after
  // resolving `..` and symbolic links; otherwise a bundle could map the metamodels onto `/` and
  // read past the loader's sandbox.
  std::string confined_path(const json::Value& v, const std::string& what) const {
    namespace fs = std::filesystem;
    const std::string p = path(std::string(string(v, what)));
    if (!check_files_) return p;
    const fs::path target = canonical_path(p);
    const fs::path world_dir = fs::absolute(fs::path(file_)).parent_path();
    const fs::path robots_dir = fs::path(MOSPEC_DEFAULT_ROBOT_MODEL).parent_path();
    // The current directory is the tree an app's iri-map resolves against
    // (app::load), so a bundle run from its top may keep robots/ beside models/.
    for (const fs::path& root :
         {world_dir, fs::current_path(), robots_dir, fs::path(MOSPEC_METAMODELS_DIR)}) {
      if (is_within(target, canonical_path(root.string()))) return p;
    }
    fail(v, what + ": '" + escaped_bytes(target.string()) +
                "' lies outside the model tree (the world file's directory " +
                escaped_bytes(world_dir.string()) +
                ", the current directory, mospec's robot descriptions and metamodels); put the "
                "file there or run from the bundle's top directory");
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  bool check_files_ = true;
};

void read_robot_source(const Reader& r, const json::Value& v, const std::string& what,
                       RobotModelSource& source) {
  const json::Object& o = r.object(v, what, {"model", "chain", "map"});
  if (auto* m = o.find("model")) source.model = r.confined_path(*m, what + ".model");
  if (auto* m = o.find("chain")) source.chain_iri = r.string(*m, what + ".chain");
  if (auto* m = o.find("map")) {
    if (!m->is_object()) r.fail(*m, what + ".map: expected an object of IRI prefix: directory");
    const json::Object& mo = m->as_object();
    for (size_t k = 0; k < mo.size(); ++k) {
      const std::string dir = r.confined_path(mo.value(k), what + ".map");
      bool replaced = false;
      for (auto& [prefix, d] : source.maps) {
        if (prefix == mo.key(k)) {
          d = dir;
          replaced = true;
        }
      }
      if (!replaced) source.maps.emplace_back(mo.key(k), dir);
    }
  }
}

ArmActuation read_actuation(const Reader& r, const json::Value& v, const std::string& what,
                            ArmActuation a) {
  const json::Object& o = r.object(v, what, {"effort_limit", "lower", "upper", "damping"});
  if (auto* x = o.find("effort_limit"))
    a.effort_limit = r.joint_numbers(*x, what + ".effort_limit", 0.0, kMaxTorque, "N·m", true);
  if (auto* x = o.find("lower")) a.lower = r.joint_numbers(*x, what + ".lower", -1e9, 1e9, "rad");
  if (auto* x = o.find("upper")) a.upper = r.joint_numbers(*x, what + ".upper", -1e9, 1e9, "rad");
  if (auto* x = o.find("damping")) {
    a.damping = r.non_negative(*x, what + ".damping", kMaxDamping, "N·m·s/rad");
  }
  if (o.find("effort_limit") && !o.find("lower") && !o.find("upper") &&
      a.effort_limit.size() != a.lower.size()) {
    // Efforts for another arm than the Gen3 without position limits: none.
    a.lower.assign(a.effort_limit.size(), -1e9);
    a.upper.assign(a.effort_limit.size(), 1e9);
  }
  return a;
}

// `arms`: an object keyed by arm name. An entry for an arm of the default
// robot (right, left) changes it; `"present": false` removes it; any other
// name adds an arm, which then needs its `robot`, `q` and `actuation`.
void read_arms(const Reader& r, const json::Value& v, WorldConfig& c) {
  if (!v.is_object()) r.fail(v, "arms: expected an object of arm name: arm");
  const json::Object& o = v.as_object();
  for (size_t k = 0; k < o.size(); ++k) {
    const std::string name(o.key(k));
    const std::string what = "arms." + name;
    if (name.empty() || name.size() > 32 ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789") != std::string::npos) {
      const SourceLoc l = o.key_location(k);
      throw Error("invalid-world",
                  what +
                      ": an arm's name must be 1 to 32 lower-case letters and digits (it "
                      "prefixes sensor names and log columns)",
                  r.file(), l.line, l.column);
    }
    const json::Object& a =
        r.object(o.value(k), what, {"present", "robot", "chain", "q", "mount", "actuation"});
    auto it = std::find_if(c.arms.begin(), c.arms.end(),
                           [&](const ArmSetup& s) { return s.name == name; });
    if (auto* p = a.find("present"); p && !r.boolean(*p, what + ".present")) {
      if (a.size() != 1) r.fail(o.value(k), what + ": an absent arm takes no other keys");
      if (it != c.arms.end()) c.arms.erase(it);
      continue;
    }
    const bool added = it == c.arms.end();
    if (added) {
      // A robot of more arms is not plausible, and each costs a model load
      // and a MuJoCo subtree: a bound keeps a hostile file from growing both.
      constexpr size_t kMaxArms = 16;
      if (c.arms.size() >= kMaxArms) {
        r.fail(o.value(k), what + ": a robot has at most " + std::to_string(kMaxArms) + " arms");
      }
      // Its actuation may come from its robot description's joint limits
      // (actuation_from_chains), so only the robot and q are required.
      if (!a.find("robot") || !a.find("q")) {
        r.fail(o.value(k), what +
                               ": a new arm needs its `robot` (model and chain) and `q` "
                               "(mospec's default robot has the arms right and left)");
      }
      c.arms.emplace_back();
      c.arms.back().name = name;
      it = c.arms.end() - 1;
    }
    ArmSetup& arm = *it;
    arm.where = r.where(o.value(k));
    if (auto* x = a.find("robot")) {
      read_robot_source(r, *x, what + ".robot", arm.robot);
      if (arm.robot.model.empty() || arm.robot.chain_iri.empty()) {
        r.fail(*x, what + ".robot: expected the `model` file and the `chain` IRI in it");
      }
      arm.chain_iri = arm.robot.chain_iri;
    }
    if (auto* x = a.find("chain")) {
      // The name the task models give an arm that is the world's `robot`
      // (two arms of one description need two chain IRIs); an arm with its
      // own `robot` is bound by that robot's `chain`.
      if (a.find("robot")) {
        r.fail(*x, what +
                       ".chain: an arm with its own `robot` is bound by `robot.chain`; state "
                       "the chain IRI once, there");
      }
      arm.chain_iri = r.string(*x, what + ".chain");
      if (arm.chain_iri.empty()) r.fail(*x, what + ".chain: expected a chain IRI");
    }
    if (auto* q = a.find("q"))
      arm.q0 = r.joint_numbers(*q, what + ".q", -kMaxAngle, kMaxAngle, "rad");
    if (auto* x = a.find("actuation")) {
      arm.actuation = read_actuation(r, *x, what + ".actuation",
                                     arm_actuation(c, static_cast<size_t>(it - c.arms.begin())));
    }
    if (auto* m = a.find("mount")) {
      const json::Object& mo = r.object(
          *m, what + ".mount",
          {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z", "x", "y", "z"});
      arm.mount_source = "the world file's " + what + ".mount";
      runtime::Pose& X = arm.X_PB;
      runtime::Vec3 cols[3] = {X.R.col(0), X.R.col(1), X.R.col(2)};
      const char* names[3] = {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z"};
      for (int j = 0; j < 3; ++j) {
        if (auto* d = mo.find(names[j])) {
          auto n = r.numbers<3>(*d, what + ".mount." + names[j], -1.01, 1.01, "");
          cols[j] = runtime::Vec3(n[0], n[1], n[2]);
        }
      }
      runtime::Vec3 p = X.p;
      if (auto* x = mo.find("x"))
        p.x() = r.in_range(*x, what + ".mount.x", -kMaxLength, kMaxLength, "m");
      if (auto* y = mo.find("y"))
        p.y() = r.in_range(*y, what + ".mount.y", -kMaxLength, kMaxLength, "m");
      if (auto* z = mo.find("z"))
        p.z() = r.in_range(*z, what + ".mount.z", -kMaxLength, kMaxLength, "m");
      const runtime::Mat3 R = (runtime::Mat3() << cols[0], cols[1], cols[2]).finished();
      if (std::abs(R.determinant() - 1.0) > 1e-3 ||
          !(R.transpose() * R).isApprox(runtime::Mat3::Identity(), 1e-3)) {
        r.fail(*m, what + ".mount: the direction cosines are not a rotation");
      }
      X = pose_from_cosines(cols[0], cols[1], cols[2], p);
    }
  }
}

}  // namespace

WorldConfig parse_world_config(std::string_view text, const std::string& file_name,
                               bool check_files) {
  WorldConfig c = default_world();
  const json::Value doc = json::parse(text, 1, file_name);
  const Reader r(file_name, check_files);
  const json::Object& top = r.object(
      doc, "world",
      {"base", "control_period", "substeps", "command_delay_ticks", "seed", "robot", "arms",
       "actuation", "end_effector", "platform", "table", "mount", "initial", "perturbation"});
  for (size_t i = 0; i < top.size(); ++i) {
    const std::string_view key = top.key(i);
    const json::Value& v = top.value(i);
    if (key == "base") {
      auto b = parse_base_fidelity(r.string(v, "base"));
      if (!b) r.fail(v, "base: expected \"wheeled\", \"planar\" or \"fixed\"");
      c.base = *b;
    } else if (key == "control_period") {
      c.control_period = r.in_range(v, key, kMinControlPeriod, kMaxControlPeriod, "s");
    } else if (key == "substeps") {
      const double n = r.number(v, key);
      if (n != std::floor(n) || n < 1 || n > 100) r.fail(v, "substeps: expected an integer 1..100");
      c.substeps = static_cast<int>(n);
    } else if (key == "command_delay_ticks") {
      const double n = r.number(v, key);
      if (n != 0 && n != 1) r.fail(v, "command_delay_ticks: expected 0 or 1");
      c.command_delay_ticks = static_cast<int>(n);
    } else if (key == "seed") {
      const double n = r.number(v, key);
      if (n != std::floor(n) || n < 0 || n > 9007199254740992.0) {
        r.fail(v, "seed: expected an integer 0..2^53");
      }
      c.seed = static_cast<std::uint64_t>(n);
    } else if (key == "robot") {
      read_robot_source(r, v, "robot", c.robot);
    } else if (key == "arms") {
      read_arms(r, v, c);
    } else if (key == "actuation") {
      c.actuation = read_actuation(r, v, "actuation", c.actuation);
      c.actuation_stated = true;
    } else if (key == "end_effector") {
      const json::Object& o = r.object(v, "end_effector", {"radius", "friction"});
      if (auto* x = o.find("radius")) c.end_effector.radius = r.positive(*x, "radius", 1.0, "m");
      if (auto* x = o.find("friction")) {
        c.end_effector.friction = r.non_negative(*x, "friction", kMaxFriction, "");
      }
    } else if (key == "platform") {
      const json::Object& o =
          r.object(v, "platform",
                   {"mass", "size", "deck_height", "drive_mass", "wheel_mass", "pivot_damping",
                    "wheel_damping", "wheel_torque_limit", "wheel_friction"});
      PlatformParameters& p = c.platform;
      if (auto* x = o.find("mass")) p.mass = r.positive(*x, "mass", kMaxMass, "kg");
      if (auto* x = o.find("size")) p.size = r.numbers<3>(*x, "size", 0.0, kMaxLength, "m", true);
      if (auto* x = o.find("deck_height")) {
        p.deck_height = r.positive(*x, "deck_height", kMaxLength, "m");
      }
      if (auto* x = o.find("drive_mass"))
        p.drive_mass = r.positive(*x, "drive_mass", kMaxMass, "kg");
      if (auto* x = o.find("wheel_mass"))
        p.wheel_mass = r.positive(*x, "wheel_mass", kMaxMass, "kg");
      if (auto* x = o.find("pivot_damping")) {
        p.pivot_damping = r.non_negative(*x, "pivot_damping", kMaxDamping, "N·m·s/rad");
      }
      if (auto* x = o.find("wheel_damping")) {
        p.wheel_damping = r.non_negative(*x, "wheel_damping", kMaxDamping, "N·m·s/rad");
      }
      if (auto* x = o.find("wheel_torque_limit")) {
        p.wheel_torque_limit = r.positive(*x, "wheel_torque_limit", kMaxTorque, "N·m");
      }
      if (auto* x = o.find("wheel_friction")) {
        p.wheel_friction = r.positive(*x, "wheel_friction", kMaxFriction, "");
      }
    } else if (key == "table") {
      const json::Object& o = r.object(
          v, "table", {"present", "depth", "width", "edge_height_offset", "friction", "pose"});
      if (auto* x = o.find("present")) c.table.present = r.boolean(*x, "present");
      if (auto* x = o.find("depth")) c.table.depth = r.positive(*x, "depth", kMaxLength, "m");
      if (auto* x = o.find("width")) c.table.width = r.positive(*x, "width", kMaxLength, "m");
      if (auto* x = o.find("edge_height_offset")) {
        c.table.edge_height_offset =
            r.in_range(*x, "edge_height_offset", -kMaxLength, kMaxLength, "m");
      }
      if (auto* x = o.find("friction")) {
        c.table.friction = r.non_negative(*x, "friction", kMaxFriction, "");
      }
      if (auto* x = o.find("pose")) {
        const json::Object& po = r.object(*x, "table.pose", {"x", "y", "yaw"});
        if (auto* e = po.find("x"))
          c.table.x = r.in_range(*e, "table.pose.x", -kMaxLength, kMaxLength, "m");
        if (auto* e = po.find("y"))
          c.table.y = r.in_range(*e, "table.pose.y", -kMaxLength, kMaxLength, "m");
        if (auto* e = po.find("yaw")) {
          c.table.yaw = r.in_range(*e, "table.pose.yaw", -kMaxAngle, kMaxAngle, "rad");
        }
      }
    } else if (key == "mount") {
      const json::Object& o = r.object(v, "mount", {"active", "time_constant"});
      if (auto* x = o.find("active")) c.mount.active = r.boolean(*x, "active");
      if (auto* x = o.find("time_constant"))
        c.mount.time_constant = r.in_range(*x, "time_constant", 1e-4, 10.0, "s");
    } else if (key == "initial") {
      const json::Object& o =
          r.object(v, "initial", {"base_x", "base_y", "base_yaw", "contact_gap", "pivot_q"});
      auto length = [&](const json::Value& x, const char* what) {
        return r.in_range(x, what, -kMaxLength, kMaxLength, "m");
      };
      auto angle = [&](const json::Value& x, const char* what) {
        return r.in_range(x, what, -kMaxAngle, kMaxAngle, "rad");
      };
      if (auto* x = o.find("base_x")) c.initial.base_x = length(*x, "base_x");
      if (auto* x = o.find("base_y")) c.initial.base_y = length(*x, "base_y");
      if (auto* x = o.find("base_yaw")) c.initial.base_yaw = angle(*x, "base_yaw");
      if (auto* x = o.find("contact_gap")) c.initial.contact_gap = length(*x, "contact_gap");
      if (auto* x = o.find("pivot_q")) {
        c.initial.pivot_q = r.joint_numbers(*x, "pivot_q", -kMaxAngle, kMaxAngle, "rad");
      }
    } else if (key == "perturbation") {
      const json::Object& o =
          r.object(v, "perturbation", {"arm_q", "base_xy", "base_yaw", "pivot_q"});
      constexpr double kPi = 3.141592653589793;
      if (auto* x = o.find("arm_q")) c.perturbation.arm_q = r.non_negative(*x, "arm_q", kPi, "rad");
      if (auto* x = o.find("base_xy")) {
        c.perturbation.base_xy = r.non_negative(*x, "base_xy", 1.0, "m");
      }
      if (auto* x = o.find("base_yaw")) {
        c.perturbation.base_yaw = r.non_negative(*x, "base_yaw", kPi, "rad");
      }
      if (auto* x = o.find("pivot_q")) {
        c.perturbation.pivot_q = r.non_negative(*x, "pivot_q", kPi, "rad");
      }
    }
  }
  // Each chain drives one arm: a second arm bound by the same IRI would leave
  // which arm a solver drives to the order of the map.
  for (size_t k = 0; k < c.arms.size(); ++k) {
    for (size_t j = 0; j < k; ++j) {
      if (arm_chain(c, j) != arm_chain(c, k)) continue;
      const Place& at = c.arms[k].where.known() ? c.arms[k].where : c.arms[j].where;
      const auto bound_by = [&](size_t i) {
        return c.arms[i].chain_iri.empty() ? std::string("the world's `robot.chain`")
                                           : "arms." + c.arms[i].name;
      };
      throw Error(
          "invalid-world",
          "arms " + c.arms[j].name + " and " + c.arms[k].name + " are both bound to the chain '" +
              arm_chain(c, k) + "' (by " + bound_by(j) + " and " + bound_by(k) +
              "); give each arm the chain IRI its task models name it by (`arms.<arm>."
              "chain`, or its own `robot`)",
          at.known() ? at.file : file_name, at.known() ? at.line : 0, at.known() ? at.column : 0);
    }
  }
  return c;
}

WorldConfig load_world_config(const std::string& path, bool check_files) {
  return parse_world_config(read_file(path), path, check_files);
}

}  // namespace mospec::sim
