// PairedFetch (paired_fetch.h): a small join of several fetch callbacks under one mutex.

#include "streaming/paired_fetch.h"

#include <algorithm>
#include <mutex>
#include <optional>

#include "streaming/decode_pipeline.h"

namespace vegstream::streaming::detail {
namespace {

struct Join {
  std::mutex mu;
  std::optional<FetchResult> imagery;
  std::array<std::optional<FetchResult>, kCompanionCount> companions;
  std::array<bool, kCompanionCount> expected{};
  bool delivered = false;
};

// What to hand on once enough is known; nullopt while waiting. Called under the join's lock.
std::optional<FetchResult> joined(Join& j, CompanionBytes& companions) {
  if (j.delivered || !j.imagery) return std::nullopt;
  if (j.imagery->outcome != FetchOutcome::Ok) {  // the imagery decides alone; its companions are moot
    j.delivered = true;
    return std::move(*j.imagery);
  }
  for (size_t c = 0; c < kCompanionCount; ++c)
    if (j.expected[c] && !j.companions[c]) return std::nullopt;
  j.delivered = true;
  FetchResult out = std::move(*j.imagery);
  for (size_t c = 0; c < kCompanionCount; ++c) {
    if (!j.expected[c]) continue;
    FetchResult& r = *j.companions[c];
    out.attempts = std::max(out.attempts, r.attempts);
    switch (r.outcome) {
      case FetchOutcome::Ok: companions.bytes[c] = std::move(r.bytes); break;
      case FetchOutcome::Missing: break;  // none of this layer over the tile: without it
      case FetchOutcome::Failed:
      case FetchOutcome::Cancelled:
        if (out.outcome == FetchOutcome::Ok) {
          out.outcome = FetchOutcome::Failed;
          out.bytes.clear();
          out.message = r.message.empty() ? "a companion file of the tile could not be fetched" : r.message;
          out.permanent = r.permanent;
        }
        break;
    }
  }
  if (out.outcome != FetchOutcome::Ok) companions = {};
  return out;
}

}  // namespace

std::vector<CompanionFile> companionsOf(const datasets::DatasetMeta& meta, const geo::TileId& id) {
  std::vector<CompanionFile> out;
  if (meta.ndvi) out.push_back({Companion::Ndvi, datasets::ndviTilePath({}, id).generic_string()});
  if (meta.landcover) out.push_back({Companion::Landcover, datasets::landcoverTilePath({}, id).generic_string()});
  return out;
}

void cancelCompanions(TileSource& source, const datasets::DatasetMeta& meta, RequestId id) {
  if (meta.ndvi) source.cancel(companionId(id, Companion::Ndvi));
  if (meta.landcover) source.cancel(companionId(id, Companion::Landcover));
}

void startPairedFetch(TileSource& source, RequestId id, const TileKey& key, const std::string& imageryPath,
                      std::vector<CompanionFile> companions, const std::shared_ptr<DecodePipeline>& pipeline) {
  auto join = std::make_shared<Join>();
  CompanionBytes names;
  for (const CompanionFile& f : companions) {
    join->expected[static_cast<size_t>(f.kind)] = true;
    names.names[static_cast<size_t>(f.kind)] = f.path;
  }
  // index kCompanionCount: the imagery itself.
  auto arrive = [join, pipeline, key, imageryPath, names](size_t which, FetchResult&& r) {
    std::optional<FetchResult> out;
    CompanionBytes got;
    {
      std::lock_guard lock(join->mu);
      (which == kCompanionCount ? join->imagery : join->companions[which]) = std::move(r);
      out = joined(*join, got);
    }
    if (!out) return;
    got.names = names.names;
    pipeline->onFetched(key, imageryPath, std::move(*out), std::move(got));
  };
  source.start(id, imageryPath, [arrive](FetchResult&& r) mutable { arrive(kCompanionCount, std::move(r)); });
  for (const CompanionFile& f : companions)
    source.start(companionId(id, f.kind), f.path, [arrive, c = static_cast<size_t>(f.kind)](FetchResult&& r) mutable {
      r.id = requestOfCompanion(r.id);  // reported under the request's own id
      arrive(c, std::move(r));
    });
}

}  // namespace vegstream::streaming::detail
