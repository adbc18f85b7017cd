// `mospec report`: one self-contained HTML page about a run (or a directory
// of trials) that works offline — the verdicts, a timeline of motions and
// events, interactive time series of the log's columns (dygraphs, from
// Debian's libjs-dygraphs, inlined), the run's video when there is one, and
// the model's constraints, monitors and controllers with their file:line.
// Nothing on the page is fetched when it is opened.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mospec::report {

// One run: its log, its summary (`mospec run --summary`) and, if present, its
// video (`--video`), all files.
struct Run {
  std::string name;
  std::string log_path, summary_path, video_path;
};

// A model entity the page lists, located where the model defines it.
struct Entity {
  std::string kind;  // "constraint", "monitor", "controller", "motion"
  std::string iri;
  std::string file;  // as the loader named it (relative to where mospec ran)
  std::string url;   // file:// URL of the file, for the link (works wherever the page is)
  std::uint32_t line = 0;
};

struct Input {
  std::string title;
  std::vector<Run> runs;  // one, or the trials in order
  // Validation and lowering of the run's app today: its verdict in a line,
  // and whether it passed.
  std::string model_verdict;
  bool model_ok = false;
  std::vector<Entity> entities;
};

// Where the JavaScript and CSS come from (the Debian package's files);
// $MOSPEC_DYGRAPHS_DIR overrides it.
std::string dygraphs_dir();

// The page. Throws mospec::Error (code "report") naming the missing file and
// the fix when dygraphs is not installed, and the CSV/JSON readers' located
// errors for a malformed log or summary.
std::string render(const Input& input);

}  // namespace mospec::report
