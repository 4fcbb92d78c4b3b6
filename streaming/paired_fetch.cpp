// PairedFetch (paired_fetch.h): a small join of two fetch callbacks under one mutex.

#include "streaming/paired_fetch.h"

#include <algorithm>
#include <mutex>
#include <optional>

namespace vegstream::streaming::detail {
namespace {

struct Join {
  std::mutex mu;
  std::optional<FetchResult> imagery, ndvi;
  bool delivered = false;
};

// What to hand on once enough is known; nullopt while waiting. Called under the join's lock.
std::optional<FetchResult> joined(Join& j, std::vector<uint8_t>& ndviBytes) {
  if (j.delivered || !j.imagery) return std::nullopt;
  if (j.imagery->outcome != FetchOutcome::Ok) {  // the imagery decides alone; its NDVI is moot
    j.delivered = true;
    return std::move(*j.imagery);
  }
  if (!j.ndvi) return std::nullopt;
  j.delivered = true;
  FetchResult out = std::move(*j.imagery);
  switch (j.ndvi->outcome) {
    case FetchOutcome::Ok: ndviBytes = std::move(j.ndvi->bytes); break;
    case FetchOutcome::Missing: break;  // no NDVI over this tile: the colour alone
    case FetchOutcome::Failed:
    case FetchOutcome::Cancelled:
      out.outcome = FetchOutcome::Failed;
      out.bytes.clear();
      out.message = j.ndvi->message.empty() ? "the tile's NDVI could not be fetched" : j.ndvi->message;
      out.permanent = j.ndvi->permanent;
      break;
  }
  out.attempts = std::max(out.attempts, j.ndvi->attempts);
  return out;
}

}  // namespace

void startPairedFetch(TileSource& source, RequestId id, const TileKey& key, const std::string& imageryPath,
                      const std::string& ndviPath, const std::shared_ptr<DecodePipeline>& pipeline) {
  auto join = std::make_shared<Join>();
  auto arrive = [join, pipeline, key, imageryPath, ndviPath](bool isNdvi, FetchResult&& r) {
    std::optional<FetchResult> out;
    std::vector<uint8_t> ndviBytes;
    {
      std::lock_guard lock(join->mu);
      (isNdvi ? join->ndvi : join->imagery) = std::move(r);
      out = joined(*join, ndviBytes);
    }
    if (out) pipeline->onFetched(key, imageryPath, std::move(*out), std::move(ndviBytes), ndviPath);
  };
  source.start(id, imageryPath, [arrive](FetchResult&& r) mutable { arrive(false, std::move(r)); });
  source.start(companionId(id), ndviPath, [arrive](FetchResult&& r) mutable {
    r.id &= ~(RequestId{1} << 63);  // reported under the request's own id
    arrive(true, std::move(r));
  });
}

}  // namespace vegstream::streaming::detail
