#include "codegen/codegen.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string_view>

#include "codegen/build.hpp"
#include "codegen/templates.hpp"
#include "ir/controllers.hpp"
#include "ir/emit.hpp"
#include "ir/operators.hpp"
#include "support/io.hpp"
#include "support/mustache.hpp"

namespace mospec::codegen {

using ir::DataType;

std::string cpp_double(double value) {
  if (std::isnan(value)) return "std::numeric_limits<double>::quiet_NaN()";
  if (std::isinf(value)) {
    return value > 0 ? "std::numeric_limits<double>::infinity()"
                     : "-std::numeric_limits<double>::infinity()";
  }
  // "%.17g": to_chars with a precision writes what printf would, without
  // printf's cost (this runs for every number of the model).
  std::array<char, 40> buf{};
  const auto written =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::general, 17);
  std::string s(buf.data(), written.ptr);
  if (s.find_first_of(".e") == std::string::npos) s.append(".0");
  return s;
}

std::string cpp_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(c);
    } else if (u < 0x20 || u >= 0x7f || c == '?') {
      // Octal escapes (three digits, so a following digit is never absorbed):
      // control characters, every byte outside ASCII (the literal holds the
      // same bytes, and no bidi control reaches the source), and '?', so no
      // trigraph can form.
      std::array<char, 8> buf{};
      std::snprintf(buf.data(), buf.size(), "\\%03o", static_cast<unsigned>(u));
      out.append(buf.data());
    } else {
      out.push_back(c);
    }
  }
  out.push_back('"');
  return out;
}

namespace {

[[noreturn]] void fail(const std::string& what) {
  std::string msg = "codegen: ";
  msg.append(what);
  throw Error("codegen", msg);
}

// One character of UTF-8 at text[at] (advancing `at`): its code point, or -1
// for a byte that does not start a well-formed, shortest-form sequence.
long decode_utf8(std::string_view text, std::size_t& at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char b0 = byte(at);
  int extra = 0;
  long cp = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    extra = 1;
    cp = b0 & 0x1F;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    extra = 2;
    cp = b0 & 0x0F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    extra = 3;
    cp = b0 & 0x07;
  } else {
    ++at;
    return -1;
  }
  if (at + static_cast<std::size_t>(extra) >= text.size()) {
    ++at;
    return -1;
  }
  for (int k = 1; k <= extra; ++k) {
    const unsigned char b = byte(at + static_cast<std::size_t>(k));
    if ((b & 0xC0) != 0x80) {
      ++at;
      return -1;
    }
    cp = (cp << 6) | (b & 0x3F);
  }
  const long min = extra == 1 ? 0x80 : extra == 2 ? 0x800 : 0x10000;
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
    ++at;
    return -1;
  }
  at += static_cast<std::size_t>(extra) + 1;
  return cp;
}

std::string hex_escape(const char* format, unsigned long value) {
  std::array<char, 16> buf{};
  std::snprintf(buf.data(), buf.size(), format, value);
  return buf.data();
}

}  // namespace

std::string comment_text(std::string_view text) {
  // The common case, an IRI or a name: nothing to escape.
  bool plain = true;
  for (std::size_t at = 0; at < text.size() && plain; ++at) {
    const auto u = static_cast<unsigned char>(text[at]);
    const char next = at + 1 < text.size() ? text[at + 1] : '\0';
    plain = u >= 0x20 && u < 0x7f && u != '\\' && !(u == '?' && next == '?') &&
            !(u == '*' && next == '/') && !(u == '/' && next == '*');
  }
  if (plain) return std::string(text);
  std::string out;
  for (std::size_t at = 0; at < text.size();) {
    const char c = text[at];
    const auto u = static_cast<unsigned char>(c);
    const char next = at + 1 < text.size() ? text[at + 1] : '\0';
    if (u >= 0x80) {
      const std::size_t start = at;
      const long cp = decode_utf8(text, at);
      if (cp < 0) {
        out.append(hex_escape("\\x%02X", static_cast<unsigned char>(text[start])));
      } else {
        out.append(
            hex_escape(cp > 0xFFFF ? "\\U%08lX" : "\\u%04lX", static_cast<unsigned long>(cp)));
      }
      continue;
    }
    // Control characters (line breaks above all), the backslash (a line
    // splice), '?' before '?' (a trigraph), and the two characters of "*/"
    // and "/*" (a block comment's end or start).
    const bool escape = u < 0x20 || u == 0x7f || c == '\\' || (c == '?' && next == '?') ||
                        (c == '*' && next == '/') || (c == '/' && next == '*');
    if (escape) {
      out.append(hex_escape("\\x%02X", u));
    } else {
      out.push_back(c);
    }
    ++at;
  }
  return out;
}

namespace {

bool is_alnum(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

}  // namespace

std::string mangle(std::string_view role, std::string_view name) {
  std::string out(role);
  out.push_back('_');
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (i == 0) {
      // First: a letter or digit stands for itself, except 'x', which (like
      // every other byte) is written xHH.
      if (is_alnum(c) && c != 'x') {
        out.push_back(static_cast<char>(c));
      } else {
        out.append(hex_escape("x%02X", c));
      }
      continue;
    }
    const bool next_plain = i + 1 < name.size() &&
                            is_alnum(static_cast<unsigned char>(name[i + 1])) && name[i + 1] != 'x';
    if (is_alnum(c) || (c == '_' && next_plain)) {
      // A letter or digit, or an underscore between that and a letter or
      // digit other than 'x': itself. So "_x" only ever starts an escape, and
      // no "__" can form.
      out.push_back(static_cast<char>(c));
    } else {
      out.append(hex_escape("_x%02X", c));
    }
  }
  return out;
}

namespace {

// The member of Data that holds each data type's slots.
std::string_view type_member(DataType t) {
  switch (t) {
    case DataType::Scalar:
      return "scalar";
    case DataType::Vector3:
      return "vec3";
    case DataType::Pose:
      return "pose";
    case DataType::Twist:
      return "twist";
    case DataType::Wrench:
      return "wrench";
    case DataType::Flag:
      return "flag";
    case DataType::Event:
      return "event";
    case DataType::Inertia:
      return "inertia";
  }
  return "scalar";
}

std::string join_doubles(const double* values, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) {
    if (i > 0) out.append(", ");
    out.append(cpp_double(values[i]));
  }
  return out;
}
std::string vec3(const runtime::Vec3& v) {
  return join_doubles(v.data(), 3);
}
// A 3x3 matrix row-major, for Eigen's comma initializer.
std::string mat3(const runtime::Mat3& M) {
  const std::array<double, 9> r{M(0, 0), M(0, 1), M(0, 2), M(1, 0), M(1, 1),
                                M(1, 2), M(2, 0), M(2, 1), M(2, 2)};
  return join_doubles(r.data(), 9);
}

std::string constraint_kind(runtime::ConstraintKind k) {
  switch (k) {
    case runtime::ConstraintKind::Equality:
      return "rt::ConstraintKind::Equality";
    case runtime::ConstraintKind::LessThan:
      return "rt::ConstraintKind::LessThan";
    case runtime::ConstraintKind::GreaterThan:
      return "rt::ConstraintKind::GreaterThan";
    case runtime::ConstraintKind::Bilateral:
      return "rt::ConstraintKind::Bilateral";
    case runtime::ConstraintKind::Assignment:
      return "rt::ConstraintKind::Assignment";
  }
  return "rt::ConstraintKind::Equality";
}

// Bit-for-bit equality (distinguishes -0 from +0; NaN equals itself).
template <typename M>
bool same_bits(const M& a, const M& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

using ir::append;
using ir::list;
using ir::put;

// Builds the template data for one Program. Every choice is made here.
class Builder final : public ir::EmitContext {
  using ArmNames = ir::ArmNames;

  // The identifiers one role of entities takes: an entity whose identifier is
  // already taken is an error naming both entities' IRIs and locations.
  class Scope {
   public:
    Scope(const Builder& b, std::string what) : b_(b), what_(std::move(what)) {}
    std::string take(std::string_view role, const std::string& name, const std::string& iri,
                     const SourceLoc& where) {
      std::string id = mangle(role, name);
      const auto [it, inserted] = taken_.emplace(id, Entity{iri, where});
      if (!inserted) {
        std::string msg = "codegen: the ";
        msg.append(what_).append(" '").append(it->second.iri).append("' (");
        msg.append(b_.location(it->second.where)).append(") and '").append(iri);
        msg.append("' share the name '").append(name).append("', so both would be the C++ '");
        msg.append(id).append("'; give one of them another local name");
        const std::string file = b_.file_of(where);
        throw Error("codegen-name-collision", msg, file, where.line, where.column);
      }
      return id;
    }

   private:
    struct Entity {
      std::string iri;
      SourceLoc where;
    };
    const Builder& b_;
    std::string what_;
    std::map<std::string, Entity> taken_;
  };

 public:
  Builder(const ir::Program& p, const SourceFiles* files) : p_(p), files_(files) {
    // Every model-derived identifier is mangle(role, IR name): distinct roles
    // never meet, and within a role distinct names never meet (mangle is
    // injective), so only two entities with the same IR name in one role can
    // collide: that is an error naming both.
    Scope slots(*this, "data"), arms(*this, "arm solvers"), evals(*this, "evaluation steps"),
        monitors(*this, "monitor steps");
    // One role per controller kind: its name ("pid_<step>").
    std::vector<Scope> controllers;
    for (const ir::ControllerKind& k : ir::controller_kinds())
      controllers.emplace_back(*this, std::string(k.title));
    for (std::size_t i = 0; i < p.data.size(); ++i) {
      const ir::Data& d = p.data[i];
      data_names_.push_back(slots.take("v", d.name, d.iri, d.where));
    }
    for (const ir::ArmSolver& a : p.arms) {
      ArmNames n;
      n.arm = arms.take("arm", a.name, a.iri, a.where);
      n.task = mangle("task", a.name);
      n.X_BR = mangle("XBR", a.name);
      n.model_fn = mangle("model", a.name);
      n.X_RB_fn = mangle("XRB", a.name);
      n.ws = mangle("ws", a.name);
      arm_names_.push_back(std::move(n));
    }
    for (const ir::Step& st : p.steps) {
      std::string m;
      switch (ir::info(st.kind).member) {
        case ir::StepMember::None:
          break;
        case ir::StepMember::Evaluator:
          m = evals.take("eval", st.name, st.iri, st.where);
          break;
        case ir::StepMember::Controller: {
          const auto k = static_cast<std::size_t>(st.controller);
          m = controllers[k].take(ir::controller_kinds()[k].name, st.name, st.iri, st.where);
          break;
        }
        case ir::StepMember::MonitorTolerance:
          m = monitors.take("tolerance", st.name, st.iri, st.where);
          break;
      }
      step_members_.push_back(m);
    }
  }

  mustache::Data build() {
    mustache::Data root;
    put(root, "app_comment", comment_text(p_.app));
    put(root, "app_literal", cpp_string(p_.app));
    add_slots(root);
    add_model(root);
    add_data(root);
    add_steps(root);
    add_log(root);
    return root;
  }

 private:
  // The program is verified (render() runs ir::verify): indices are in range,
  // types match each step's kind, guards, gates and state slots fit.
  // What the step kinds' emit hooks ask (ir/emit.hpp).
  const ir::Program& program() const override { return p_; }
  std::string ref(int index) const override { return ref(index, "d."); }
  const std::string& member(std::size_t step) const override { return step_members_[step]; }
  const ArmNames& arm(int solver) const override {
    return arm_names_[static_cast<std::size_t>(solver)];
  }
  std::string number(double value) const override { return cpp_double(value); }
  std::string comment(std::string_view text) const override { return comment_text(text); }
  static bool owns(const ir::Step& st, ir::StepMember member) {
    return ir::info(st.kind).member == member;
  }

  // The expression that names a datum's slot in `object`, e.g.
  // "d.scalar[slot::time]".
  std::string ref(int index, std::string_view object) const {
    const ir::Data& d = datum(index);
    std::string s(object);
    s.append(type_member(d.type))
        .append("[slot::")
        .append(data_names_[static_cast<std::size_t>(index)])
        .append("]");
    return s;
  }
  // Whether a step of controller kind `k` is in the program.
  bool uses_controller(int k) const {
    for (const ir::Step& st : p_.steps) {
      if (owns(st, ir::StepMember::Controller) && st.controller == k) return true;
    }
    return false;
  }
  // The path of a location's file ("" when unknown).
  std::string file_of(const SourceLoc& loc) const {
    if (files_ != nullptr && loc.file != 0 && loc.file < files_->size())
      return files_->path(loc.file);
    return {};
  }
  // "file:line:col" as messages quote it.
  std::string location(const SourceLoc& loc) const {
    if (!loc.known()) return "no source location";
    std::string s = file_of(loc);
    if (s.empty()) s = "<file " + std::to_string(loc.file) + ">";
    s.append(":").append(std::to_string(loc.line));
    if (loc.column != 0) s.append(":").append(std::to_string(loc.column));
    return s;
  }
  std::string where(const SourceLoc& loc) const {
    if (!loc.known()) return "(no source location)";
    std::string s;
    if (files_ != nullptr && loc.file != 0 && loc.file < files_->size()) {
      s = files_->path(loc.file);
    } else {
      s = "<file " + std::to_string(loc.file) + ">";
    }
    s.append(":").append(std::to_string(loc.line));
    if (loc.column != 0) s.append(":").append(std::to_string(loc.column));
    return comment_text(s);
  }
  void add_slots(mustache::Data& root) const {
    mustache::Data types = list();
    for (int t = 0; t < ir::kDataTypes; ++t) {
      const auto type = static_cast<DataType>(t);
      if (p_.count(type) == 0) continue;
      // By slot, so the listing reads like the arrays.
      std::vector<std::size_t> by_slot(static_cast<std::size_t>(p_.count(type)), p_.data.size());
      for (std::size_t i = 0; i < p_.data.size(); ++i) {
        if (p_.data[i].type == type) by_slot[static_cast<std::size_t>(p_.data[i].slot)] = i;
      }
      mustache::Data slots = list();
      for (const std::size_t i : by_slot) {
        if (i == p_.data.size()) continue;
        const ir::Data& d = p_.data[i];
        mustache::Data s;
        put(s, "name", data_names_[i]);
        put(s, "slot", std::to_string(d.slot));
        put(s, "iri", comment_text(d.iri));
        put(s, "has_unit", !d.unit.empty());
        put(s, "unit", comment_text(d.unit));
        append(slots, std::move(s));
      }
      mustache::Data entry;
      put(entry, "type", std::string(type_member(type)));
      put(entry, "count", std::to_string(p_.count(type)));
      put(entry, "slots", std::move(slots));
      append(types, std::move(entry));
    }
    put(root, "slot_types", std::move(types));
  }

  void add_model(mustache::Data& root) const {
    std::vector<std::string> inits;
    mustache::Data arms = list();
    for (std::size_t a = 0; a < p_.arms.size(); ++a) {
      const ir::ArmSolver& s = p_.arms[a];
      const ArmNames& n = arm_names_[a];
      const std::string& member = n.arm;
      mustache::Data e;
      put(e, "name", comment_text(s.name));
      put(e, "iri", comment_text(s.iri));
      put(e, "chain_iri", comment_text(s.chain_iri));
      put(e, "root", comment_text(s.chain.root()));
      put(e, "root_literal", cpp_string(s.chain.root()));
      put(e, "segments", std::to_string(s.chain.size()));
      put(e, "port", std::to_string(s.port));
      put(e, "member", member);
      put(e, "workspace", n.ws);
      put(e, "task", n.task);
      put(e, "X_BR", n.X_BR);
      put(e, "model_fn", n.model_fn);
      put(e, "X_RB_fn", n.X_RB_fn);
      put(e, "constraints", std::to_string(s.acceleration_constraints.size()));
      put(e, "gravity", join_doubles(s.gravity.data(), 3));
      put(e, "task_gravity",
          s.gravity_compensated ? "none (GravityCompensated: free directions keep their velocity)"
                                : "the same (free directions fall)");
      put(e, "X_RB_R", mat3(s.X_RB.R));
      put(e, "X_RB_p", vec3(s.X_RB.p));
      put(e, "has_mount", !s.mount_pose_iri.empty());
      put(e, "mount_iri", comment_text(s.mount_pose_iri));
      put(e, "tip_is_last_segment", s.tip_is_last_segment);
      put(e, "X_NT_R", mat3(s.chain.X_NT().R));
      put(e, "X_NT_p", vec3(s.chain.X_NT().p));
      mustache::Data segments = list();
      runtime::Chain rebuilt(s.chain.root());
      for (int i = 0; i < s.chain.size(); ++i) {
        const runtime::Segment& g = s.chain.segment(i);
        mustache::Data seg;
        put(seg, "link_literal", cpp_string(g.link));
        put(seg, "joint_literal", cpp_string(g.joint));
        put(seg, "joint_type", g.type == runtime::JointType::Revolute ? "Revolute" : "Prismatic");
        put(seg, "R", mat3(g.X_PJ.R));
        put(seg, "p", vec3(g.X_PJ.p));
        put(seg, "axis", vec3(g.axis_J));
        put(seg, "mass", cpp_double(g.inertia.mass));
        put(seg, "com", vec3(g.inertia.p_SoScm_S));
        put(seg, "inertia", mat3(g.inertia.I_Scm_S));
        put(seg, "lower", cpp_double(g.limits.lower));
        put(seg, "upper", cpp_double(g.limits.upper));
        put(seg, "velocity", cpp_double(g.limits.velocity));
        put(seg, "effort", cpp_double(g.limits.effort));
        put(seg, "armature", cpp_double(g.armature));
        append(segments, std::move(seg));
        runtime::Segment copy = g;
        rebuilt.add_segment(std::move(copy));
      }
      // The generated code rebuilds the chain with add_segment, exactly as here;
      // it must reproduce the IR's chain bit for bit (a composed identity can
      // turn a -0 into +0), or the tick would not match the interpreter's.
      for (int i = 0; i < s.chain.size(); ++i) {
        const runtime::Pose& want = s.chain.segment(i).X_PJ;
        const runtime::Pose& got = rebuilt.segment(i).X_PJ;
        if (!same_bits(want.R, got.R) || !same_bits(want.p, got.p)) {
          fail("arm '" + s.name + "': segment " + std::to_string(i) +
               "'s joint placement does not survive Chain::add_segment bit for bit");
        }
      }
      put(e, "chain_segments", std::move(segments));
      mustache::Data alpha = list();
      for (std::size_t k = 0; k < s.acceleration_constraints.size(); ++k) {
        mustache::Data c;
        put(c, "workspace", n.ws);
        put(c, "component", std::to_string(s.acceleration_constraints[k].component));
        put(c, "column", std::to_string(k));
        put(c, "iri", comment_text(s.acceleration_constraints[k].iri));
        append(alpha, std::move(c));
      }
      put(e, "alpha", std::move(alpha));
      append(arms, std::move(e));
      // The physical model (the solver's gravity: kinematics and the torque
      // command), the task model (the ACHD solve: no gravity when the solver
      // is GravityCompensated), the mount.
      const std::string gravity = "rt::Vec3(" + join_doubles(s.gravity.data(), 3) + ")";
      inits.push_back(member + "(" + n.model_fn + "(" + gravity + ", true))");
      inits.push_back(n.task + "(" + n.model_fn + "(" +
                      (s.gravity_compensated ? std::string("rt::Vec3::Zero()") : gravity) + ", " +
                      (s.tip_is_last_segment ? "false" : "true") + "))");
      inits.push_back(n.X_BR + "(" + n.X_RB_fn + "().inverse())");
    }
    put(root, "arms", std::move(arms));

    put(root, "has_base", p_.base.has_value());
    if (p_.base) {
      const ir::BaseSolver& b = *p_.base;
      put(root, "base_name", comment_text(b.name));
      put(root, "base_iri", comment_text(b.iri));
      put(root, "base_configuration", comment_text(b.configuration));
      const runtime::KeloConfig& c = b.config;
      mustache::Data drives = list();
      for (std::size_t i = 0; i < c.geometry.p_PoAi_P.size(); ++i) {
        mustache::Data d;
        put(d, "index", std::to_string(i));
        put(d, "pivot", join_doubles(c.geometry.p_PoAi_P[i].data(), 2));
        put(d, "drive_weight", cpp_double(c.drive_weight[i]));
        put(d, "align_force_weight", cpp_double(c.align_force_weight[i]));
        put(d, "align_moment_weight", cpp_double(c.align_moment_weight[i]));
        drives.append(std::move(d));
      }
      put(root, "drives", std::move(drives));
      put(root, "n_drives", std::to_string(c.geometry.p_PoAi_P.size()));
      put(root, "wheel_radius", cpp_double(c.geometry.wheel_radius));
      put(root, "wheel_distance", cpp_double(c.geometry.wheel_distance));
      put(root, "castor_offset", cpp_double(c.geometry.castor_offset));
      put(root, "rescale_reference", c.rescale_reference ? "true" : "false");
      inits.emplace_back("base(base_config())");
    }

    mustache::Data evaluators = list(), monitors = list();
    for (std::size_t i = 0; i < p_.steps.size(); ++i) {
      const ir::Step& st = p_.steps[i];
      if (!owns(st, ir::StepMember::Evaluator)) continue;
      const runtime::ConstraintSpec& c = st.constraint;
      mustache::Data e;
      put(e, "member", step_members_[i]);
      put(e, "iri", comment_text(st.iri));
      append(evaluators, std::move(e));
      std::string init = step_members_[i];
      init.append("(rt::ConstraintSpec{.kind = ").append(constraint_kind(c.kind));
      init.append(", .reference = ").append(cpp_double(c.reference));
      init.append(", .threshold = ").append(cpp_double(c.threshold));
      init.append(", .lower = ").append(cpp_double(c.lower));
      init.append(", .upper = ").append(cpp_double(c.upper));
      init.append(", .tolerance = ").append(cpp_double(c.tolerance));
      init.append("},\n        ").append(cpp_string(st.name)).append(")");
      inits.push_back(init);
    }
    // Controllers, kind by kind in the registry's order: each step's runtime
    // model, built from the kind's Spec with the step's parameter values.
    mustache::Data controller_kinds = list();
    const auto kinds = ir::controller_kinds();
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const ir::ControllerKind& kind = kinds[k];
      mustache::Data members = list();
      for (std::size_t i = 0; i < p_.steps.size(); ++i) {
        const ir::Step& st = p_.steps[i];
        if (!owns(st, ir::StepMember::Controller) || st.controller != static_cast<int>(k)) continue;
        mustache::Data e;
        put(e, "type", std::string(kind.model_type));
        put(e, "member", step_members_[i]);
        put(e, "iri", comment_text(st.iri));
        append(members, std::move(e));
        std::string init = step_members_[i];
        init.append("(rt::").append(kind.spec_type).append("{");
        for (std::size_t f = 0; f < kind.parameters.size(); ++f) {
          const ir::ControllerParameter& field = kind.parameters[f];
          if (f > 0) init.append(field.new_line ? ",\n                   " : ", ");
          init.append(".").append(field.member).append(" = ");
          const double v = st.parameters[f];
          if (field.enumerators.empty()) {
            init.append(cpp_double(v));
          } else {
            init.append("rt::").append(field.enum_type).append("::");
            init.append(field.enumerators.at(static_cast<std::size_t>(v)));
          }
        }
        init.append("},\n        ").append(cpp_string(st.name)).append(")");
        inits.push_back(init);
      }
      if (members.items().empty()) continue;
      mustache::Data e;
      put(e, "title", std::string(kind.title));
      put(e, "members", std::move(members));
      append(controller_kinds, std::move(e));
    }
    for (std::size_t i = 0; i < p_.steps.size(); ++i) {
      const ir::Step& st = p_.steps[i];
      if (!owns(st, ir::StepMember::MonitorTolerance)) continue;
      mustache::Data e;
      put(e, "member", step_members_[i]);
      put(e, "iri", comment_text(st.iri));
      put(e, "tolerance", cpp_double(st.constraint.tolerance));
      append(monitors, std::move(e));
    }
    put(root, "has_evaluators", !evaluators.items().empty());
    put(root, "evaluators", std::move(evaluators));
    put(root, "controller_kinds", std::move(controller_kinds));
    put(root, "has_monitors", !monitors.items().empty());
    put(root, "monitors", std::move(monitors));
    put(root, "has_initializers", !inits.empty());
    put(root, "initializers", initializer_list(inits));
  }

  static mustache::Data initializer_list(const std::vector<std::string>& inits) {
    mustache::Data l = list();
    for (std::size_t i = 0; i < inits.size(); ++i) {
      mustache::Data e;
      put(e, "text", inits[i]);
      put(e, "last", i + 1 == inits.size());
      append(l, std::move(e));
    }
    return l;
  }

  void add_data(mustache::Data& root) const {
    put(root, "n_scalar", std::to_string(p_.count(DataType::Scalar)));
    put(root, "n_vec3", std::to_string(p_.count(DataType::Vector3)));
    put(root, "n_pose", std::to_string(p_.count(DataType::Pose)));
    put(root, "n_twist", std::to_string(p_.count(DataType::Twist)));
    put(root, "n_wrench", std::to_string(p_.count(DataType::Wrench)));
    put(root, "n_flag", std::to_string(p_.count(DataType::Flag)));
    put(root, "n_event", std::to_string(p_.count(DataType::Event)));
    // Only programs that use inertias declare their array, so the others'
    // generated code does not change with the type's introduction.
    put(root, "has_inertia", p_.count(DataType::Inertia) > 0);
    put(root, "n_inertia", std::to_string(p_.count(DataType::Inertia)));
    // Controller state, one array per stateful kind the program uses.
    mustache::Data controller_states = list();
    const auto kinds = ir::controller_kinds();
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      if (!kinds[k].has_state() || !uses_controller(static_cast<int>(k))) continue;
      mustache::Data e;
      put(e, "type", std::string(kinds[k].state_type));
      put(e, "count", std::to_string(p_.controller_state_count(static_cast<int>(k))));
      put(e, "member", std::string(kinds[k].name));
      append(controller_states, std::move(e));
    }
    put(root, "controller_states", std::move(controller_states));
    put(root, "n_monitor_states",
        std::to_string(p_.states[static_cast<std::size_t>(ir::StateKind::Monitor)]));
    put(root, "n_motion_states",
        std::to_string(p_.states[static_cast<std::size_t>(ir::StateKind::Motion)]));

    std::vector<std::string> inits;
    for (std::size_t a = 0; a < p_.arms.size(); ++a) {
      inits.push_back(arm_names_[a].arm + "(m." + arm_names_[a].arm + ")");
      inits.push_back(arm_names_[a].ws + "(m." + arm_names_[a].arm + ", " +
                      std::to_string(p_.arms[a].acceleration_constraints.size()) + ")");
    }
    if (p_.base) inits.emplace_back("base(m.base)");
    put(root, "has_data_initializers", !inits.empty());
    put(root, "data_initializers", initializer_list(inits));

    // Model constants: values in Model (set by its constructor), copied into
    // their slots by Data's constructor once (as the interpreter does).
    mustache::Data constants = list();
    for (std::size_t i = 0; i < p_.data.size(); ++i) {
      const ir::Data& d = p_.data[i];
      if (d.value.empty() || d.type == DataType::Event) continue;  // events clear every tick
      const std::string member = mangle("value", d.name);
      std::string type, assign;
      switch (d.type) {
        case DataType::Scalar:
          type = "double";
          assign = member + " = " + cpp_double(d.value[0]) + ";";
          break;
        case DataType::Vector3:
          type = "rt::Vec3";
          assign = member + " = rt::Vec3(" + join_doubles(d.value.data(), 3) + ");";
          break;
        case DataType::Pose:
          type = "rt::Pose";
          assign = member + ".R << " + join_doubles(d.value.data(), 9) + ";\n  " + member +
                   ".p = rt::Vec3(" + join_doubles(d.value.data() + 9, 3) + ");";
          break;
        case DataType::Twist:
        case DataType::Wrench:
          type = "rt::Vec6";
          assign = member + " << " + join_doubles(d.value.data(), 6) + ";";
          break;
        case DataType::Flag:
          type = "bool";
          assign = member + " = " + (d.value[0] != 0.0 ? "true" : "false") + ";";
          break;
        case DataType::Event:
          break;
        case DataType::Inertia:
          type = "rt::RigidBodyInertia";
          assign = member + " = rt::rigid_body_inertia(std::array<double, 10>{" +
                   join_doubles(d.value.data(), 10) + "});";
          break;
      }
      mustache::Data c;
      put(c, "type", type);
      put(c, "member", member);
      put(c, "assign", assign);
      put(c, "copy", ref(static_cast<int>(i), "") + " = m." + member + ";");
      put(c, "name", comment_text(d.iri.empty() ? d.name : d.iri));
      put(c, "has_unit", !d.unit.empty());
      put(c, "unit", comment_text(d.unit));
      append(constants, std::move(c));
    }
    put(root, "has_constants", !constants.items().empty());
    put(root, "constants", std::move(constants));
  }

  void add_steps(mustache::Data& root) const {
    mustache::Data steps = list();
    for (std::size_t i = 0; i < p_.steps.size(); ++i) append(steps, step(i));
    put(root, "steps", std::move(steps));
  }

  mustache::Data step(std::size_t index) const {
    const ir::Step& st = p_.steps[index];
    mustache::Data s;
    put(s, "index", std::to_string(index));
    put(s, "kind", std::string(ir::kind_name(st)));
    put(s, "name", comment_text(st.name));
    put(s, "iri", comment_text(st.iri));
    put(s, "where", where(st.where));
    // A blank line, then what the block implements and where it is written.
    std::string header = "\n  // [";
    header.append(std::to_string(index)).append("] ").append(ir::kind_name(st)).append(" '");
    header.append(comment_text(st.name))
        .append("': ")
        .append(comment_text(st.iri))
        .append("\n  //     ");
    header.append(where(st.where));
    put(s, "header", header);
    put(s, ir::template_section(st.kind), true);
    ir::info(st.kind).emit(*this, st, index, s);
    return s;
  }

  void add_log(mustache::Data& root) const {
    mustache::Data log = list();
    for (std::size_t i = 0; i < p_.log.size(); ++i) {
      const ir::LogColumn& c = p_.log[i];
      const ir::Data& d = datum(c.data);
      std::string value;
      switch (d.type) {
        case DataType::Twist:
        case DataType::Wrench:
          if (c.component >= 0) {
            value = ref(c.data) + "[" + std::to_string(c.component) + "]";
          } else {
            value = "std::numeric_limits<double>::quiet_NaN()";
          }
          break;
        case DataType::Scalar:
          value = ref(c.data);
          break;
        case DataType::Flag:
          value = "(" + ref(c.data) + " ? 1.0 : 0.0)";
          break;
        case DataType::Event:
          value = "static_cast<double>(" + ref(c.data) + ")";
          break;
        default:
          value = "std::numeric_limits<double>::quiet_NaN()";
          break;
      }
      mustache::Data e;
      put(e, "index", std::to_string(i));
      put(e, "name_literal", cpp_string(c.name));
      put(e, "unit_literal", cpp_string(c.unit));
      put(e, "kind",
          std::string(c.kind == robot::LogColumnKind::Flag    ? "Flag"
                      : c.kind == robot::LogColumnKind::Event ? "Event"
                                                              : "Value"));
      put(e, "value", value);
      append(log, std::move(e));
    }
    put(root, "n_log", std::to_string(p_.log.size()));
    const std::vector<int> joints = ir::arm_joints(p_);
    std::string list;
    for (int n : joints) list += (list.empty() ? "" : ", ") + std::to_string(n);
    put(root, "n_arm_ports", std::to_string(joints.size()));
    put(root, "arm_joints", list);
    put(root, "log", std::move(log));
  }

  const ir::Program& p_;
  const SourceFiles* files_;
  std::vector<std::string> data_names_;    // by data index: its slot:: identifier
  std::vector<ArmNames> arm_names_;        // by arm solver index
  std::vector<std::string> step_members_;  // by step index: its Model member ("" if none)
};

// The Mustache spec's "standalone" rule, which mustache::render (like kainjow's
// Mustache before it) applies only to the sections that render: a line holding nothing but one
// section tag ({{#x}},
// {{^x}}, {{/x}}) or comment ({{! }}) leaves no trace in the output, neither
// its indentation nor its line break. Applied to the template text before
// parsing (the tag joins the start of the next line), so skipped sections
// leave no blank lines either. Templates put blank lines before a section tag,
// not after it.
std::string strip_standalone_tags(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    const bool has_newline = end != std::string_view::npos;
    if (!has_newline) end = text.size();
    const std::string_view line = text.substr(at, end - at);
    const std::size_t first = line.find_first_not_of(" \t");
    const std::size_t last = line.find_last_not_of(" \t");
    bool standalone = false;
    if (first != std::string_view::npos && line.substr(first, 2) == "{{" &&
        first + 2 < line.size() &&
        (line[first + 2] == '#' || line[first + 2] == '^' || line[first + 2] == '/' ||
         line[first + 2] == '!')) {
      const std::string_view tag = line.substr(first, last + 1 - first);
      standalone =
          tag.size() >= 5 && tag.substr(tag.size() - 2) == "}}" && tag.find("}}") == tag.size() - 2;
      if (standalone) out.append(tag);
    }
    if (!standalone) {
      out.append(line);
      if (has_newline) out.push_back('\n');
    }
    at = has_newline ? end + 1 : end;
  }
  return out;
}

// Blank lines of the rendered C++ as a person would leave them: at most one in
// a row, none after an opening brace or before a closing one. (Sections that
// render nothing leave their surrounding blank lines behind.)
std::string tidy_blank_lines(const std::string& text) {
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    lines.push_back(std::string_view(text).substr(at, end - at));
    at = end + 1;
  }
  const auto blank = [](std::string_view l) {
    return l.find_first_not_of(" \t") == std::string_view::npos;
  };
  std::string out;
  out.reserve(text.size());
  std::string_view previous = "{";  // no blank line at the top
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (blank(lines[i])) {
      std::size_t next = i + 1;
      while (next < lines.size() && blank(lines[next])) ++next;
      const std::string_view after = next < lines.size() ? lines[next] : std::string_view("}");
      // An indented closing brace, or a bare "}" / "};" (not "}  // namespace").
      const std::size_t first = after.find_first_not_of(" \t");
      const bool closes = first != std::string_view::npos && after[first] == '}' &&
                          (first > 0 || after == "}" || after == "};");
      if (blank(previous) || previous.back() == '{' || closes) continue;
      out.push_back('\n');
      previous = "";
      continue;
    }
    out.append(lines[i]).push_back('\n');
    previous = lines[i];
  }
  return out;
}

}  // namespace

std::vector<GeneratedFile> render(const ir::Program& program, const SourceFiles* files) {
  // The back-end trusts a verified program; one that is not is refused here,
  // every problem located.
  ir::verify(program, files);
  const mustache::Data data = Builder(program, files).build();
  std::vector<GeneratedFile> out;
  for (const Template& t : kTemplates) {
    std::string text;
    try {
      text = mustache::render(strip_standalone_tags(t.text), data);
    } catch (const Error& e) {
      std::string msg = "template ";
      msg.append(t.file).append(".mustache: ").append(e.diagnostic().message);
      fail(msg);
    }
    if (t.file.ends_with(".hpp") || t.file.ends_with(".cpp")) text = tidy_blank_lines(text);
    out.push_back({std::string(t.file), std::move(text)});
  }
  return out;
}

void generate(const ir::Program& program, const std::string& out_dir, const SourceFiles* files) {
  // A project there could not be built safely (build.hpp): refused before anything is written.
  std::error_code absolute_ec;
  const std::filesystem::path absolute = std::filesystem::absolute(out_dir, absolute_ec);
  check_cmake_path(absolute_ec ? out_dir : absolute.string(), "the output directory");
  const std::vector<GeneratedFile> rendered = render(program, files);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::string msg = "cannot create directory '";
    msg.append(out_dir).append("': ").append(ec.message());
    throw Error("io", msg);
  }
  for (const GeneratedFile& f : rendered) {
    write_output((std::filesystem::path(out_dir) / f.path).string(), f.content);
  }
}

}  // namespace mospec::codegen
