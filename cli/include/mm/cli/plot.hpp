#pragma once

// `maneuvermap plot`: finds the plotting script and a Python with matplotlib, and runs it on a
// run directory, a sweep directory or a snapshot CSV (docs/outputs.md, "Figures").

#include <filesystem>
#include <string>

namespace mm::cli {

/// The interpreter and script `maneuvermap plot` uses: the environment variables MM_PYTHON and
/// MM_PLOT_SCRIPT when set and not empty, else the paths configured at build time (CMake cache
/// variables of the same names; by default /usr/bin/python3 and tools/plot/maneuvermap_plot.py of
/// the source tree).
struct plot_tool {
  std::string python;
  std::string script;
};
plot_tool find_plot_tool();

/// Draws the figures of `target` (a run directory, a sweep directory or a snapshot CSV) into
/// `out_dir` (empty: next to the target) by running the script; its output goes to this
/// process's standard output and error. Throws input_error (exit code 2) when the script or the
/// interpreter cannot be found or run, when the interpreter lacks matplotlib, or when the script
/// rejects `target`; std::runtime_error when the script fails otherwise.
void draw_plots(const std::filesystem::path& target, const std::filesystem::path& out_dir);

}  // namespace mm::cli
