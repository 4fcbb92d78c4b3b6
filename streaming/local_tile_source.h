#pragma once
// LocalTileSource: the TileSource for a dataset directory on disk. Reads of whole files run as
// tasks of an injected TaskRunner (core/task_runner.h), at most `ioConcurrency` at once (2 by
// default: enough to keep a local SSD busy while the decodes run); the frame thread only queues
// requests.
//
// Outcomes: Ok with the file's bytes; Missing when the file does not exist (ENOENT/ENOTDIR);
// Failed for any other read error and for paths that are absolute or climb out of the root
// ("..") — the message names the file. cancel() on a queued request makes it end Cancelled
// without touching the disk; a request being read when cancelled also ends Cancelled (its bytes
// are dropped). Callbacks run on the runner's tasks, never inside start() or cancel(). The
// destructor ends every queued request Cancelled (its callback runs, on the destroying thread)
// and waits for the reads under way; tasks that run later find nothing to do. The runner must
// outlive the source; without one the source makes a ThreadPool of its own.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "core/task_runner.h"
#include "streaming/tile_source.h"

namespace vegstream::streaming {

class LocalTileSource final : public TileSource {
 public:
  explicit LocalTileSource(std::filesystem::path datasetDir, int ioConcurrency = 2, TaskRunner* tasks = nullptr);
  ~LocalTileSource() override;
  LocalTileSource(const LocalTileSource&) = delete;
  LocalTileSource& operator=(const LocalTileSource&) = delete;

  std::string describe() const override;  // "dir /path/to/dataset"
  Result<std::string> readText(const std::string& relativePath) override;
  void start(RequestId id, const std::string& relativePath, FetchCallback done) override;
  void cancel(RequestId id) override;
  std::size_t inFlight() const override;
  SourceCounters counters() const override;

 private:
  struct Impl;
  std::unique_ptr<ThreadPool> ownPool_;  // only without an injected runner; after impl_ is done
  std::shared_ptr<Impl> impl_;           // shared with the tasks posted
};

}  // namespace vegstream::streaming
