// The impostor atlases kept between processes (impostor_atlas_cache.h).
#include "render/impostor_atlas_cache.h"

#include "core/stopwatch.h"
#include "render/impostor_atlas_file.h"

namespace vegstream::render {

std::string impostorCacheEntry(const std::string& key) { return key + ".vsimpat"; }

std::unique_ptr<TreeImpostors> loadCachedImpostors(const Context& ctx, streaming::DiskTileCache& cache,
                                                   const std::string& key, uint32_t layers,
                                                   ImpostorCacheFigures& figures) {
  Stopwatch watch;
  const std::string entry = impostorCacheEntry(key);
  const std::optional<std::vector<uint8_t>> file = cache.get(entry);
  if (!file) return nullptr;
  auto impostors = TreeImpostors::fromPixels(
      ctx, layers, [&](std::span<uint8_t> pixels) { return decodeImpostorAtlas(*file, key, layers, pixels); });
  if (!impostors) {
    figures.rejected = true;
    cache.remove(entry);
    if (ctx.logger())
      ctx.logger()->warn("impostor cache {}: {}; removed, the impostors captured again",
                         (cache.dir() / streaming::DiskTileCache::relativeFileFor(entry)).string(),
                         impostors.error().message);
    return nullptr;
  }
  figures.hit = true;
  figures.fileBytes = file->size();
  figures.ms = watch.elapsedMs();
  return std::move(*impostors);
}

void storeCachedImpostors(const Context& ctx, streaming::DiskTileCache& cache, const std::string& key,
                          const TreeImpostors& impostors, ImpostorCacheFigures& figures) {
  Stopwatch watch;
  std::vector<uint8_t> file;
  impostors.readPixels(
      [&](std::span<const uint8_t> pixels) { file = encodeImpostorAtlas(key, impostors.layers(), pixels); });
  if (file.size() > cache.budgetBytes()) return;  // the store would refuse it
  if (Status s = cache.put(impostorCacheEntry(key), file); !s) {
    if (ctx.logger()) ctx.logger()->warn("impostor cache: {}", s.error().message);
    return;
  }
  figures.stored = true;
  figures.fileBytes = file.size();
  figures.ms = watch.elapsedMs();
}

}  // namespace vegstream::render
