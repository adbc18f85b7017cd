#include "plot/gnuplot.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "plot/process.hpp"
#include "support/diagnostics.hpp"

namespace mospec::plot {

namespace fs = std::filesystem;

void render(const Figure& figure, const std::string& output) {
  const Format format = format_of(output);
  fs::path out(output);
  fs::path dir = out.parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    std::string message = "cannot write '";
    message.append(output).append("': no directory '").append(dir.string()).append("'");
    throw Error("io", message);
  }
  // The figure replaces the output by a rename, which must never replace a
  // directory, a device or a pipe.
  const fs::file_status status = fs::status(out, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    std::string message = "cannot write '";
    message.append(output).append("': not a regular file");
    throw Error("io", message);
  }
  std::string temp = ".mospec-plot-";
  temp.append(std::to_string(::getpid())).append(format == Format::Svg ? ".svg" : ".png");
  const fs::path temp_path = dir / temp;
  const std::string script = gnuplot_script(figure, format, temp);
  CapturedRun run;
  try {
    run = run_captured({"gnuplot"}, script, dir.string());
  } catch (const Error& e) {
    if (e.code() != "not-found") throw;
    std::string message = e.diagnostic().message;
    message.append(
        "; mospec plot needs gnuplot with svg and png terminals (Debian: gnuplot-nox, installed by "
        "scripts/install-deps)");
    throw Error("not-found", message);
  }
  const bool written = fs::is_regular_file(temp_path, ec) && fs::file_size(temp_path, ec) > 0;
  // gnuplot reports a script error on stderr and exits non-zero; a warning
  // alone (e.g. a missing font) is not a failure.
  if (!run.exit.ok() || !written) {
    fs::remove(temp_path, ec);
    std::string message = "gnuplot ";
    message.append(run.exit.describe());
    if (!written) message.append(" and wrote no figure");
    if (!run.output.empty()) {
      std::string text = run.output.substr(0, 2000);
      while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
      message.append(":\n").append(text);
    }
    throw Error("plot", message);
  }
  if (::rename(temp_path.c_str(), out.c_str()) != 0) {
    const int saved = errno;
    fs::remove(temp_path, ec);
    std::string message = "cannot write '";
    message.append(output).append("': ").append(std::strerror(saved));
    throw Error("io", message);
  }
}

}  // namespace mospec::plot
