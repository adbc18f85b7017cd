// The paper's result figures from run logs. A Figure is decided here (which
// columns, labels, units, colours, statistics); gnuplot_script() only writes
// it down, with every number inline, so gnuplot never reads a user's file.
//
// Fig. 4 (one run): left panel, the shoulder-contact distances d_r, d_l [m]
// with their thresholds (the constraints' .lower/.upper columns) dashed; right
// panel, the platform wrench the base distributes (F_perp, F_par [N]; tau
// [N m] on the right-hand scale) or, without one (SC2), each arm's
// distance-controller output [N].
// Fig. 6 (trials): the same panels as mean +- one standard deviation bands over
// trials that share columns and time base.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "plot/csv.hpp"
#include "plot/log_info.hpp"

namespace mospec::plot {

enum class Format { Svg, Png };

// By the output's extension (.svg, .png; any case); throws mospec::Error
// (code "usage") otherwise.
Format format_of(const std::string& path);

// Column choices; empty lists take the defaults named above. A log without
// the shoulder-contact distances (any app but SC1/SC2's) defaults to its
// constraints' values with their setpoints or thresholds dashed (left), and
// its controllers' outputs, else those constraints' errors (right): of each,
// the columns of the unit most of them share, at most kMaxDefaultCurves.
struct Selection {
  std::vector<std::string> distances;
  std::vector<std::string> forces;
  // The columns' units and the constraints' thresholds: from the run's
  // summary beside the log when there is one (`mospec run --summary`).
  LogInfo info;
};

inline constexpr std::size_t kMaxDefaultCurves = 8;

struct Curve {
  std::string label;
  bool label_enhanced = true;  // false: a column name, shown verbatim
  std::vector<double> y;
  std::vector<double> sd;  // one standard deviation per row; empty: no band
  std::string color;       // "#rrggbb"
  bool dashed = false;
  bool titled = true;       // false: not in the key (e.g. the second threshold)
  bool right_axis = false;  // on the panel's y2 scale
};

// A y scale's extent, decided by mospec (never gnuplot's autoscale): the data
// curves and their bands with a margin, so that nothing drawn sits on the
// frame. A start-up spike does not set it: values in the first 5 % of the run
// that reach more than three spans of the rest beyond the rest's extent are
// clipped, and `clipped` says so.
struct Range {
  double lo = 0.0, hi = 1.0;
  std::string clipped;  // what was clipped: "down to -137 N", "up to 62.8 N",
                        // "-134.9 to 49.52 N"; empty: nothing
};

struct Panel {
  std::string ylabel;   // shown verbatim (no enhanced-text markup)
  std::string y2label;  // empty: no right-hand scale
  std::vector<Curve> curves;
  Range y, y2;  // filled by decide_ranges()
};

// A vertical line across every panel at a time something happened: a motion
// started (its `.running` column became 1) or ended (its `.ended` code: until,
// while violated), or an event column fired (rising, falling).
struct Marker {
  double t = 0.0;     // [s]
  std::string label;  // shown verbatim, e.g. "motion-sc1-rightarm starts"
};

struct Figure {
  std::string title;      // shown verbatim
  std::vector<double> t;  // [s]
  std::vector<Panel> panels;
  std::vector<Marker> markers;  // in time order; at most kMaxMarkers
  std::size_t markers_dropped = 0;
};

inline constexpr std::size_t kMaxMarkers = 16;

// The unit of a log column by mospec's naming (the simulator's columns, the
// distance constraints and controllers, the platform wrench): "m", "N",
// "N·m", "rad", "rad/s", "s", "1"; "" when the name does not tell.
std::string unit_of(std::string_view column);

// The markers of a run log, merged per row ("a starts, b starts") and capped
// at kMaxMarkers (the rest counted in markers_dropped).
void add_markers(const Table& run, Figure& figure);

// Fig. 4 from one run log. Throws mospec::Error (code "missing-column") naming
// the file, the column and the available columns.
Figure run_figure(const Table& run, const Selection& selection, const std::string& title);

// Fig. 6 from trials (at least one). Throws mospec::Error when the trials'
// columns or time bases differ (located at the first difference) or a column
// is missing.
Figure trials_figure(const std::vector<Table>& trials, const Selection& selection,
                     const std::string& title);

// The gnuplot script that renders `figure` to `output_name` (a plain file name,
// relative to gnuplot's working directory) as `format`.
std::string gnuplot_script(const Figure& figure, Format format, const std::string& output_name);

}  // namespace mospec::plot
