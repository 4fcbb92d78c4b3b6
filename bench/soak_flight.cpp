// soak_flight: the long-running half of `scripts/soak` (issue 42 item 7). Flies a flight path
// in realtime, as the window does — flight time follows the wall clock, the I/O races the frames
// (StreamingMode::Realtime) — back and forth along the path (a ping-pong loop: no jump at the
// ends) for the minutes asked, drawing every frame through the one frame driver, and every
// `--every-s` seconds appends one row of what a leak or a stuck request would show:
//
//   wall_s, frames, rss_bytes, hwm_bytes (VmRSS, VmHWM of /proc/self/status), fds (entries of
//   /proc/self/fd), gpu_bytes (render::deviceMemoryInUse: every device allocation alive),
//   cache_bytes (the --http-cache directory's files), the tile source's counters (started,
//   completed, missing, failed, cancelled, retries, cache hits, in flight, bytes), resident tiles and bytes
//   (CPU and GPU), the slowest frame of the interval (ms), and heap_bytes (malloc's in-use bytes:
//   RSS growing while they stay flat is the allocator's free memory, not a leak).
//
//   soak_flight DATASET --path PATH.json --minutes M --samples OUT.csv
//               [--size WxH] [--cpu-budget-mb MB] [--gpu-budget-mb MB] [--http-cache DIR]
//               [--every-s S] [--validate]
//
// Exit 0 when the time is up with every frame drawn (and, with --validate, the validation layer
// silent), 1 when a frame failed or validation spoke, 2 on a usage mistake.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <malloc.h>

#include "flight/flight_path_json.h"
#include "flight/path_sampler.h"
#include "render/gpu_resources.h"
#include "scene/frame_driver.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace vegstream;

namespace {

struct Args {
  std::string dataset, path, samples, cache;
  double minutes = 0.0, everyS = 10.0, cpuBudgetMb = 64.0, gpuBudgetMb = 32.0;
  int width = 160, height = 90;
  bool validate = false;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr, "soak_flight: %s\n", why.c_str());
  std::fprintf(stderr,
               "usage: soak_flight DATASET --path PATH.json --minutes M --samples OUT.csv [--size WxH] "
               "[--cpu-budget-mb MB] [--gpu-budget-mb MB] [--http-cache DIR] [--every-s S] [--validate]\n");
  std::exit(2);
}

double number(const std::string& flag, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v <= 0.0)
    usage(flag + " " + text + ": not a positive number");
  return v;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    const bool hasValue = i + 1 < argc;
    if (f == "--validate")
      a.validate = true;
    else if (!f.starts_with("--"))
      a.dataset = f;
    else if (!hasValue)
      usage(f + ": a value is missing");
    else if (f == "--path")
      a.path = argv[++i];
    else if (f == "--samples")
      a.samples = argv[++i];
    else if (f == "--http-cache")
      a.cache = argv[++i];
    else if (f == "--minutes")
      a.minutes = number(f, argv[++i]);
    else if (f == "--every-s")
      a.everyS = number(f, argv[++i]);
    else if (f == "--cpu-budget-mb")
      a.cpuBudgetMb = number(f, argv[++i]);
    else if (f == "--gpu-budget-mb")
      a.gpuBudgetMb = number(f, argv[++i]);
    else if (f == "--size") {
      if (std::sscanf(argv[++i], "%dx%d", &a.width, &a.height) != 2 || a.width < 16 || a.height < 16)
        usage(std::string("--size ") + argv[i] + ": not WxH");
    } else
      usage(f + ": unknown option");
  }
  if (a.dataset.empty() || a.path.empty() || a.samples.empty() || a.minutes <= 0.0)
    usage("DATASET, --path, --minutes and --samples are required");
  return a;
}

// A field of /proc/self/status in bytes (its value is in kB), 0 if absent.
uint64_t statusBytes(const std::string& field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field + ":", 0) == 0) return std::strtoull(line.c_str() + field.size() + 1, nullptr, 10) * 1024;
  return 0;
}

uint64_t openFiles() {
  std::error_code ec;
  uint64_t n = 0;
  for (auto it = fs::directory_iterator("/proc/self/fd", ec); !ec && it != fs::directory_iterator(); it.increment(ec))
    ++n;
  return n;
}

uint64_t directoryBytes(const std::string& dir) {
  std::error_code ec;
  uint64_t bytes = 0;
  if (dir.empty() || !fs::is_directory(dir, ec)) return 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_regular_file(ec)) bytes += it->file_size(ec);
  return bytes;
}

// Bytes malloc has handed out and not had back (mallinfo2: in-use chunks and mmapped blocks):
// what the program holds on the heap, where RSS also counts what the allocator keeps free.
uint64_t heapBytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<uint64_t>(m.uordblks) + static_cast<uint64_t>(m.hblkhd);
}

// Flight time of wall second `s` on a path of `duration` flown forth and back.
double pingPong(double s, double duration) {
  const double lap = std::fmod(s, 2.0 * duration);
  return lap <= duration ? lap : 2.0 * duration - lap;
}

constexpr const char* kHeader =
    "wall_s,frames,rss_bytes,hwm_bytes,fds,gpu_bytes,cache_bytes,requests_started,requests_completed,"
    "requests_missing,requests_failed,requests_cancelled,retries,cache_hits,requests_in_flight,bytes_read,tiles_"
    "resident_cpu,"
    "bytes_resident_cpu,tiles_resident_gpu,bytes_resident_gpu,slowest_frame_ms,heap_bytes";

void writeRow(std::FILE* out, double wallS, uint64_t frames, const scene::Scene& scene, const std::string& cache,
              double slowestMs) {
  const auto io = scene.tileIoProgress();
  const auto& st = scene.lastFrameFigures().streaming;
  const auto& c = io.source;
  std::fprintf(
      out,
      "%.1f,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%zu,%llu,%llu,%llu,%llu,%llu,%.2f,%llu\n",
      wallS, (unsigned long long)frames, (unsigned long long)statusBytes("VmRSS"),
      (unsigned long long)statusBytes("VmHWM"), (unsigned long long)openFiles(),
      (unsigned long long)render::deviceMemoryInUse(), (unsigned long long)directoryBytes(cache),
      (unsigned long long)c.requestsStarted, (unsigned long long)c.requestsCompleted,
      (unsigned long long)c.requestsMissing, (unsigned long long)c.requestsFailed,
      (unsigned long long)c.requestsCancelled, (unsigned long long)c.retries, (unsigned long long)c.cacheHits,
      io.sourceInFlight, (unsigned long long)c.bytesRead, (unsigned long long)st.tilesResidentCpu,
      (unsigned long long)st.bytesResidentCpu, (unsigned long long)st.tilesResidentGpu,
      (unsigned long long)st.bytesResidentGpu, slowestMs, (unsigned long long)heapBytes());
  std::fflush(out);
}

scene::SceneOptions sceneOptions(const Args& a, const std::shared_ptr<render::ValidationLog>& log) {
  scene::SceneOptions o;
  o.dataset = a.dataset;
  o.mode = scene::StreamingMode::Realtime;
  o.lookAhead = true;
  if (!a.cache.empty()) o.httpCacheDir = a.cache;
  o.streaming.cpuBudgetBytes = static_cast<uint64_t>(a.cpuBudgetMb * (1 << 20));
  o.streaming.gpuBudgetBytes = static_cast<uint64_t>(a.gpuBudgetMb * (1 << 20));
  o.renderer.width = static_cast<uint32_t>(a.width);
  o.renderer.height = static_cast<uint32_t>(a.height);
  o.renderer.msaa = 1;
  o.renderer.context.validate = a.validate;
  o.renderer.context.validationLog = log;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  auto path = flight::loadFlightPath(a.path);
  if (!path.ok()) usage(path.error().message);
  auto log = std::make_shared<render::ValidationLog>();
  auto scene = scene::Scene::open(sceneOptions(a, log));
  if (!scene.ok()) {
    std::fprintf(stderr, "soak_flight: %s\n", scene.error().message.c_str());
    return 2;
  }
  std::FILE* out = std::fopen(a.samples.c_str(), "w");
  if (!out) usage(a.samples + ": cannot be written");
  std::fprintf(out, "%s\n", kHeader);

  const flight::PathSampler sampler(*path);
  const auto ground = (*scene)->groundFunction();
  scene::FrameDriver driver(**scene);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double endS = a.minutes * 60.0;
  uint64_t frames = 0;
  double nextRowS = 0.0, slowestMs = 0.0;
  for (;;) {
    const auto before = Clock::now();
    const double wallS = std::chrono::duration<double>(before - start).count();
    if (wallS >= nextRowS || wallS >= endS) {
      writeRow(out, wallS, frames, **scene, a.cache, slowestMs);
      nextRowS += a.everyS;
      slowestMs = 0.0;
    }
    if (wallS >= endS) break;
    scene::FrameInput in;
    in.timeS = pingPong(wallS, sampler.duration());
    in.pose = sampler.sample(in.timeS, ground);
    in.ahead = flight::lookAheadSamples(sampler, ground, in.timeS);
    auto frame = driver.run(in);
    if (!frame.ok()) {
      std::fprintf(stderr, "soak_flight: frame %llu at %.1f s: %s\n", (unsigned long long)frames, wallS,
                   frame.error().message.c_str());
      std::fclose(out);
      return 1;
    }
    ++frames;
    slowestMs = std::max(slowestMs, std::chrono::duration<double, std::milli>(Clock::now() - before).count());
  }
  std::fclose(out);
  for (const auto& m : log->messages()) std::fprintf(stderr, "soak_flight: validation: %s\n", m.c_str());
  std::printf("soak_flight: %llu frames in %.1f min\n", (unsigned long long)frames, a.minutes);
  return log->messages().empty() ? 0 : 1;
}
