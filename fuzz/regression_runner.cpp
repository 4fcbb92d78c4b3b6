// fuzz_regressions (ctest, label fuzz): every fuzz target's function (fuzz/targets.h), built by
// the ordinary compiler without libFuzzer, over every file of fuzz/regressions/<target>/ (the
// inputs that once crashed a target) and fuzz/corpus/<target>/ (the committed seeds).
//   fuzz_regressions FUZZ_DIR [TARGET …]     no TARGET: all of them
// A crash or a broken invariant aborts the program after the line naming the file; an exception
// escaping a target is reported and fails it. Exit 0 when every file ran through.
// Each input runs on a thread of a 1 MiB stack (libFuzzer's main thread has 8 MiB, under ASan's
// larger frames): a recursion over nesting that the fuzzer overflowed with 20 000 levels then
// overflows again on a regression input of a few thousand, a few KB.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <pthread.h>
#include <string>
#include <vector>

#include "fuzz/targets.h"

namespace fs = std::filesystem;
using vegstream::fuzz::kTargets;

namespace {

std::vector<fs::path> filesUnder(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string().rfind('.', 0) != 0) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

struct Call {
  vegstream::fuzz::TargetFn fn;
  const std::vector<uint8_t>* bytes;
  std::string thrown;  // what escaped the target, empty when nothing did
};

void* runCall(void* arg) {
  auto* call = static_cast<Call*>(arg);
  try {
    call->fn(call->bytes->data(), call->bytes->size());
  } catch (const std::exception& e) {
    call->thrown = std::string("threw ") + e.what();
  } catch (...) {
    call->thrown = "threw a non-std exception";
  }
  return nullptr;
}

// Runs fn(bytes) on a thread with a 1 MiB stack; what escaped it, or "".
std::string runOnSmallStack(vegstream::fuzz::TargetFn fn, const std::vector<uint8_t>& bytes) {
  Call call{fn, &bytes, {}};
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, size_t{1} << 20);
  pthread_t thread;
  if (pthread_create(&thread, &attr, runCall, &call) != 0) {
    pthread_attr_destroy(&attr);
    runCall(&call);  // no thread to be had: on this one
    return call.thrown;
  }
  pthread_attr_destroy(&attr);
  pthread_join(thread, nullptr);
  return call.thrown;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_regressions FUZZ_DIR [TARGET ...]\n");
    return 2;
  }
  const fs::path root = argv[1];
  std::vector<std::string> wanted(argv + 2, argv + argc);
  for (const auto& w : wanted) {
    if (std::none_of(std::begin(kTargets), std::end(kTargets), [&](const auto& t) { return w == t.name; })) {
      std::fprintf(stderr, "fuzz_regressions: no target '%s'\n", w.c_str());
      return 2;
    }
  }
  int failures = 0;
  for (const auto& target : kTargets) {
    if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), target.name) == wanted.end()) continue;
    const auto start = std::chrono::steady_clock::now();
    int runs = 0;
    for (const char* kind : {"regressions", "corpus"}) {
      for (const fs::path& file : filesUnder(root / kind / target.name)) {
        std::ifstream in(file, std::ios::binary);
        const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::printf("%s: %s\n", target.name, file.string().c_str());
        std::fflush(stdout);
        if (const std::string thrown = runOnSmallStack(target.fn, bytes); !thrown.empty()) {
          std::printf("  FAILED: %s\n", thrown.c_str());
          ++failures;
        }
        ++runs;
      }
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %d inputs, %.0f ms\n", target.name, runs, ms);
    if (runs == 0) {
      std::printf("  FAILED: no input for %s (fuzz/corpus/%s/ must hold its seeds)\n", target.name, target.name);
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
