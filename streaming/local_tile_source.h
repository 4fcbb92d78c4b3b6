#pragma once
// LocalTileSource: the TileSource for a dataset directory on disk. A small pool of I/O threads
// (2 by default: enough to keep a local SSD busy while the decode threads work) reads whole
// files; the frame thread only queues requests.
//
// Outcomes: Ok with the file's bytes; Missing when the file does not exist (ENOENT/ENOTDIR);
// Failed for any other read error and for paths that are absolute or climb out of the root
// ("..") — the message names the file. cancel() on a queued request makes it end Cancelled
// without touching the disk; a request being read when cancelled also ends Cancelled (its bytes
// are dropped). Callbacks run on the I/O threads. The destructor ends every queued request
// Cancelled (its callback still runs) and joins the threads.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "streaming/tile_source.h"

namespace vegstream::streaming {

class LocalTileSource final : public TileSource {
 public:
  explicit LocalTileSource(std::filesystem::path datasetDir, int ioThreads = 2);
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
  std::unique_ptr<Impl> impl_;
};

}  // namespace vegstream::streaming
