#include "diagnostic_cases.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <sstream>

#include "app/app.hpp"
#include "default_robot_ports.hpp"
#include "ir/lower.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "validation/model_validation.hpp"

namespace fs = std::filesystem;

namespace mospec::test {

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out.push_back(line);
  }
  return out;
}

std::string trim(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  size_t k = 0;
  while (k < s.size() && std::isspace(static_cast<unsigned char>(s[k]))) ++k;
  return s.substr(k);
}

// The one line of `file` containing `needle` (1-based), or an explanation.
uint32_t find_line(const fs::path& file, const std::string& needle, std::string& problem) {
  std::string text;
  if (std::string why = read_file_reason(file.string(), text); !why.empty()) {
    problem = why;
    return 0;
  }
  uint32_t found = 0, count = 0, n = 0;
  for (const std::string& line : split_lines(text)) {
    ++n;
    if (line.find(needle) == std::string::npos) continue;
    if (++count == 1) found = n;
  }
  if (count == 1) return found;
  problem = count == 0 ? "no line of " + file.filename().string() + " contains {{" + needle + "}}"
                       : std::to_string(count) + " lines of " + file.filename().string() +
                             " contain {{" + needle + "}}; make the text unique";
  return 0;
}

fs::path canonical_or_same(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? p : c;
}

// "model.json:12" relative to the case directory (or the path as reported).
std::string show_location(const fs::path& file, uint32_t line, const fs::path& case_dir) {
  if (file.empty()) return "-";
  std::error_code ec;
  fs::path rel = fs::relative(file, case_dir, ec);
  std::string name = ec || rel.empty() ? file.string() : rel.string();
  return name + ":" + std::to_string(line);
}

}  // namespace

Expectations parse_expectations(const std::string& text, const fs::path& case_dir) {
  Expectations out;
  int n = 0;
  for (const std::string& raw : split_lines(text)) {
    ++n;
    const std::string line = trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const auto fail = [&](const std::string& why) {
      out.errors.push_back("expected.txt:" + std::to_string(n) + ": " + why + "\n    " + raw);
    };
    if (line.rfind("validation:", 0) == 0) {
      const std::string v = trim(line.substr(11));
      if (out.validation != Expectations::Validation::Unstated) {
        fail("`validation:` is stated twice");
      } else if (v == "clean") {
        out.validation = Expectations::Validation::Clean;
      } else if (v == "refused") {
        out.validation = Expectations::Validation::Refused;
      } else {
        fail("`validation:` is `clean` or `refused`, not `" + v + "`");
      }
      continue;
    }
    // FILE:LOCATOR: error[CODE]: TEXT
    ExpectedDiagnostic e;
    e.spelled = line;
    e.source_line = n;
    const size_t colon = line.find(':');
    if (colon == std::string::npos || colon == 0) {
      fail("expected `FILE:LINE: error[CODE]: MESSAGE` (LINE a number or {{TEXT}})");
      continue;
    }
    const std::string file = line.substr(0, colon);
    std::string rest = line.substr(colon + 1);
    if (file != "-") {
      e.file = canonical_or_same(case_dir / file);
      size_t end = 0;
      if (rest.rfind("{{", 0) == 0) {
        const size_t close = rest.find("}}:");
        if (close == std::string::npos) {
          fail("a {{TEXT}} locator ends with `}}:`");
          continue;
        }
        std::string problem;
        e.line = find_line(e.file, rest.substr(2, close - 2), problem);
        if (!e.line) {
          fail(problem);
          continue;
        }
        end = close + 3;
      } else {
        while (end < rest.size() && std::isdigit(static_cast<unsigned char>(rest[end]))) ++end;
        if (end == 0 || end >= rest.size() || rest[end] != ':') {
          fail("after `" + file + ":` comes a line number or {{TEXT}}, then `:`");
          continue;
        }
        e.line = static_cast<uint32_t>(std::stoul(rest.substr(0, end)));
        ++end;
      }
      rest = rest.substr(end);
    }
    rest = trim(rest);
    const size_t close = rest.find("]:");
    size_t open = 0;
    for (Severity sev : {Severity::Error, Severity::Warning, Severity::Note}) {
      const std::string tag = std::string(to_string(sev)) + "[";
      if (rest.rfind(tag, 0) == 0) {
        e.severity = sev;
        open = tag.size();
      }
    }
    if (open == 0 || close == std::string::npos) {
      fail(
          "expected `error[CODE]: MESSAGE`, `warning[CODE]: MESSAGE` or `note[CODE]: MESSAGE` "
          "after the location");
      continue;
    }
    e.code = rest.substr(open, close - open);
    e.text = trim(rest.substr(close + 2));
    if (e.code.empty() || e.text.empty()) {
      fail("a code and a message substring are both needed");
      continue;
    }
    out.diagnostics.push_back(std::move(e));
  }
  if (out.validation == Expectations::Validation::Unstated)
    out.errors.push_back("expected.txt: states no `validation: clean|refused`");
  if (out.diagnostics.empty() && out.errors.empty())
    out.errors.push_back("expected.txt: expects no diagnostic; a case tests at least one");
  return out;
}

CaseResult check_case(const fs::path& source_dir, const fs::path& case_dir,
                      std::string expected_text) {
  CaseResult result;
  std::ostringstream report;
  const std::string name = case_dir.filename().string();
  if (expected_text.empty()) {
    if (std::string why = read_file_reason((case_dir / "expected.txt").string(), expected_text);
        !why.empty()) {
      result.report = name + ": cannot read expected.txt: " + why + "\n";
      return result;
    }
  }
  const Expectations expected = parse_expectations(expected_text, case_dir);
  if (!expected.errors.empty()) {
    report << name << ": the expectations are ill-formed:\n";
    for (const std::string& e : expected.errors) report << "  " << e << "\n";
    result.report = report.str();
    return result;
  }

  std::vector<Diagnostic> got;
  bool validation_clean = false;
  std::string validation_text;
  try {
    app::LoadOptions options;
    options.root = source_dir.string();
    app::LoadedModel model = app::load({(case_dir / "app.json").string()}, options);
    validation::ModelValidation v = validation::validate_model(model, {});
    validation_clean =
        v.report.count(shacl::Level::Violation) == 0 && v.report.count(shacl::Level::Other) == 0;
    if (!validation_clean) validation_text = shacl::to_text(v.report, &model.files());
    DiagnosticSink warnings;
    ir::LowerOptions lower_options;
    lower_options.ports = testing::default_robot_ports();
    lower_options.warnings = &warnings;
    try {
      ir::lower(model, lower_options);
    } catch (const ir::LowerError& e) {
      got = e.diagnostics();
      // Lowering's errors are thrown together under one code of their own.
      if (e.code() != "lowering-failed") {
        result.report = name + ": lowering threw [" + e.code() + "], not [lowering-failed]\n";
        return result;
      }
    }
    got.insert(got.end(), warnings.diagnostics().begin(), warnings.diagnostics().end());
  } catch (const Error& e) {
    result.report = name + ": the case does not load: " + e.what() + "\n";
    return result;
  }

  bool ok = true;
  const bool want_clean = expected.validation == Expectations::Validation::Clean;
  if (want_clean != validation_clean) {
    ok = false;
    report << "  validation: expected " << (want_clean ? "clean" : "refused") << ", got "
           << (validation_clean ? "clean" : "refused") << "\n";
    if (!validation_text.empty()) {
      std::istringstream in(validation_text);
      for (std::string l; std::getline(in, l);) report << "    " << l << "\n";
    }
  }

  // Match expectations to reported diagnostics one to one: same file, line
  // and code, and the message contains the text ("^TEXT": starts with it).
  // A maximum bipartite matching (augmenting paths), so a loose expectation
  // never takes the diagnostic a stricter one needs.
  const auto fits = [&](const ExpectedDiagnostic& e, const Diagnostic& d) {
    const bool anchored = e.text[0] == '^';
    const size_t at = d.message.find(anchored ? e.text.substr(1) : e.text);
    if (d.code != e.code || at == std::string::npos || (anchored && at != 0)) return false;
    if (e.severity != d.severity) return false;
    if (e.file.empty()) return d.file.empty();
    return !d.file.empty() && canonical_or_same(d.file) == e.file && d.line == e.line;
  };
  const size_t n_expected = expected.diagnostics.size();
  std::vector<std::vector<size_t>> candidates(n_expected);
  for (size_t k = 0; k < n_expected; ++k) {
    for (size_t i = 0; i < got.size(); ++i) {
      if (fits(expected.diagnostics[k], got[i])) candidates[k].push_back(i);
    }
  }
  std::vector<int> owner(got.size(), -1);  // diagnostic -> expectation
  std::function<bool(size_t, std::vector<char>&)> augment = [&](size_t k, std::vector<char>& seen) {
    for (size_t i : candidates[k]) {
      if (seen[i]) continue;
      seen[i] = 1;
      if (owner[i] < 0 || augment(static_cast<size_t>(owner[i]), seen)) {
        owner[i] = static_cast<int>(k);
        return true;
      }
    }
    return false;
  };
  std::vector<char> found(n_expected, 0);
  for (size_t k = 0; k < n_expected; ++k) {
    std::vector<char> seen(got.size(), 0);
    augment(k, seen);
  }
  for (int k : owner) {
    if (k >= 0) found[static_cast<size_t>(k)] = 1;
  }
  std::vector<char> used(got.size(), 0);
  for (size_t i = 0; i < got.size(); ++i) used[i] = owner[i] >= 0;
  std::vector<const ExpectedDiagnostic*> missing;
  std::vector<std::string> matched;
  for (size_t k = 0; k < n_expected; ++k) {
    if (found[k]) {
      matched.push_back(expected.diagnostics[k].spelled);
    } else {
      missing.push_back(&expected.diagnostics[k]);
      ok = false;
    }
  }
  std::vector<const Diagnostic*> unexpected;
  for (size_t i = 0; i < got.size(); ++i) {
    if (!used[i]) unexpected.push_back(&got[i]);
  }
  if (!unexpected.empty()) ok = false;

  for (const std::string& m : matched) report << "  ok          " << m << "\n";
  for (const ExpectedDiagnostic* e : missing) {
    report << "  MISSING     " << show_location(e->file, e->line, case_dir) << ": "
           << to_string(e->severity) << "[" << e->code << "]: ..." << e->text
           << "...   (expected.txt:" << e->source_line << ")\n";
  }
  for (const Diagnostic* d : unexpected) {
    report << "  UNEXPECTED  " << show_location(d->file, d->line, case_dir) << ": "
           << to_string(d->severity) << "[" << d->code << "]: " << d->message << "\n";
  }
  result.ok = ok;
  result.report = name + (ok ? ": ok" : ": FAILED") + " (" +
                  std::to_string(expected.diagnostics.size()) + " expected, " +
                  std::to_string(got.size()) + " reported)\n" + report.str();
  return result;
}

std::vector<fs::path> list_cases(const fs::path& cases_dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(cases_dir, ec)) {
    if (entry.is_directory() && fs::exists(entry.path() / "expected.txt"))
      out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace mospec::test
