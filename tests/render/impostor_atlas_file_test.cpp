// The impostor atlases' file and key (render/impostor_atlas_file.h), without a GPU: pixels come
// back as they went in; every kind of damage or mismatch — a short or foreign header, another
// layer count, pixel count or key, a truncated, altered or extended zstd frame — is an error value
// saying what, never wrong pixels; the key follows every byte it is given and how they are split.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/impostor_atlas_file.h"

namespace vegstream::render {
namespace {

// An atlas-like block: mostly empty background with a few patches of varying texels.
std::vector<uint8_t> somePixels(size_t n) {
  std::vector<uint8_t> p(n, 0);
  uint32_t h = 12345u;
  for (size_t i = 0; i < n; ++i)
    if ((i / 4096) % 5 == 1) {
      h = h * 1664525u + 1013904223u;
      p[i] = static_cast<uint8_t>(h >> 24);
    }
  return p;
}

std::string keyOf(const std::string& text) {
  ImpostorKey k;
  k.add(text);
  return k.finish();
}

class ImpostorAtlasFile : public ::testing::Test {
 protected:
  const std::vector<uint8_t> pixels_ = somePixels(1 << 20);
  const std::string key_ = keyOf("models A");
  const std::vector<uint8_t> file_ = encodeImpostorAtlas(key_, 3, pixels_);

  // decodeImpostorAtlas's message for `file`, or "" when it decoded (to `out`).
  static std::string problem(const std::vector<uint8_t>& file, const std::string& key, uint32_t layers,
                             std::vector<uint8_t>& out) {
    const Status s = decodeImpostorAtlas(file, key, layers, out);
    if (s) return "";
    EXPECT_EQ(s.error().kind, ErrorKind::InvalidInput);
    return s.error().message;
  }
};

TEST_F(ImpostorAtlasFile, PixelsComeBackAsTheyWentIn) {
  EXPECT_LT(file_.size(), pixels_.size() / 2) << "the empty background compresses";
  std::vector<uint8_t> out(pixels_.size(), 0xee);
  EXPECT_EQ(problem(file_, key_, 3, out), "");
  EXPECT_TRUE(out == pixels_);
  // Level 3 gives the same pixels, in a smaller file.
  EXPECT_LE(encodeImpostorAtlas(key_, 3, pixels_, 3).size(), file_.size());
  // The same input, the same bytes.
  EXPECT_TRUE(encodeImpostorAtlas(key_, 3, pixels_) == file_);
}

TEST_F(ImpostorAtlasFile, EveryMismatchIsAnErrorSayingWhat) {
  std::vector<uint8_t> out(pixels_.size());
  std::vector<uint8_t> shortSpan(pixels_.size() - 4);
  EXPECT_NE(problem(file_, key_, 4, out).find("3 layers, not 4"), std::string::npos);
  EXPECT_NE(problem(file_, keyOf("models B"), 3, out).find("other key"), std::string::npos);
  EXPECT_NE(problem(file_, key_, 3, shortSpan).find("another pixel count"), std::string::npos);
}

TEST_F(ImpostorAtlasFile, EveryDamageIsAnErrorNeverWrongPixels) {
  std::vector<uint8_t> out(pixels_.size());
  auto damaged = [&](auto change) {
    std::vector<uint8_t> f = file_;
    change(f);
    return problem(f, key_, 3, out);
  };
  EXPECT_NE(damaged([](auto& f) { f.resize(20); }).find("truncated header"), std::string::npos);
  EXPECT_NE(damaged([](auto& f) { f[0] = 'X'; }).find("magic"), std::string::npos);
  EXPECT_NE(damaged([](auto& f) { f[8] ^= 1; }).find("format version"), std::string::npos);
  EXPECT_NE(damaged([](auto& f) { f[30] ^= 1; }).find("other key"), std::string::npos);
  EXPECT_NE(damaged([](auto& f) { f.resize(f.size() - 7); }).find("zstd frame"), std::string::npos);
  EXPECT_NE(damaged([](auto& f) { f.push_back(0); }).find("followed by other bytes"), std::string::npos);
  // A changed byte anywhere in the frame's blocks: the content checksum (or the block's own
  // structure) catches it.
  for (size_t at : {file_.size() / 3, file_.size() / 2, file_.size() - 6}) {
    const std::string p = damaged([at](auto& f) { f[at] ^= 0x10; });
    EXPECT_NE(p.find("zstd frame"), std::string::npos) << "byte " << at << ": " << p;
  }
}

TEST(ImpostorKey, FollowsEveryByteAndHowTheyAreSplit) {
  const std::string a = keyOf("abc");
  EXPECT_EQ(a.size(), 64u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(keyOf("abc"), a);
  EXPECT_NE(keyOf("abd"), a);
  ImpostorKey split;
  split.add("ab");
  split.add("c");
  EXPECT_NE(split.finish(), a) << "each piece's length is part of the key";
  ImpostorKey values;
  const uint32_t v[] = {1, 2, 3};
  values.addValues(std::span(v));
  ImpostorKey other;
  const uint32_t w[] = {1, 2, 4};
  other.addValues(std::span(w));
  EXPECT_NE(values.finish(), other.finish());
}

}  // namespace
}  // namespace vegstream::render
