// The impostor atlases' file and key (impostor_atlas_file.h).
#include "render/impostor_atlas_file.h"

#include <cassert>
#include <cstring>
#include <stdexcept>

#include <openssl/evp.h>
#include <zstd.h>

namespace vegstream::render {
namespace {

constexpr char kMagic[8] = {'V', 'S', 'I', 'M', 'P', 'A', 'T', '1'};
constexpr size_t kKeyDigits = 64;
constexpr size_t kHeaderBytes = sizeof(kMagic) + 4 + 4 + 8 + kKeyDigits;

void putLe(std::vector<uint8_t>& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

uint64_t getLe(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= uint64_t{p[i]} << (8 * i);
  return v;
}

Status bad(const std::string& what) { return makeError(ErrorKind::InvalidInput, what); }

}  // namespace

ImpostorKey::ImpostorKey() : ctx_(EVP_MD_CTX_new()) {
  if (!ctx_ || EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(ctx_), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL: SHA-256 is not available");
}

ImpostorKey::~ImpostorKey() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(ctx_)); }

void ImpostorKey::add(std::span<const uint8_t> bytes) {
  uint8_t length[8];
  for (int i = 0; i < 8; ++i) length[i] = static_cast<uint8_t>(uint64_t{bytes.size()} >> (8 * i));
  auto* c = static_cast<EVP_MD_CTX*>(ctx_);
  EVP_DigestUpdate(c, length, sizeof(length));
  if (!bytes.empty()) EVP_DigestUpdate(c, bytes.data(), bytes.size());
}

std::string ImpostorKey::finish() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(ctx_), digest, &size);
  assert(size * 2 == kKeyDigits);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) {
    hex.push_back(kHex[digest[i] >> 4]);
    hex.push_back(kHex[digest[i] & 15]);
  }
  return hex;
}

std::vector<uint8_t> encodeImpostorAtlas(const std::string& key, uint32_t layers, std::span<const uint8_t> pixels,
                                         int level) {
  assert(key.size() == kKeyDigits);
  std::vector<uint8_t> out(kMagic, kMagic + sizeof(kMagic));
  putLe(out, kHeaderBytes, 4);
  putLe(out, layers, 4);
  putLe(out, pixels.size(), 8);
  out.insert(out.end(), key.begin(), key.end());
  assert(out.size() == kHeaderBytes);
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
  out.resize(kHeaderBytes + ZSTD_compressBound(pixels.size()));
  const size_t n =
      ZSTD_compress2(cctx, out.data() + kHeaderBytes, out.size() - kHeaderBytes, pixels.data(), pixels.size());
  ZSTD_freeCCtx(cctx);
  // The bound holds every input: failing here is a bug in this function, not in the data.
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out.resize(kHeaderBytes + n);
  return out;
}

Status decodeImpostorAtlas(std::span<const uint8_t> file, const std::string& key, uint32_t layers,
                           std::span<uint8_t> pixels) {
  if (file.size() < kHeaderBytes) return bad("truncated header (" + std::to_string(file.size()) + " bytes)");
  const uint8_t* h = file.data();
  if (std::memcmp(h, kMagic, sizeof(kMagic)) != 0) return bad("not an impostor atlas (magic)");
  if (getLe(h + 8, 4) != kHeaderBytes) return bad("another format version (header size)");
  if (getLe(h + 12, 4) != layers)
    return bad(std::to_string(getLe(h + 12, 4)) + " layers, not " + std::to_string(layers));
  if (getLe(h + 16, 8) != pixels.size()) return bad("another pixel count");
  if (key.size() != kKeyDigits || std::memcmp(h + 24, key.data(), kKeyDigits) != 0) return bad("other key");
  const std::span<const uint8_t> frame = file.subspan(kHeaderBytes);
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN || content != pixels.size())
    return bad("the pixels' zstd frame is damaged or of another size");
  if (ZSTD_findFrameCompressedSize(frame.data(), frame.size()) != frame.size())
    return bad("the pixels' zstd frame is truncated or followed by other bytes");
  const size_t n = ZSTD_decompress(pixels.data(), pixels.size(), frame.data(), frame.size());
  if (ZSTD_isError(n)) return bad(std::string("the pixels' zstd frame: ") + ZSTD_getErrorName(n));
  if (n != pixels.size()) return bad("the pixels' zstd frame holds " + std::to_string(n) + " bytes");
  return {};
}

}  // namespace vegstream::render
