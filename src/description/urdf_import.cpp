#include "description/urdf_import.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <exception>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "description/xml_outline.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::description {

using namespace mospec::runtime;

namespace {

// Captures urdfdom's console_bridge errors during one parse so they end up in
// the thrown mospec::Error instead of on stderr. urdfdom logs an error and
// carries on for much of what it cannot read (a link whose <inertial> does not
// parse is kept, massless), so any error refuses the document.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::string quoted(std::string_view name) {
  std::string out(1, '\'');
  out += shown(name);
  out += '\'';
  return out;
}

// A sorted list of names for a message, cut after a few so that a URDF with
// thousands of links does not make a message of thousands of names.
std::string name_list(std::vector<std::string> names) {
  static constexpr std::size_t kShown = 20;
  std::sort(names.begin(), names.end());
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i) {
    if (i) out += ", ";
    out += shown(names[i]);
  }
  if (names.size() > kShown) out += ", ... (" + std::to_string(names.size() - kShown) + " more)";
  return out;
}

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) {
    if (!out.empty()) out += ' ';
    out += exact_number(v);
  }
  return out;
}

// Where refusals point: the elements of the scanned document by role, as
// urdfdom reads them (the <robot> root's <link> and <joint> children; of
// several children of one name, the first).
class Places {
 public:
  Places(const XmlOutline& outline, const std::string& source)
      : outline_(outline), source_(source) {
    for (int c = outline.elements[0].first_child; c >= 0; c = element(c).next_sibling) {
      const XmlElement& e = element(c);
      const bool is_link = e.name == "link", is_joint = e.name == "joint";
      if (!is_link && !is_joint) continue;
      auto& named = is_link ? links_ : joints_;
      const std::string* name = e.attribute("name");
      if (name == nullptr) {
        if (is_link && unnamed_link_ < 0) unnamed_link_ = c;
        if (is_joint && unnamed_joint_ < 0) unnamed_joint_ = c;
      } else if (!named.emplace(*name, c).second) {
        fail(c, std::string(is_link ? "link " : "joint ") + quoted(*name) +
                    " is defined twice (first at " + where(named.at(*name)) + ")");
      } else if (is_joint) {
        joint_order_.push_back(c);
      }
    }
  }

  const XmlElement& element(int i) const { return outline_.elements[static_cast<std::size_t>(i)]; }
  int link(const std::string& name) const { return find(links_, name); }
  int joint(const std::string& name) const { return find(joints_, name); }
  int unnamed_link() const { return unnamed_link_; }
  int unnamed_joint() const { return unnamed_joint_; }
  // The named <joint> elements in document order.
  const std::vector<int>& joints() const { return joint_order_; }
  // The first child named `name` of `parent`, else `parent` itself: the
  // nearest element that holds the offending value.
  int child_or_self(int parent, std::string_view name) const {
    if (parent < 0) return parent;
    const int c = outline_.first_child(parent, name);
    return c >= 0 ? c : parent;
  }
  std::string where(int i) const {
    return "line " + std::to_string(element(i).line) + ", column " +
           std::to_string(element(i).column);
  }

  // At the element when it is known, else naming only the file.
  [[noreturn]] void fail(int at, const std::string& message) const {
    if (at < 0) throw Error("invalid-urdf", message, source_);
    throw Error("invalid-urdf", message, source_, element(at).line, element(at).column);
  }

 private:
  static int find(const std::unordered_map<std::string, int>& map, const std::string& name) {
    const auto it = map.find(name);
    return it == map.end() ? -1 : it->second;
  }
  const XmlOutline& outline_;
  const std::string& source_;
  std::unordered_map<std::string, int> links_, joints_;
  std::vector<int> joint_order_;
  int unnamed_link_ = -1, unnamed_joint_ = -1;
};

// Where the name urdfdom quoted after `word` starts: past `word`, any spaces
// (it writes "for joint  [j]" in places) and the '['; npos when absent.
std::size_t bracket_after(const std::string& m, std::string_view word, std::size_t from = 0) {
  for (std::size_t w = m.find(word, from); w != std::string::npos; w = m.find(word, w + 1)) {
    std::size_t b = w + word.size();
    while (b < m.size() && m[b] == ' ') ++b;
    if (b < m.size() && m[b] == '[') return b + 1;
  }
  return std::string::npos;
}

// The <link> or <joint> whose name starts at `begin` in urdfdom's message: a
// name may hold ']' itself, so each of the next few ']' is tried as its end.
int bracketed(const std::string& m, std::size_t begin, bool joint, const Places& places) {
  if (begin == std::string::npos) return -1;
  int tries = 0;
  for (std::size_t e = m.find(']', begin); e != std::string::npos && tries < 16;
       e = m.find(']', e + 1), ++tries) {
    const std::string name = m.substr(begin, e - begin);
    const int at = joint ? places.joint(name) : places.link(name);
    if (at >= 0) return at;
  }
  return -1;
}

bool contains(const std::string& s, std::string_view part) {
  return s.find(part) != std::string::npos;
}

// The element one urdfdom message is about, or -1. urdfdom names links and
// joints in its messages ("... for Link [l1]", "Malformed axis element for
// joint [j1]: ..."), and says which part of them it could not read.
int element_of(const std::string& m, const std::vector<std::string>& all, const Places& places) {
  if (const std::size_t b = bracket_after(m, "] of joint"); b != std::string::npos) {
    const int joint = bracketed(m, b, true, places);
    return places.child_or_self(joint, contains(m, "child link [") ? "child" : "parent");
  }
  if (contains(m, "Two root links found")) {
    return bracketed(m, bracket_after(m, "] and"), false, places);
  }
  if (const std::size_t b = bracket_after(m, "Link"); b != std::string::npos) {
    const int link = bracketed(m, b, false, places);
    if (!contains(m, "inertial element")) return link;
    const int inertial = places.child_or_self(link, "inertial");
    // The messages before this one say which part of <inertial> failed.
    for (const std::string& before : all) {
      if (&before == &m) break;
      if (contains(before, "Inertial: mass")) return places.child_or_self(inertial, "mass");
      if (contains(before, "Inertial: inertia")) return places.child_or_self(inertial, "inertia");
      if (contains(before, "vector")) return places.child_or_self(inertial, "origin");
    }
    return inertial;
  }
  if (const std::size_t b = bracket_after(m, "oint"); b != std::string::npos) {  // j or J
    const int joint = bracketed(m, b, true, places);
    static constexpr std::pair<std::string_view, std::string_view> kParts[] = {
        {"origin element", "origin"},
        {"axis element", "axis"},
        {"limit element", "limit"},
        {"safety element", "safety_controller"},
        {"calibration element", "calibration"},
        {"mimic element", "mimic"},
        {"does not specify limits", "limit"},
        {"without limits", "limit"}};
    for (const auto& [part, child] : kParts) {
      if (contains(m, part)) return places.child_or_self(joint, child);
    }
    return joint;
  }
  if (contains(m, "No name given for the link")) return places.unnamed_link();
  if (contains(m, "unnamed joint")) return places.unnamed_joint();
  if (contains(m, "robot") || contains(m, "version") || contains(m, "No link elements") ||
      contains(m, "root link")) {
    return 0;
  }
  return -1;
}

// A URDF is a tree: every link the child of at most one joint, and no joint
// path leading back to where it started. urdfdom checks neither (it keeps one
// of two parents, and a cycle away from the root parses), and its links own
// their children, so a cycle would also never be freed. Checked on the
// document, before urdfdom builds anything.
void check_tree(const XmlOutline& outline, const Places& places) {
  struct Edge {
    std::string parent;
    int joint;
  };
  std::unordered_map<std::string, Edge> parent_of;  // child link -> its joint
  std::vector<const std::string*> children;         // in document order
  for (const int joint : places.joints()) {
    const int p = outline.first_child(joint, "parent"), c = outline.first_child(joint, "child");
    const std::string* parent = p >= 0 ? places.element(p).attribute("link") : nullptr;
    const std::string* child = c >= 0 ? places.element(c).attribute("link") : nullptr;
    if (parent == nullptr || child == nullptr) continue;  // urdfdom refuses it
    const auto [it, fresh] = parent_of.emplace(*child, Edge{*parent, joint});
    if (!fresh) {
      const int first = std::min(it->second.joint, joint),
                second = std::max(it->second.joint, joint);
      places.fail(second, "link " + quoted(*child) + " is the child of joints " +
                              quoted(*places.element(first).attribute("name")) + " (" +
                              places.where(first) + ") and " +
                              quoted(*places.element(second).attribute("name")) +
                              "; a URDF is a tree, each link has one parent joint");
    }
    children.push_back(&it->first);
  }
  // Walk up from every link once; a walk that meets itself is a cycle.
  std::unordered_map<std::string, int> walk_of;  // link -> the walk that visited it
  int walk = 0;
  for (const std::string* start : children) {
    ++walk;
    for (std::string link = *start;;) {
      const auto [visited, fresh] = walk_of.emplace(link, walk);
      if (!fresh) {
        if (visited->second != walk) break;  // an earlier walk went on from here
        const int joint = parent_of.at(link).joint;
        places.fail(joint, "joint " + quoted(*places.element(joint).attribute("name")) +
                               " closes a cycle through link " + quoted(link) +
                               "; a URDF is a tree");
      }
      const auto up = parent_of.find(link);
      if (up == parent_of.end()) break;
      link = up->second.parent;
    }
  }
}

// Frees urdfdom's model without recursion: each link owns its children, so a
// chain of thousands of links would otherwise be freed one nested destructor
// per link. The model's map still holds every link while this runs.
struct FlattenOnExit {
  urdf::ModelInterface* model;
  ~FlattenOnExit() {
    if (model == nullptr) return;
    for (auto& [name, link] : model->links_) {
      link->child_links.clear();
      link->child_joints.clear();
    }
  }
};

// Why a body's mass properties are not physical, or empty. A stated <mass>
// must be > 0 (`mass_required`); a folded result may be 0 (a massless link
// with massless links folded into it).
std::string inertia_problem(double mass, const Vec3& com, const Mat3& I, bool mass_required) {
  if (!std::isfinite(mass) || mass < 0.0 || (mass_required && mass == 0.0)) {
    return std::string("the mass is ") + exact_number(mass) + " kg; it must be finite and " +
           (mass_required ? "> 0 (a massless link has no <inertial>)" : ">= 0");
  }
  if (!com.allFinite()) {
    return "the centre of mass (" + numbers({com.x(), com.y(), com.z()}) + ") is not finite";
  }
  if (!I.allFinite()) {
    return "the rotational inertia (ixx iyy izz ixy ixz iyz = " +
           numbers({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}) + ") is not finite";
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(I, Eigen::EigenvaluesOnly);
  const Vec3 m = eig.eigenvalues();  // ascending
  // Relative: CAD exports round their inertias; a physical body's principal
  // moments are non-negative and each at most the sum of the other two.
  const double tolerance = 1e-9 * std::max(std::abs(m(2)), std::abs(m(0)));
  if (m(0) < -tolerance) {
    return "the rotational inertia is not positive semi-definite (principal moments " +
           numbers({m(0), m(1), m(2)}) + " kg m^2)";
  }
  if (m(0) + m(1) < m(2) - tolerance) {
    return "the rotational inertia's principal moments " + numbers({m(0), m(1), m(2)}) +
           " kg m^2 break the triangle inequality (the largest exceeds the sum of the other two, "
           "which no body can)";
  }
  return {};
}

std::string pose_problem(const Pose& X) {
  if (!X.p.allFinite()) {
    return "its position (" + numbers({X.p.x(), X.p.y(), X.p.z()}) + ") is not finite";
  }
  if (!X.R.allFinite() || (X.R * X.R.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
      X.R.determinant() < 0.0) {
    return "its rotation is not a rotation (not finite or not orthonormal)";
  }
  return {};
}

// urdf::Pose -> Pose, refusing at `at` what is not a rigid transform.
Pose to_pose(const urdf::Pose& p, const Places& places, int at, const std::string& what) {
  const urdf::Rotation& r = p.rotation;
  const Eigen::Quaterniond q(r.w, r.x, r.y, r.z);
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-6) {
    places.fail(at, what + ": its rotation is degenerate (quaternion x y z w = " +
                        numbers({r.x, r.y, r.z, r.w}) + ")");
  }
  Pose X;
  X.R = q.normalized().toRotationMatrix();
  X.p = Vec3(p.position.x, p.position.y, p.position.z);
  if (const std::string problem = pose_problem(X); !problem.empty()) {
    places.fail(at, what + ": " + problem);
  }
  return X;
}

// The link's inertia in its own frame L: URDF gives it about the CoM in the
// frame of <inertial><origin> (rotated by its rpy). Every stated number and
// every result is checked, at the element that states it.
RigidInertia to_inertia(const urdf::Link& link, const Places& places) {
  RigidInertia I;
  if (!link.inertial) return I;
  const int inertial = places.child_or_self(places.link(link.name), "inertial");
  const std::string what = "link " + quoted(link.name);
  const urdf::Inertial& in = *link.inertial;
  Mat3 I_C;
  I_C << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  if (const std::string p = inertia_problem(in.mass, Vec3::Zero(), Mat3::Zero(), true);
      !p.empty()) {
    places.fail(places.child_or_self(inertial, "mass"), what + ": " + p);
  }
  if (const std::string p = inertia_problem(in.mass, Vec3::Zero(), I_C, true); !p.empty()) {
    places.fail(places.child_or_self(inertial, "inertia"), what + ": " + p);
  }
  const Pose X_LC = to_pose(in.origin, places, places.child_or_self(inertial, "origin"),
                            what + ": <inertial><origin>");
  I.mass = in.mass;
  I.p_SoScm_S = X_LC.p;
  I.I_Scm_S = X_LC.R * I_C * X_LC.R.transpose();
  if (const std::string p = inertia_problem(I.mass, I.p_SoScm_S, I.I_Scm_S, true); !p.empty()) {
    places.fail(inertial, what + ": rotated into the link frame, " + p);
  }
  return I;
}

// The joint axis as a unit vector; scaled before normalising so that large
// components do not overflow the norm.
Vec3 unit_axis(const urdf::Joint& joint, const Places& places, int at) {
  const Vec3 axis(joint.axis.x, joint.axis.y, joint.axis.z);
  const double scale = axis.cwiseAbs().maxCoeff();
  const std::string what =
      "joint " + quoted(joint.name) + ": axis (" + numbers({axis.x(), axis.y(), axis.z()}) + ")";
  if (!std::isfinite(scale)) places.fail(at, what + " is not finite");
  if (!(scale > 0.0)) places.fail(at, what + " is zero");
  const Vec3 unit = (axis / scale).normalized();
  if (!unit.allFinite() || std::abs(unit.norm() - 1.0) > 1e-9) {
    places.fail(at, what + " does not normalise to a unit vector");
  }
  return unit;
}

void check_limits(const urdf::Joint& joint, const Places& places, int at) {
  const urdf::JointLimits& l = *joint.limits;
  const std::string what = "joint " + quoted(joint.name) + ": <limit> ";
  if (joint.type != urdf::Joint::CONTINUOUS && !(l.lower <= l.upper)) {
    places.fail(
        at, what + "lower " + exact_number(l.lower) + " exceeds upper " + exact_number(l.upper));
  }
  if (!(l.velocity >= 0.0) || !(l.effort >= 0.0)) {
    places.fail(at, what + "velocity " + exact_number(l.velocity) + " and effort " +
                        exact_number(l.effort) + " must be >= 0");
  }
}

// Link and joint names become parts of the written model's IRIs ("link-" +
// name, relative to the base) and of its JSON strings: a space, a quote, a
// line break, a '#' or a ':' (which would make "link-x:y" an absolute IRI of
// scheme "link-x") would write a model that does not load, or loads as
// something else.
void check_name(const std::string& name, const char* kind, const Places& places, int at) {
  const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
           c == '.' || c == '_' || c == '~';
  });
  if (!ok) {
    places.fail(at, std::string(kind) + " " + quoted(name) +
                        ": the names of the chain's links and joints become IRIs of the written "
                        "model and may hold only letters, digits and - . _ ~ (rename it)");
  }
}

urdf::ModelInterfaceSharedPtr parse(const std::string& urdf_xml, const Places& places) {
  CapturingHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(urdf_xml);
  } catch (const std::exception& e) {
    handler.messages.push_back(e.what());
  }
  console_bridge::restorePreviousOutputHandler();
  if (model && handler.messages.empty()) return model;
  const FlattenOnExit flatten{model.get()};
  std::string text;
  int at = -1;
  for (const std::string& m : handler.messages) {
    if (!text.empty()) text += "; ";
    // urdfdom's messages quote the names and values it read; whole, but cut
    // past a length no honest message reaches.
    text += shown(m, 400);
    if (at < 0) at = element_of(m, handler.messages, places);
  }
  places.fail(at, "urdfdom cannot read the URDF: " + (text.empty() ? "it gives no reason" : text));
}

}  // namespace

UrdfChain import_urdf(const std::string& urdf_xml, const std::string& root_link,
                      const std::string& tip_link, const std::string& source) {
  const XmlOutline outline = scan_xml(urdf_xml, source);
  if (outline.elements[0].name != "robot") {
    throw Error(
        "invalid-urdf",
        "the root element is <" + shown(outline.elements[0].name) + ">; a URDF's is <robot>",
        source, outline.elements[0].line, outline.elements[0].column);
  }
  const Places places(outline, source);
  check_tree(outline, places);
  const urdf::ModelInterfaceSharedPtr model = parse(urdf_xml, places);
  const FlattenOnExit flatten{model.get()};

  const std::string root = root_link.empty() ? model->getRoot()->name : root_link;
  std::string tip = tip_link;
  if (tip.empty()) {
    std::vector<std::string> leaves;
    for (const auto& [name, link] : model->links_)
      if (link->child_links.empty()) leaves.push_back(name);
    if (leaves.size() != 1) {
      places.fail(0, "robot " + quoted(model->getName()) + " has " + std::to_string(leaves.size()) +
                         " leaf links (" + name_list(leaves) + "); name the chain's tip link");
    }
    tip = leaves.front();
  }
  const std::string* const names[] = {&root, &tip};
  for (const std::string* name : names) {
    if (!model->getLink(*name)) {
      std::vector<std::string> links;
      for (const auto& [n, link] : model->links_) links.push_back(n);
      places.fail(0, "robot " + quoted(model->getName()) + " has no link " + quoted(*name) +
                         " (links: " + name_list(links) + ")");
    }
  }
  // Walk up from the tip; the joints on the path, tip first. check_tree
  // excluded cycles; the bound keeps this loop finite whatever urdfdom built.
  std::vector<urdf::JointConstSharedPtr> path;
  for (urdf::LinkConstSharedPtr link = model->getLink(tip); link->name != root;) {
    if (!link->parent_joint || path.size() > model->links_.size()) {
      places.fail(places.link(tip), "link " + quoted(root) + " is not an ancestor of link " +
                                        quoted(tip) + " (the path from " + quoted(tip) +
                                        " ends at the root link " + quoted(link->name) + ")");
    }
    path.push_back(link->parent_joint);
    link = model->getLink(link->parent_joint->parent_link_name);
  }
  std::reverse(path.begin(), path.end());

  check_name(root, "link", places, places.link(root));
  for (const auto& joint : path) {
    check_name(joint->name, "joint", places, places.joint(joint->name));
    check_name(joint->child_link_name, "link", places, places.link(joint->child_link_name));
  }

  Chain chain(root);
  for (const auto& joint : path) {
    const int at = places.joint(joint->name);
    const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
    const Pose X_PJ =
        to_pose(joint->parent_to_joint_origin_transform, places, places.child_or_self(at, "origin"),
                "joint " + quoted(joint->name) + ": <origin>");
    const RigidInertia inertia = to_inertia(*child, places);
    const bool fixed = joint->type == urdf::Joint::FIXED;
    if (!fixed && joint->type != urdf::Joint::REVOLUTE && joint->type != urdf::Joint::CONTINUOUS &&
        joint->type != urdf::Joint::PRISMATIC) {
      places.fail(at, "joint " + quoted(joint->name) +
                          ": only revolute, continuous, prismatic and fixed joints can be in a "
                          "chain (floating and planar joints have more than one degree of "
                          "freedom)");
    }
    Segment s;
    if (!fixed) {
      s.link = child->name;
      s.joint = joint->name;
      s.type = joint->type == urdf::Joint::PRISMATIC ? JointType::Prismatic : JointType::Revolute;
      s.X_PJ = X_PJ;
      s.axis_J = unit_axis(*joint, places, places.child_or_self(at, "axis"));
      s.inertia = inertia;
      if (joint->limits) {
        check_limits(*joint, places, places.child_or_self(at, "limit"));
        if (joint->type != urdf::Joint::CONTINUOUS) {
          s.limits.lower = joint->limits->lower;
          s.limits.upper = joint->limits->upper;
        }
        s.limits.velocity = joint->limits->velocity;
        s.limits.effort = joint->limits->effort;
      }
    }
    // Folding composes this joint's origin with those before it and merges
    // the link's inertia into the segment's: both are checked again after.
    const std::string what = fixed && chain.size() > 0
                                 ? "fixed joint " + quoted(joint->name) + " folds link " +
                                       quoted(child->name) + " into link " +
                                       quoted(chain.segment(chain.size() - 1).link)
                                 : "joint " + quoted(joint->name);
    try {
      if (fixed) {
        chain.add_fixed(child->name, X_PJ, inertia);
      } else {
        chain.add_segment(std::move(s));
      }
    } catch (const Error& e) {
      // add_segment's messages name the joint already.
      places.fail(at, (fixed ? what + ": " : "") + e.diagnostic().message);
    }
    if (chain.size() > 0) {
      const Segment& last = chain.segment(chain.size() - 1);
      const RigidInertia& merged = last.inertia;
      if (const std::string p =
              inertia_problem(merged.mass, merged.p_SoScm_S, merged.I_Scm_S, false);
          !p.empty()) {
        places.fail(at, what + ": the merged inertia of link " + quoted(last.link) + ": " + p);
      }
      if (const std::string p = pose_problem(last.X_PJ); !p.empty()) {
        places.fail(at, what + ": composed with the fixed joints before it, the origin: " + p);
      }
    }
    if (const std::string p = pose_problem(chain.X_NT()); !p.empty()) {
      places.fail(at, what + ": composed with the fixed joints before it, the tip pose: " + p);
    }
  }
  UrdfChain out{std::move(chain), model->getName(), {}};
  // The fixed joints between the last moving link and the tip, tip last.
  for (const auto& joint : path) {
    if (joint->type != urdf::Joint::FIXED) {
      out.tip_joints.clear();
    } else {
      out.tip_joints.push_back(joint->name);
    }
  }
  return out;
}

Chain chain_from_urdf(const std::string& urdf_xml, const std::string& root, const std::string& tip,
                      const std::string& source) {
  return import_urdf(urdf_xml, root, tip, source).chain;
}

UrdfChain import_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip) {
  return import_urdf(read_file(path), root, tip, path);
}

Chain chain_from_urdf_file(const std::string& path, const std::string& root,
                           const std::string& tip) {
  return import_urdf_file(path, root, tip).chain;
}

}  // namespace mospec::description
