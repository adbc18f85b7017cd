// `mospec report`: one self-contained HTML page about a run (or a directory
// of trials) that works offline — the verdicts, a timeline of motions and
// events, interactive time series of the log's columns (dygraphs, from
// Debian's libjs-dygraphs, inlined), the run's video when there is one, and
// the model's constraints, monitors and controllers with their file:line.
// Nothing on the page is fetched when it is opened.
//
// A run directory is shared like a model bundle, so everything in it is
// untrusted: a run's files are read only from inside its directory (no
// symbolic link out), the summary is type-checked (summary.hpp), the video is
// inlined only when its header says MP4 or GIF, and every value reaches the
// page through the escaping of the context it lands in (html.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "plot/csv.hpp"
#include "report/summary.hpp"

namespace mospec::report {

// One run's files: its summary (`mospec run --summary`), its log beside it
// and, if present, its video (`--video`), all inside `dir`.
struct Run {
  std::string name;
  std::string dir;  // the run's directory: nothing is read from outside it
  std::string log_path, summary_path, video_path;
};

enum class VideoKind { None, Mp4, Gif };

// What a video file's first bytes say it is: an ISO media file ("ftyp" box
// first) or a GIF ("GIF87a"/"GIF89a"); anything else is None.
VideoKind sniff_video(std::string_view bytes);

struct LoadedRun {
  std::string name;
  Summary summary;
  plot::Table log;
  std::string video;  // the file's bytes, empty when there is none
  VideoKind video_kind = VideoKind::None;
};

// Reads one run's files. Throws mospec::Error: a file outside `run.dir`
// (after symbolic links), a malformed summary or log (located), a video whose
// header is neither MP4 nor GIF or does not match its extension.
LoadedRun load_run(const Run& run, SourceFiles& files);

// A model entity the page lists, located where the model defines it.
struct Entity {
  std::string kind;  // "constraint", "monitor", "controller", "motion"
  std::string iri;
  std::string file;  // as the loader named it (relative to where mospec ran)
  std::uint32_t line = 0;
};

// The link from the page at `page` to `file`: relative to the page's
// directory and percent-encoded, or with `absolute` a file:// URL (which
// embeds the machine's directory names, so only on request).
std::string link_to(const std::string& file, const std::string& page, bool absolute);

struct Input {
  std::string title;
  std::vector<LoadedRun> runs;  // one, or the trials in order
  // Validation and lowering of the run's app today: its verdict in a line,
  // and whether it passed.
  std::string model_verdict;
  bool model_ok = false;
  std::vector<Entity> entities;
  // The log's units and thresholds from the model, for a summary written
  // without them (Summary::log is used when it has them).
  plot::LogInfo log_info;
  // Where the page is written ("-": standard output), for links relative to
  // it; with absolute_links, file:// URLs instead (link_to()).
  std::string page = "-";
  bool absolute_links = false;
};

// A chart's rows decimated to what a screen shows: per bucket of rows (of
// `buckets`), two output rows drawn at the bucket's first and last time that
// hold each series' minimum and maximum in the order they occur (NaN aside).
// Every series' extremes are kept exactly; a value is drawn less than one
// bucket from its time. With rows <= 2 * buckets every row is kept.
struct Decimation {
  std::vector<size_t> time_row;          // per output row, the row whose time it is drawn at
  std::vector<std::vector<size_t>> row;  // row[series][output row]: the row its value is from
};
Decimation decimate(const std::vector<const std::vector<double>*>& series, size_t rows,
                    size_t buckets);

// The page's script and style (dygraphs, inlined).
struct Assets {
  std::string js, css;
};

// Where the JavaScript and CSS come from (the Debian package's files);
// $MOSPEC_DYGRAPHS_DIR overrides it.
std::string dygraphs_dir();

// Reads them. Throws mospec::Error (code "report") naming the missing file
// and the fix when dygraphs is not installed.
Assets load_assets();

// The page. Throws mospec::Error (code "report") when there is no run or the
// trials' logs have different columns.
std::string render(const Input& input, const Assets& assets);

}  // namespace mospec::report
