// Renders a Figure through gnuplot: the script goes to gnuplot's stdin (no
// shell), gnuplot runs in the output's directory and writes a hidden temporary
// file there, which is renamed over the output only when gnuplot succeeded, so
// a reader never sees half a figure.
#pragma once

#include <string>

#include "plot/figure.hpp"

namespace mospec::plot {

// Throws mospec::Error: code "not-found" when gnuplot is not installed, "plot"
// when gnuplot fails (its messages included), "io" when the output's directory
// is missing or the rename fails.
void render(const Figure& figure, const std::string& output);

}  // namespace mospec::plot
