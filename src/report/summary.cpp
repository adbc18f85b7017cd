#include "report/summary.hpp"

#include <cmath>

#include "json/json.hpp"

namespace mospec::report {
namespace {

constexpr std::string_view kCode = "report";

// Reads the fields of one summary, each error located at the value (or, for
// a missing member, at its object).
class Reader {
 public:
  Reader(const SourceFiles& files) : files_(files) {}

  [[noreturn]] void fail(const json::Value& at, const std::string& message) const {
    const SourceLoc l = at.location();
    throw Error(std::string(kCode), message, files_.path(l.file), l.line, l.column);
  }

  void expect(const json::Value& v, json::Kind kind, std::string_view what,
              std::string_view should) const {
    if (v.kind() == kind) return;
    fail(v, std::string(what) + " is " + std::string(json::kind_name(v.kind())) +
                "; a run summary has " + std::string(should) +
                " there (write summaries with `mospec run --summary`)");
  }

  std::string string(const json::Value& object, std::string_view key, std::string_view what) const {
    const json::Value* v = object.get(key);
    if (!v) return {};
    expect(*v, json::Kind::String, what, "a string");
    return std::string(v->as_string());
  }

  bool boolean(const json::Value& object, std::string_view key, std::string_view what,
               bool absent) const {
    const json::Value* v = object.get(key);
    if (!v) return absent;
    expect(*v, json::Kind::Boolean, what, "true or false");
    return v->as_bool();
  }

  // A finite number, or nothing for null or a missing member.
  std::optional<double> number(const json::Value& object, std::string_view key,
                               std::string_view what) const {
    const json::Value* v = object.get(key);
    if (!v || v->is_null()) return std::nullopt;
    expect(*v, json::Kind::Number, what, "a number or null");
    if (!std::isfinite(v->as_number()))
      fail(*v, std::string(what) + " is not a finite number; a run summary writes null instead");
    return v->as_number();
  }

  // The elements of an array member (none when it is missing), each an object.
  const json::Array* objects(const json::Value& object, std::string_view key,
                             std::string_view what) const {
    const json::Value* v = object.get(key);
    if (!v) return nullptr;
    expect(*v, json::Kind::Array, what, "an array");
    for (const json::Value& e : v->as_array())
      expect(e, json::Kind::Object, std::string("an element of ") + std::string(what), "an object");
    return &v->as_array();
  }

 private:
  const SourceFiles& files_;
};

}  // namespace

Summary parse_summary(std::string_view text, const std::string& path, SourceFiles& files) {
  const uint32_t id = files.add(path);
  const json::Value root = json::parse(text, id, path);
  const Reader r(files);
  if (!root.is_object() || !root.get("verdict")) {
    r.fail(root,
           "not a run summary (a JSON object with a \"verdict\"): write it with `mospec run "
           "--sim --summary FILE.json`");
  }
  Summary s;
  const json::Value& verdict = *root.get("verdict");
  r.expect(verdict, json::Kind::Object, "\"verdict\"", "an object");
  s.status = r.string(verdict, "status", "verdict.status");
  if (s.status.empty()) s.status = "unknown";
  if (const json::Value* why = verdict.get("why")) {
    r.expect(*why, json::Kind::Array, "verdict.why", "an array of strings");
    for (const json::Value& w : why->as_array()) {
      r.expect(w, json::Kind::String, "an element of verdict.why", "a string");
      s.why.emplace_back(w.as_string());
    }
  }
  if (const json::Array* motions = r.objects(verdict, "motions", "verdict.motions")) {
    for (const json::Value& m : *motions) {
      MotionRow row;
      row.name = r.string(m, "name", "a motion's \"name\"");
      row.started_time = r.number(m, "started_time", "a motion's \"started_time\"");
      row.ended_time = r.number(m, "ended_time", "a motion's \"ended_time\"");
      row.ended_by = r.string(m, "ended_by", "a motion's \"ended_by\"");
      s.motions.push_back(std::move(row));
    }
  }
  if (const json::Array* constraints = r.objects(verdict, "constraints", "verdict.constraints")) {
    for (const json::Value& c : *constraints) {
      ConstraintRow row;
      row.name = r.string(c, "name", "a constraint's \"name\"");
      row.relation = r.string(c, "relation", "a constraint's \"relation\"");
      row.guard = r.boolean(c, "guard", "a constraint's \"guard\"", false);
      row.final_value = r.number(c, "final_value", "a constraint's \"final_value\"");
      row.final_error = r.number(c, "final_error", "a constraint's \"final_error\"");
      row.judged = r.boolean(c, "judged", "a constraint's \"judged\"", true);
      row.satisfied = r.boolean(c, "satisfied", "a constraint's \"satisfied\"", false);
      s.constraints.push_back(std::move(row));
    }
  }
  s.controller = r.string(root, "controller", "\"controller\"");
  if (const json::Value* d = root.get("duration")) {
    r.expect(*d, json::Kind::Number, "\"duration\"", "a number of seconds");
    if (!std::isfinite(d->as_number()) || d->as_number() < 0)
      r.fail(*d, "\"duration\" is " + exact_number(d->as_number()) +
                     "; a run lasts a finite, non-negative number of seconds");
    s.duration = d->as_number();
  }
  s.ticks = r.number(root, "ticks", "\"ticks\"");
  s.max_torque_ratio = r.number(root, "max_torque_ratio", "\"max_torque_ratio\"");
  if (const json::Array* events = r.objects(root, "events", "\"events\"")) {
    for (const json::Value& e : *events) {
      EventRow row;
      row.tick = r.number(e, "tick", "an event's \"tick\"");
      row.column = r.string(e, "event", "an event's \"event\"");
      row.what = e.get("reason") ? r.string(e, "reason", "an event's \"reason\"")
                                 : r.string(e, "edge", "an event's \"edge\"");
      s.events.push_back(std::move(row));
    }
  }
  s.scenario = r.string(root, "scenario", "\"scenario\"");
  if (const json::Value* log = root.get("log")) {
    r.expect(*log, json::Kind::Object, "\"log\"", "an object");
    if (const json::Value* units = log->get("units")) {
      r.expect(*units, json::Kind::Object, "log.units", "an object of column: unit");
      const json::Object& o = units->as_object();
      for (size_t i = 0; i < o.size(); ++i) {
        r.expect(o.value(i), json::Kind::String, "a unit of log.units", "a string");
        s.log.units[std::string(o.key(i))] = std::string(o.value(i).as_string());
      }
    }
    if (const json::Value* constraints = log->get("constraints")) {
      r.expect(*constraints, json::Kind::Object, "log.constraints", "an object of name: relation");
      const json::Object& o = constraints->as_object();
      for (size_t i = 0; i < o.size(); ++i) {
        const json::Value& c = o.value(i);
        r.expect(c, json::Kind::Object, "a constraint of log.constraints", "an object");
        plot::ConstraintInfo info;
        info.relation = r.string(c, "relation", "a constraint's \"relation\"");
        info.reference = r.number(c, "reference", "a constraint's \"reference\"");
        info.lower = r.number(c, "lower", "a constraint's \"lower\"");
        info.upper = r.number(c, "upper", "a constraint's \"upper\"");
        info.tolerance = r.number(c, "tolerance", "a constraint's \"tolerance\"");
        info.guard = r.boolean(c, "guard", "a constraint's \"guard\"", false);
        s.log.constraints[std::string(o.key(i))] = std::move(info);
      }
    }
  }
  return s;
}

}  // namespace mospec::report
