#include "mm/cli/plot.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "mm/cli/commands.hpp"

extern char** environ;

namespace mm::cli {
namespace {

/// The plotting script's exit codes (tools/plot/maneuvermap_plot.py).
constexpr int script_bad_input = 2;
constexpr int script_missing_matplotlib = 3;

std::string from_environment(const char* name, const char* fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::string(value) : std::string(fallback);
}

}  // namespace

plot_tool find_plot_tool() { return {from_environment("MM_PYTHON", MM_PYTHON), from_environment("MM_PLOT_SCRIPT", MM_PLOT_SCRIPT)}; }

void draw_plots(const std::filesystem::path& target, const std::filesystem::path& out_dir) {
  const plot_tool tool = find_plot_tool();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(tool.script, ec)) {
    throw input_error("plot: the plotting script " + tool.script +
                      " does not exist (set MM_PLOT_SCRIPT to tools/plot/maneuvermap_plot.py of the source tree)");
  }
  std::vector<std::string> args{tool.python, tool.script, target.string()};
  if (!out_dir.empty()) {
    args.emplace_back("--out");
    args.push_back(out_dir.string());
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, tool.python.c_str(), nullptr, nullptr, argv.data(), environ);
  if (spawned != 0) {
    throw input_error("plot: cannot run " + tool.python + ": " + std::strerror(spawned) +
                      " (install python3 and python3-matplotlib: scripts/install-deps.sh; or set MM_PYTHON)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("plot: waiting for the plotting script: ") + std::strerror(errno));
  }
  if (!WIFEXITED(status)) throw std::runtime_error("plot: the plotting script was killed by signal " + std::to_string(WTERMSIG(status)));
  const int code = WEXITSTATUS(status);
  if (code == 0) return;
  if (code == script_missing_matplotlib) {
    throw input_error("plot: " + tool.python +
                      " cannot import matplotlib (install python3-matplotlib: scripts/install-deps.sh; or set MM_PYTHON to a "
                      "Python that has it)");
  }
  if (code == script_bad_input) throw input_error("plot: nothing to plot in " + target.string() + " (see above)");
  if (code == 127) throw input_error("plot: cannot run " + tool.python + " (install python3, or set MM_PYTHON)");
  throw std::runtime_error("plot: the plotting script failed with exit code " + std::to_string(code));
}

}  // namespace mm::cli
