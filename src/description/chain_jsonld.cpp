#include "description/chain_jsonld.hpp"

#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include "support/diagnostics.hpp"

namespace mospec::description {

using namespace mospec::runtime;

namespace {

// Shortest text that reads back to the same double; -0 prints as 0.
std::string num(double v) {
  if (v == 0.0) return "0";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string list(const std::vector<std::string>& items) {
  std::string out = "[ ";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + " ]";
}

// One node: "key": value lines, four-space indented like the authors' models.
class Node {
 public:
  Node& add(std::string_view key, std::string value) {
    lines_.push_back("            " + quoted(key) + ": " + std::move(value));
    return *this;
  }
  std::string str() const {
    std::string out = "        {\n";
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      out += lines_[i] + (i + 1 < lines_.size() ? ",\n" : "\n");
    }
    return out + "        }";
  }

 private:
  std::vector<std::string> lines_;
};

std::vector<std::string> types(std::initializer_list<std::string_view> ts) {
  std::vector<std::string> out;
  for (auto t : ts) out.push_back(quoted(t));
  return out;
}

Node pose_node(const std::string& id, const std::string& of, const std::string& wrt,
               const Pose& X) {
  Node n;
  n.add("@id", quoted(id))
      .add("@type", list(types({"Pose", "PoseCoordinate", "DirectionCosineXYZ", "VectorXYZ"})))
      .add("of", quoted(of))
      .add("with-respect-to", quoted(wrt))
      .add("as-seen-by", quoted(wrt))
      .add("quantity-kind", list(types({"PlaneAngle", "Length"})))
      .add("unit", list(types({"UNITLESS", "M"})));
  const char* axis_keys[] = {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z"};
  for (int c = 0; c < 3; ++c) {
    n.add(axis_keys[c], list({num(X.R(0, c)), num(X.R(1, c)), num(X.R(2, c))}));
  }
  n.add("x", num(X.p.x())).add("y", num(X.p.y())).add("z", num(X.p.z()));
  return n;
}

void add_link(std::vector<Node>& graph, const std::string& link, const RigidInertia* inertia) {
  const std::string frame = "frame-" + link, origin = "point-" + link + "-origin";
  Node l;
  // The link's frame and origin are its simplices: how a reader finds the
  // link of a frame (and a frame of a link) without spelling IRIs.
  l.add("@id", quoted("link-" + link))
      .add("@type", list(types({"SimplicialComplex", "RigidBody"})))
      .add("simplices", list({quoted(frame), quoted(origin)}));
  graph.push_back(l);
  Node f;
  f.add("@id", quoted(frame)).add("@type", quoted("Frame")).add("origin", quoted(origin));
  graph.push_back(f);
  Node o;
  o.add("@id", quoted(origin)).add("@type", quoted("Point"));
  graph.push_back(o);
  if (inertia == nullptr) return;
  const std::string com = "point-" + link + "-com";
  Node c;
  c.add("@id", quoted(com)).add("@type", quoted("Point"));
  graph.push_back(c);
  Node p;
  p.add("@id", quoted("position-" + link + "-com"))
      .add("@type", list(types({"Position", "PositionCoordinate", "VectorXYZ"})))
      .add("of", quoted(com))
      .add("with-respect-to", quoted(origin))
      .add("as-seen-by", quoted(frame))
      .add("quantity-kind", quoted("Length"))
      .add("unit", quoted("M"))
      .add("x", num(inertia->p_SoScm_S.x()))
      .add("y", num(inertia->p_SoScm_S.y()))
      .add("z", num(inertia->p_SoScm_S.z()));
  graph.push_back(p);
  Node m;
  m.add("@id", quoted("mass-" + link))
      .add("@type", list(types({"Mass", "MassCoordinate"})))
      .add("of-body", quoted("link-" + link))
      .add("quantity-kind", quoted("Mass"))
      .add("unit", quoted("KiloGM"))
      .add("mass", num(inertia->mass));
  graph.push_back(m);
  const Mat3& I = inertia->I_Scm_S;
  Node r;
  r.add("@id", quoted("inertia-" + link))
      .add("@type", list(types({"RotationalInertia", "RotationalInertiaCoordinate",
                                "MomentOfInertiaXYZ", "ProductOfInertiaXYZ"})))
      .add("of-body", quoted("link-" + link))
      .add("about", quoted(com))
      .add("as-seen-by", quoted(frame))
      .add("quantity-kind", quoted("MomentOfInertia"))
      .add("unit", quoted("KiloGM-M2"))
      .add("ixx", num(I(0, 0)))
      .add("iyy", num(I(1, 1)))
      .add("izz", num(I(2, 2)))
      .add("ixy", num(I(0, 1)))
      .add("ixz", num(I(0, 2)))
      .add("iyz", num(I(1, 2)));
  graph.push_back(r);
}

}  // namespace

std::string chain_to_jsonld(const Chain& chain, const ChainJsonldOptions& options) {
  std::vector<Node> graph;
  add_link(graph, chain.root(), nullptr);
  std::vector<std::string> joints;
  std::string parent = chain.root();
  // Needs mospec's joint extension (mospec/joints.json): a prismatic joint.
  // Joint limits need the published secorolab extension and kc-stat.
  bool extension = false, limited = false;
  for (int i = 0; i < chain.size(); ++i) {
    const Segment& s = chain.segment(i);
    const bool slides = s.type == JointType::Prismatic;
    extension = extension || slides;
    add_link(graph, s.link, &s.inertia);
    const std::string attachment = "frame-" + s.joint + "-attachment";
    Node a;
    a.add("@id", quoted(attachment))
        .add("@type", quoted("Frame"))
        .add("origin", quoted("point-" + s.joint + "-attachment-origin"));
    graph.push_back(a);
    Node ao;
    ao.add("@id", quoted("point-" + s.joint + "-attachment-origin")).add("@type", quoted("Point"));
    graph.push_back(ao);
    graph.push_back(pose_node("pose-" + s.joint, attachment, "frame-" + parent, s.X_PJ));
    Node axis;
    axis.add("@id", quoted("axis-" + s.joint))
        .add("@type", list(types({"UnitVector", "DirectionCoordinate", "VectorXYZ"})))
        .add("as-seen-by", quoted(attachment))
        .add("x", num(s.axis_J.x()))
        .add("y", num(s.axis_J.y()))
        .add("z", num(s.axis_J.z()));
    graph.push_back(axis);
    Node j;
    j.add("@id", quoted("joint-" + s.joint))
        .add("@type", list(types({"Joint", slides ? "PrismaticJoint" : "RevoluteJoint"})))
        .add("between-attachments", list({quoted(attachment), quoted("frame-" + s.link)}))
        .add("common-axis", quoted("axis-" + s.joint));
    graph.push_back(j);
    joints.push_back(quoted("joint-" + s.joint));
    // The joint's limits (the URDF's <limit>): the published kc-ext:JointLimit,
    // typed also by the kind of quantity it limits, its bounds quantities with
    // kind and unit. The world file's actuation defaults to them. A URDF's
    // velocity and effort limits are magnitudes: -limit..limit.
    const JointLimits& lim = options.limits ? s.limits : JointLimits{};
    const struct {
      const char* id;
      const char* type;
      double lower, upper;
      const char* kind;
      const char* unit;
    } limits[] = {
        {"position-limit-", "kc-stat:JointPosition", lim.lower, lim.upper,
         slides ? "Length" : "Angle", slides ? "M" : "RAD"},
        {"velocity-limit-", "kc-stat:JointVelocity", -lim.velocity, lim.velocity,
         slides ? "LinearVelocity" : "AngularVelocity", slides ? "M-PER-SEC" : "RAD-PER-SEC"},
        {"effort-limit-", "kc-stat:JointForce", -lim.effort, lim.effort,
         slides ? "Force" : "Torque", slides ? "N" : "N-M"}};
    for (const auto& l : limits) {
      if (!std::isfinite(l.lower) || !std::isfinite(l.upper)) continue;
      const auto quantity = [&](double v) {
        return "{ \"@type\": \"Quantity\", \"quantity-kind\": " + quoted(l.kind) +
               ", \"unit\": " + quoted(l.unit) + ", \"value\": " + num(v) + " }";
      };
      Node n;
      n.add("@id", quoted(l.id + s.joint))
          .add("@type", list(types({"JointLimit", l.type})))
          .add("of-joint", quoted("joint-" + s.joint))
          .add("lower", quantity(l.lower))
          .add("upper", quantity(l.upper));
      graph.push_back(n);
      limited = true;
    }
    parent = s.link;
  }
  if (chain.tip() != parent) {
    // The tip link (a tool0, a flange: after folded fixed joints), its frame
    // posed relative to the last link's. Its mass is folded into that link,
    // so it is a link of its own only to name the tool: a task attaches
    // motion drivers to it and reads its pose and twist.
    add_link(graph, chain.tip(), nullptr);
    graph.push_back(
        pose_node("pose-" + chain.tip(), "frame-" + chain.tip(), "frame-" + parent, chain.X_NT()));
  }
  Node c;
  c.add("@id", quoted("chain")).add("@type", quoted("KinematicChain")).add("joints", list(joints));
  graph.push_back(c);

  const std::string& mm = options.metamodels;
  std::string out = "{\n    \"@context\": [\n";
  for (const char* ctx : {"geometry/structural-entities.json", "geometry/spatial-relations.json",
                          "geometry/coordinates.json", "kinematic-chain/structural-entities.json",
                          "newtonian-rigid-body-dynamics/structural-entities.json",
                          "newtonian-rigid-body-dynamics/coordinates.json", "qudt.json"}) {
    out += "        " + quoted(mm + ctx) + ",\n";
  }
  if (extension) out += "        " + quoted(mm + "mospec/joints.json") + ",\n";
  if (limited) {
    out += "        " + quoted(mm + "kinematic-chain/state.json") + ",\n";
    out += "        " +
           quoted(options.secorolab + "kinematic-chain/structural-entities-extension.json") + ",\n";
  }
  out += "        { \"@base\": " + quoted(options.base) + " }\n    ],\n";
  out += "    \"@id\": " + quoted(options.base) + ",\n";
  out += "    \"@graph\": [\n";
  for (std::size_t i = 0; i < graph.size(); ++i) {
    out += graph[i].str() + (i + 1 < graph.size() ? ",\n" : "\n");
  }
  out += "    ]\n}\n";
  return out;
}

}  // namespace mospec::description
