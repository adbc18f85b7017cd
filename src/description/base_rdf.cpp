#include "description/base_rdf.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>

#include "app/app.hpp"
#include "rdf/xsd.hpp"
#include "support/diagnostics.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::description {

namespace {

using rdf::TermId;

// Concatenation without operator+ chains (GCC 12's -Wrestrict misfires on
// them under -O2).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view p : parts) out.append(p);
  return out;
}

class Reader {
 public:
  Reader(const rdf::Dataset& d, BaseReading& out) : d_(d), out_(out) {}

  TermId id(std::string_view iri) const { return d_.terms().find_iri(iri); }
  TermId base(std::string_view local) const {
    return id(vocab::term(vocab::mospec_base::ns, local));
  }
  std::string name(TermId t) const {
    const rdf::Term& term = d_.terms()[t];
    return term.is_blank() ? cat({"_:", term.value}) : std::string(term.value);
  }

  // Objects of (s, p, ?) over every graph, each once, in statement order.
  std::vector<TermId> objects(TermId s, TermId p) const {
    std::vector<TermId> out;
    if (s.is_any() || p.is_any()) return out;
    for (uint32_t i : d_.match(s, p, TermId::any())) {
      const TermId o = d_.quads()[i].object;
      if (std::find(out.begin(), out.end(), o) == out.end()) out.push_back(o);
    }
    return out;
  }
  bool defined(TermId s) const {
    return !s.is_any() && !d_.match(s, TermId::any(), TermId::any()).empty();
  }
  bool has_type(TermId s, TermId type) const {
    const TermId p = id(vocab::rdf::type);
    if (p.is_any() || type.is_any()) return false;
    return !d_.match(s, p, type).empty();
  }

  void problem(BaseProblemKind kind, TermId entity, std::string message) {
    out_.problems.push_back({kind, entity, std::move(message)});
  }

  std::optional<double> literal_number(TermId lit) const {
    const rdf::Term& t = d_.terms()[lit];
    if (!t.is_literal()) return std::nullopt;
    auto v = rdf::xsd::number(t.value, d_.terms()[t.datatype].value);
    if (!v || !std::isfinite(*v)) return std::nullopt;
    return v;
  }

  // The one number `s` gives for `local` (a plain weight), else a problem.
  std::optional<double> weight(TermId s, std::string_view local) {
    const auto all = objects(s, base(local));
    std::optional<double> v;
    if (all.size() == 1) v = literal_number(all.front());
    if (!v) {
      problem(BaseProblemKind::MissingNumber, s,
              cat({"the castor drive '", name(s), "' needs exactly one ", local,
                   ", a number >= 0 (it has ",
                   all.empty()      ? "none"
                   : all.size() > 1 ? "several"
                                    : "one that is not a number",
                   ")"}));
    }
    return v;
  }

  // A length: `s`'s one `local`, a QUDT quantity with one unit, M, and a
  // numeric value [m].
  std::optional<double> length(TermId s, std::string_view local, std::string_view what) {
    const auto qs = objects(s, base(local));
    if (qs.size() != 1) {
      problem(BaseProblemKind::MissingNumber, s,
              cat({"'", name(s), "' needs exactly one ", local, " (", what,
                   "), a quantity in M; it has ",
                   qs.empty() ? std::string("none") : std::to_string(qs.size())}));
      return std::nullopt;
    }
    const TermId q = qs.front();
    const auto units = objects(q, id(vocab::qudt::unit));
    const std::string metre = vocab::term(vocab::qudt_unit::ns, "M");
    bool unit_ok = units.size() == 1 && d_.terms()[units.front()].value == metre;
    if (!unit_ok) {
      std::string got;
      for (TermId u : units) got += (got.empty() ? "" : ", ") + name(u);
      problem(BaseProblemKind::Unit, q,
              cat({"the ", local, " of '", name(s), "' ('", name(q),
                   "') must be in metres: exactly one unit, M (", metre, "); it has ",
                   got.empty() ? std::string("none") : got}));
    }
    const auto values = objects(q, id(vocab::qudt::value));
    std::optional<double> v;
    if (values.size() == 1) v = literal_number(values.front());
    if (!v) {
      problem(BaseProblemKind::MissingNumber, q,
              cat({"the ", local, " of '", name(s), "' ('", name(q),
                   "') needs exactly one numeric value [m]"}));
    }
    return unit_ok ? v : std::nullopt;
  }

  // The members of the RDF list at `head` (stops at rdf:nil, a broken cell or
  // after 1000 cells).
  std::vector<TermId> list(TermId head) const {
    std::vector<TermId> out;
    const TermId first = id(vocab::rdf::first), rest = id(vocab::rdf::rest),
                 nil = id(vocab::rdf::nil);
    for (TermId cell = head; cell != nil && out.size() < 1000;) {
      const auto f = objects(cell, first);
      const auto r = objects(cell, rest);
      if (f.size() != 1 || r.size() != 1) break;
      out.push_back(f.front());
      cell = r.front();
    }
    return out;
  }

 private:
  const rdf::Dataset& d_;
  BaseReading& out_;
};

}  // namespace

std::string_view to_string(BaseProblemKind kind) {
  switch (kind) {
    case BaseProblemKind::Undefined:
      return "undefined-configuration";
    case BaseProblemKind::MissingNumber:
      return "missing-base-number";
    case BaseProblemKind::Unit:
      return "base-unit";
    case BaseProblemKind::DriveCount:
      return "unsupported-drive-count";
    case BaseProblemKind::Degenerate:
      return "degenerate-base";
  }
  return "invalid-base";
}

BaseReading read_base(const rdf::Dataset& dataset, std::string_view base_iri) {
  BaseReading out;
  Reader r(dataset, out);
  const TermId b = r.id(base_iri);
  if (!r.defined(b)) {
    r.problem(BaseProblemKind::Undefined, b,
              cat({"the base configuration '", base_iri,
                   "' is defined by no loaded file: import the robot description that defines "
                   "it (the paper's base: https://mospec.example/robots/kelo-base.jsonld)"}));
    return out;
  }
  if (!r.has_type(b, r.base("CastorDriveBase"))) {
    r.problem(BaseProblemKind::Undefined, b,
              cat({"'", base_iri, "' is not a base configuration: give it the type ",
                   vocab::term(vocab::mospec_base::ns, "CastorDriveBase")}));
    return out;
  }
  runtime::KeloConfig& c = out.config;
  runtime::KeloGeometry& g = c.geometry;
  const auto radius = r.length(b, "wheel-radius", "of every drive's wheels");
  const auto distance = r.length(b, "wheel-distance", "between a drive's two wheels");
  const auto offset = r.length(b, "castor-offset", "from a drive's pivot axis to its wheel axle");
  if (radius) g.wheel_radius = *radius;
  if (distance) g.wheel_distance = *distance;
  if (offset) g.castor_offset = *offset;

  const auto heads = r.objects(b, r.base("drives"));
  if (heads.size() != 1) {
    r.problem(BaseProblemKind::MissingNumber, b,
              cat({"the base '", base_iri, "' needs exactly one list of drives; it has ",
                   std::to_string(heads.size())}));
    return out;
  }
  const std::vector<TermId> drives = r.list(heads.front());
  if (drives.size() < 2 || drives.size() > static_cast<size_t>(runtime::kMaxKeloDrives)) {
    r.problem(BaseProblemKind::DriveCount, b,
              cat({"the base '", base_iri, "' has ", std::to_string(drives.size()),
                   " drive(s), but a base needs 2 to ", std::to_string(runtime::kMaxKeloDrives),
                   " (two to push the platform in every direction; at most the runtime's "
                   "workspace, runtime::kMaxKeloDrives)"}));
    return out;
  }
  g.p_PoAi_P.assign(drives.size(), runtime::Vec2::Zero());
  c.drive_weight.assign(drives.size(), 1.0);
  c.align_force_weight.assign(drives.size(), 1.0);
  c.align_moment_weight.assign(drives.size(), 1.0);
  for (size_t i = 0; i < drives.size(); ++i) {
    const TermId d = drives[i];
    if (!r.has_type(d, r.base("CastorDrive"))) {
      r.problem(BaseProblemKind::Undefined, d,
                cat({"drive ", std::to_string(i), " of the base '", base_iri, "', '", r.name(d),
                     "', is ", r.defined(d) ? "not a CastorDrive" : "defined by no loaded file"}));
      continue;
    }
    const auto x = r.length(d, "pivot-x", "its pivot axis along x of the platform frame");
    const auto y = r.length(d, "pivot-y", "its pivot axis along y of the platform frame");
    if (x && y) g.p_PoAi_P[i] = runtime::Vec2(*x, *y);
    if (auto w = r.weight(d, "drive-weight")) c.drive_weight[i] = *w;
    if (auto w = r.weight(d, "force-alignment-weight")) c.align_force_weight[i] = *w;
    if (auto w = r.weight(d, "moment-alignment-weight")) c.align_moment_weight[i] = *w;
  }
  if (!out.problems.empty()) return out;
  try {
    const runtime::KeloModel check(c);
    (void)check;
  } catch (const Error& e) {
    r.problem(BaseProblemKind::Degenerate, b,
              cat({"the base '", base_iri, "' cannot distribute every platform wrench (Eq. 2-3): ",
                   e.diagnostic().message}));
  }
  return out;
}

runtime::KeloConfig load_base(const std::string& model_file, const std::string& base_iri,
                              const std::vector<std::pair<std::string, std::string>>& maps) {
  app::LoadOptions options;
  options.maps = maps;
  const app::LoadedModel model = app::load({model_file}, options);
  BaseReading reading = read_base(model.dataset(), base_iri);
  if (!reading.problems.empty()) {
    const BaseProblem& p = reading.problems.front();
    throw Error(std::string(to_string(p.kind)), cat({model_file, ": ", p.message}));
  }
  return reading.config;
}

}  // namespace mospec::description
