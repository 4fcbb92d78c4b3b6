#pragma once
// The impostor atlases kept between processes (impostor_atlas_file.h) in an on-disk byte store
// (streaming/disk_tile_cache.h: atomic files, a byte budget, the least recently used evicted),
// one entry per key: "<key>.vsimpat".
//
// A cache must never stop the program nor change a frame: an entry that cannot be read or does
// not decode as the key's atlas is removed and reported once (a warning naming the file and what
// is wrong), and the caller captures again; a failed store is a warning too.

#include <memory>
#include <string>

#include "render/context.h"
#include "render/impostor_atlas_file.h"
#include "render/tree_impostors.h"
#include "streaming/disk_tile_cache.h"

namespace vegstream::render {

// The cache's entry name of `key` (ImpostorKey::finish()).
std::string impostorCacheEntry(const std::string& key);

// The atlases of `layers` models from the entry of `key`; null on a miss or a rejected entry.
std::unique_ptr<TreeImpostors> loadCachedImpostors(const Context& ctx, streaming::DiskTileCache& cache,
                                                   const std::string& key, uint32_t layers,
                                                   ImpostorCacheFigures& figures);

// Reads `impostors` back and stores them under `key`.
void storeCachedImpostors(const Context& ctx, streaming::DiskTileCache& cache, const std::string& key,
                          const TreeImpostors& impostors, ImpostorCacheFigures& figures);

}  // namespace vegstream::render
