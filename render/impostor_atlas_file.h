#pragma once
// The impostor atlases (tree_impostors.h) as bytes kept between processes. A capture draws every
// model 64 times over 768² pixels: 3.4 s on a CPU rasteriser for the default catalog's 18 models
// at every start of the program; read back from a file it is a decompression and one upload.
//
// The key is the SHA-256 (OpenSSL) of everything the capture's result depends on — fed by the
// caller through ImpostorKey: the capture shaders' SPIR-V, the models' vertices, indices, GPU
// records and cells, the atlas' layout constants, and the device and driver that rasterised it
// (vendor, device, driver version, pipeline-cache UUID, driver name; images are the same only on
// the same driver, DESIGN.md "Determinism"). Any change of those gives another key, never a
// stale atlas.
//
// The file: an 88-byte header — the magic "VSIMPAT1", the header's size, the layers, the pixels'
// byte count (little-endian), the key's 64 hex digits — then the pixels as one zstd frame with
// its content checksum. decodeImpostorAtlas checks every field, the frame's size and checksum; an
// entry that fails is an error value saying what, so the caller captures again (a cache never
// stops the program, nor puts wrong pixels on screen).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/result.h"

namespace vegstream::render {

// What came of an atlas' trip through the cache (impostor_atlas_cache.h; for the log and the tests).
struct ImpostorCacheFigures {
  bool hit = false;        // the atlases came from the cache
  bool stored = false;     // captured, then stored
  bool rejected = false;   // an entry was there but did not decode (removed)
  uint64_t fileBytes = 0;  // of the entry read or stored
  double ms = 0.0;         // reading and uploading, or reading back, encoding and storing
};

// SHA-256 over the pieces added, in order (each piece's length goes in first, so two splits of
// the same bytes give different keys).
class ImpostorKey {
 public:
  ImpostorKey();
  ~ImpostorKey();
  ImpostorKey(const ImpostorKey&) = delete;
  ImpostorKey& operator=(const ImpostorKey&) = delete;

  void add(std::span<const uint8_t> bytes);
  void add(std::string_view text) { add(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size())); }
  template <class T, size_t N>
  void addValues(std::span<T, N> values) {
    add(std::span(reinterpret_cast<const uint8_t*>(values.data()), values.size_bytes()));
  }
  template <class T>
  void addValue(const T& value) {
    addValues(std::span<const T>(&value, 1));
  }
  // The digest as 64 lower-case hex digits; the key takes nothing more after it.
  std::string finish();

 private:
  void* ctx_;  // EVP_MD_CTX
};

// The file of `pixels` (the atlases' levels, TreeImpostors::pixelBytes(layers) of them) under `key`.
// zstd level `level` (1: the fastest; 3 makes it 10 % smaller and twice as slow).
std::vector<uint8_t> encodeImpostorAtlas(const std::string& key, uint32_t layers, std::span<const uint8_t> pixels,
                                         int level = 1);

// Unpacks `file` into `pixels` (exactly its size) when it is the atlas of `key` with `layers`
// layers; otherwise InvalidInput naming what does not match ("truncated header", "other key", "the
// pixels' zstd frame: Restored data doesn't match checksum", …). `pixels` is undefined after an error.
Status decodeImpostorAtlas(std::span<const uint8_t> file, const std::string& key, uint32_t layers,
                           std::span<uint8_t> pixels);

}  // namespace vegstream::render
