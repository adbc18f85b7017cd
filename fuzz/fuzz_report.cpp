// libFuzzer target for the report page: the input is a run summary, and after
// a NUL byte optionally the run's CSV log (both come with a shared run
// directory). Invariants beyond "no crash, no sanitizer report, no hang":
// every rejection is a mospec::Error with a code; and a page that is written
// has exactly the template's two script blocks, no comment, and only the
// template's tags, whatever the data says.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string>
#include <string_view>

#include "report/report.hpp"
#include "report/summary.hpp"
#include "support/diagnostics.hpp"

namespace {

size_t count(std::string_view text, std::string_view what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string_view::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Every "<" outside the script blocks opens one of the template's tags.
bool only_template_tags(std::string_view page) {
  static const std::set<std::string, std::less<>> kAllowed = {
      "!DOCTYPE", "html", "head",    "meta",    "title",   "style", "body", "h1",
      "h2",       "h3",   "p",       "details", "summary", "table", "tr",   "th",
      "td",       "a",    "section", "span",    "ul",      "li",    "div",  "script"};
  const size_t data = page.rfind("<script>");
  for (size_t at = page.find('<'); at != std::string_view::npos && at < data;
       at = page.find('<', at + 1)) {
    size_t end = at + 1;
    if (end < page.size() && page[end] == '/') ++end;
    size_t stop = end;
    while (stop < page.size() &&
           (std::isalnum(static_cast<unsigned char>(page[stop])) || page[stop] == '!'))
      ++stop;
    if (!kAllowed.count(page.substr(end, stop - end))) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const size_t nul = input.find('\0');
  const std::string_view summary = input.substr(0, nul);
  const std::string_view log =
      nul == std::string_view::npos ? std::string_view("t,a.value\n0,1\n") : input.substr(nul + 1);
  try {
    mospec::SourceFiles files;
    mospec::report::Input in;
    mospec::report::LoadedRun run;
    run.name = "fuzz";
    run.summary = mospec::report::parse_summary(summary, "fuzz.json", files);
    run.log = mospec::plot::parse_csv(log, "fuzz.csv");
    in.title = run.summary.status;
    in.model_verdict = run.summary.scenario;
    in.runs.push_back(std::move(run));
    const std::string page = mospec::report::render(in, {"/*js*/", "/*css*/"});
    if (count(page, "<script") != 2 || count(page, "</script") != 2 || count(page, "<!--") != 0 ||
        !only_template_tags(page))
      std::abort();
  } catch (const mospec::Error& e) {
    if (e.code().empty()) std::abort();
  }
  return 0;
}
