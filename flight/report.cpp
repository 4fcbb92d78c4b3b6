// Running the embedded plot script (report.h): write it to a private temporary file, spawn the
// interpreter with an argument vector (no shell, so no quoting of paths), map its exit code.

#include "flight/report.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace vegstream::flight {
namespace fs = std::filesystem;

namespace {

constexpr int kScriptNoMatplotlib = 3;  // recording_plots.py's exit code when matplotlib is missing

// The script in a temporary file that is removed when this goes out of scope.
class ScriptFile {
 public:
  ScriptFile() {
    std::string pattern = (fs::temp_directory_path() / "vegstream-plots-XXXXXX.py").string();
    const int fd = ::mkstemps(pattern.data(), 3);
    if (fd < 0) return;
    const std::string text = plotScriptText();
    const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    ::close(fd);
    path_ = pattern;
    ok_ = ok;
  }
  ~ScriptFile() {
    std::error_code ec;
    if (!path_.empty()) fs::remove(path_, ec);
  }
  ScriptFile(const ScriptFile&) = delete;
  ScriptFile& operator=(const ScriptFile&) = delete;
  bool ok() const { return ok_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  bool ok_ = false;
};

const char* kInstallHint =
    "install python3-matplotlib (apt-get install python3-matplotlib) and run `vegstream report DIR` again";

// Runs one interpreter; returns its exit status (-errno-like negative when it cannot start).
int spawn(const std::string& python, const std::string& script, const std::vector<std::string>& args) {
  std::vector<std::string> all = {python, script};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

Status runScript(const std::vector<std::string>& pythons, const std::vector<std::string>& args) {
  ScriptFile script;
  if (!script.ok())
    return makeError(ErrorKind::Io, "cannot write the plot script to " + fs::temp_directory_path().string());
  std::string tried;
  bool anyPython = false;
  for (const auto& python : pythons) {
    const int rc = spawn(python, script.path(), args);
    if (rc == 0) return {};
    tried += (tried.empty() ? "" : ", ") + python;
    if (rc == -1 || rc == 127) continue;  // no such interpreter
    anyPython = true;
    if (rc == kScriptNoMatplotlib) continue;  // an interpreter without matplotlib
    return makeError(ErrorKind::Io, "no plots: the plot script failed (" + python + " exit status " +
                                        std::to_string(rc) + "; its message is above)");
  }
  return makeError(ErrorKind::Unsupported,
                   std::string("no plots: ") + (anyPython ? "matplotlib cannot be imported by " : "cannot run ") +
                       tried + "; " + kInstallHint + " (or set VEGSTREAM_PYTHON to a Python that has matplotlib)");
}

}  // namespace

const std::vector<std::string>& reportPlotNames() {
  static const std::vector<std::string> names = {"frame_time.png", "geometric_load.png", "streaming_memory.png"};
  return names;
}

std::vector<std::string> defaultPythons() {
  const char* env = std::getenv("VEGSTREAM_PYTHON");
  if (env && *env) return {env};
  return {"python3", "/usr/bin/python3"};
}

Status makePlots(const fs::path& dir, const std::vector<std::string>& pythons) {
  return runScript(pythons, {"report", dir.string()});
}

Status makeComparePlot(const fs::path& dirA, const fs::path& dirB, const fs::path& outPng,
                       const std::vector<std::string>& pythons) {
  return runScript(pythons, {"compare", dirA.string(), dirB.string(), outPng.string()});
}

}  // namespace vegstream::flight
