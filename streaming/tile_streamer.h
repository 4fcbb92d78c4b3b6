#pragma once
// TileStreamer: gets the tiles the frame wants into memory without the frame ever waiting.
//
// Frame thread, once per frame:
//   update(wants, timeS)  — takes in finished decodes (→ ResidentCpu), evicts least-recently-used
//                           tiles over the CPU budget (never one wanted this frame), cancels
//                           requests no longer wanted, issues new ones in priority order up to
//                           the in-flight limit.
//   find*/get             — read resident tiles (marks them used this frame).
//   planUploads()         — imagery tiles to copy to the GPU this frame (→ Uploading), within
//                           the per-frame byte budget and the GPU budget; uploadsRecorded()
//                           after the copies are recorded (→ ResidentGpu).
// Workers (never the frame thread): the source's I/O tasks, then decode tasks (OpenImageIO
// through datasets/tile_codec) that turn bytes into HeightTile / ColorTile, both on an injected
// TaskRunner (core/task_runner.h).
//
// Tile states (README diagram):
//   Unloaded → Requested → Decoding → ResidentCpu → Uploading → ResidentGpu   (imagery)
//   Unloaded → Requested → Decoding → ResidentCpu                            (heights: the CPU
//                                                                           builds the mesh)
//   Requested → FailedTemporarily (source gave up this time; may be asked again after a
//               back-off) ; Requested → Failed (missing, or corrupt bytes: final, draw the parent)
//   any resident state → Unloaded on eviction; Requested/Decoding → Unloaded on cancellation.
//
// Thread-safety: every public member is for the frame thread only, except where noted.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/clock.h"
#include "core/log.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/tile_codec.h"
#include "streaming/tile_key.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming {

enum class TileState { Unloaded, Requested, Decoding, ResidentCpu, Uploading, ResidentGpu, FailedTemporarily, Failed };
const char* toString(TileState s);

// Data derived from a decoded height tile on the decode thread (e.g. the terrain's wedgie
// thicknesses), kept with the tile and counted against the CPU budget with it. The streamer
// does not know what it is: the terrain injects the builder (StreamingOptions::heightExtra).
class TileExtra {
 public:
  virtual ~TileExtra() = default;
  virtual uint64_t bytes() const = 0;
};
using HeightExtraFn = std::function<std::shared_ptr<const TileExtra>(const datasets::HeightTile&)>;

struct StreamingOptions {
  uint64_t cpuBudgetBytes = 512ull << 20;  // decoded tiles resident in memory (laptop-sized)
  uint64_t gpuBudgetBytes = 256ull << 20;  // imagery tiles resident on the GPU
  uint64_t uploadBytesPerFrame = 8ull << 20;
  int maxRequestsInFlight = 24;
  int decodeThreads = 0;           // decodes at once; 0: the runner's concurrency − 1, at least 1
  TaskRunner* tasks = nullptr;     // runs the decodes; outlives the streamer. Null: a pool of
                                   // the streamer's own (decodeThreads, 0: hardware − 1)
  const Clock* clock = nullptr;    // settle()'s time-out; outlives the streamer. Null: steady
  uint32_t maxGpuSlots = 2048;     // the device's array-layer limit (Vulkan guarantees 256)
  int slotReuseDelayFrames = 2;    // a GPU slot freed at frame N is reused at N + this (frames in flight)
  double failedRetryAfterS = 2.0;  // FailedTemporarily tiles may be requested again after this
  HeightExtraFn heightExtra;       // run on the decode threads for every height tile; may be empty
  uint64_t heightExtraBytes = 0;   // what heightExtra adds to a tile (for the budget's estimates)
};

// One tile a frame wants. Priority: larger first (the terrain uses screen-space error in px);
// look-ahead wants are prefetches for later in the flight and never displace current ones.
struct TileWant {
  TileKey key;
  double priority = 0.0;
  bool lookAhead = false;
};

// A resident tile: immutable, shared with readers (a reader's copy outlives eviction).
struct ResidentTile {
  TileKey key;
  std::shared_ptr<const datasets::HeightTile> heights;  // layer Height
  std::shared_ptr<const datasets::ColorTile> colors;    // layer Imagery
  std::shared_ptr<const TileExtra> extra;               // layer Height, when heightExtra is set
  uint64_t bytes = 0;                                   // what it counts against the CPU budget
  double residentSinceS = 0.0;                          // update() time when it became resident
};

// The nearest resident tile at or above a wanted key.
struct ResidentLookup {
  std::shared_ptr<const ResidentTile> tile;
  int levelsUp = 0;  // 0: the key itself
};

struct Upload {
  std::shared_ptr<const ResidentTile> tile;
  uint32_t slot = 0;  // layer of the GPU imagery array
};

// Figures of the last update() (per frame) plus running totals, for the recorder and the HUD.
struct StreamingFrameStats {
  uint64_t requestsIssued = 0, requestsCompleted = 0, requestsCancelled = 0, requestsFailed = 0;
  uint64_t requestsMissing = 0, retries = 0;
  uint64_t bytesRead = 0;    // payload bytes that arrived this frame
  uint64_t uploadBytes = 0;  // planned for the GPU this frame
  uint64_t evictionsCpu = 0, evictionsGpu = 0;
  uint64_t tilesResidentCpu = 0, tilesResidentGpu = 0;
  uint64_t bytesResidentCpu = 0, bytesResidentGpu = 0;
  uint64_t requestsInFlight = 0, decodesQueued = 0;
  uint64_t wanted = 0, wantedResident = 0;  // current (not look-ahead) wants
  uint64_t wantedBytes = 0;                 // bytes the current wants need resident at once
  bool wantsExceedCpuBudget = false;        // the current wants alone do not fit
  double longestWaitS = 0.0;                // oldest current want not yet resident: now − first wanted
};

// Adds the per-frame counters of `from` (requests, retries, bytes read, upload bytes, evictions)
// to `into`, leaving the snapshot figures (resident, in flight, wanted) alone: for frames made
// of several updates (settle()'s rounds).
void addFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from);
// Replaces the per-frame counters of `into` with those of `from`.
void setFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from);

class TileStreamer {
 public:
  TileStreamer(std::shared_ptr<TileSource> source, datasets::DatasetMeta meta, StreamingOptions options, Logger log);
  ~TileStreamer();  // cancels what is in flight, joins the workers
  TileStreamer(const TileStreamer&) = delete;
  TileStreamer& operator=(const TileStreamer&) = delete;

  const datasets::DatasetMeta& meta() const;
  const StreamingOptions& options() const;

  void update(std::span<const TileWant> wants, double timeS);

  // Resident-CPU (or later) tile, else null. Marks it used.
  std::shared_ptr<const ResidentTile> get(const TileKey& key);
  // The key or its nearest resident ancestor (up to the dataset's min zoom); tile null if none.
  ResidentLookup findResident(const TileKey& key);
  // Same, among imagery tiles that are ResidentGpu, with their slot.
  struct GpuLookup {
    std::shared_ptr<const ResidentTile> tile;
    uint32_t slot = 0;
    int levelsUp = 0;
  };
  GpuLookup findGpuResident(const TileKey& key);

  TileState state(const TileKey& key) const;

  // Why a tile in state Failed or FailedTemporarily failed (Missing tiles have none): the
  // source's or the decoder's message, and whether the bytes arrived but could not be decoded
  // (corrupt data) rather than not arriving (I/O). nullopt for a tile that has not failed.
  struct Failure {
    std::string message;
    bool undecodable = false;
  };
  std::optional<Failure> failure(const TileKey& key) const;

  // For every current imagery want: its nearest CPU-resident ancestor-or-self that is not yet on
  // the GPU (so fallbacks can be drawn too), highest priority first, until `byteBudget` (default:
  // options().uploadBytesPerFrame) or the free slots run out; GPU tiles not used this frame are
  // evicted (least recently used first) to free slots.
  std::vector<Upload> planUploads(std::optional<uint64_t> byteBudget = std::nullopt);
  void uploadsRecorded(std::span<const Upload> uploads);
  // GPU slots the renderer has (from the GPU budget): the size of its imagery array.
  uint32_t gpuSlotCount() const;

  // Settled recordings: one frame like update(wants, timeS), but it waits until nothing is in
  // flight any more — every current want resident (imagery: ResidentCpu or later), Missing,
  // Failed (a current want that fails is asked again at once, up to 3 times) or too big for
  // the budget, and every look-ahead want that fits resident or failed too. What arrives is
  // taken in batches: all requests in flight finish, then their results are taken in request
  // order, then the next requests are issued. So the tiles resident afterwards, the LRU order
  // and the evictions depend on the wants and timeS only, never on when I/O or decoding ended:
  // the same flight gives the same frames. timeS (flight time) is the streamer's time
  // throughout; the clock only bounds the wait (30 s, then a warning and it returns).
  // Blocks the caller — never used by interactive flight. Returns the seconds waited (clock).
  // frameStats() then counts the requests of all its rounds.
  double settle(std::span<const TileWant> wants, double timeS);

  const StreamingFrameStats& frameStats() const;

  // Waits until a read or decode has finished (the next update takes it in) or `timeout` passes;
  // true when one has. For callers that step realtime frames as fast as they like (tests, tools)
  // and want the next frame to have something new, without sleeping.
  bool waitForArrivals(std::chrono::milliseconds timeout);

  // Any thread: how far the tile I/O has got — requests at the source whose callback has not
  // returned, the source's counters, and fetched files queued or being decoded. For a caller
  // that steps a manual clock (tests) and waits for the I/O of one step to settle before the
  // next frame, so that when a tile arrives depends on that clock, not on the wall's.
  struct IoProgress {
    std::size_t sourceInFlight = 0;
    SourceCounters source;
    std::size_t decoding = 0;
  };
  IoProgress ioProgress() const;

  // Keys that became CPU-resident or left the CPU since the last call, in the order it happened
  // (a key may appear twice): how the terrain learns that the heights under it changed.
  std::vector<TileKey> takeResidencyChanges();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vegstream::streaming
