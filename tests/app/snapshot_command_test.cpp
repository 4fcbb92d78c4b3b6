// `vegstream snapshot` (app/snapshot_command.h) as a user runs it, over the imported Zion sample
// on lavapipe: a 320x180 still on the Kolob plateau is a PNG of that size that is not one
// colour, with the validation layers silent; without plants the same pose looks different;
// two runs give the same bytes; every user mistake is one line naming the option, exit 2, and
// no file written.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "tests/support/zion_sample.h"

namespace vegstream::testing {
namespace {
namespace fs = std::filesystem;

Result<fs::path> zionDataset() { return zionSampleDataset(); }

// 2 m above a grassy clearing of the Kolob plateau (37.457 N, 113.022 W), looking north and a
// little down: grass from the camera's feet to the forest.
const std::string kPose = "--lat 37.457 --lon -113.022 --alt 2 --heading 0 --pitch -10";

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};

Image readPng(const fs::path& file) {
  Image img;
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << file << ": " << OIIO::geterror();
  if (!in) return img;
  const OIIO::ImageSpec& spec = in->spec();
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  img.pixels.resize(static_cast<size_t>(img.width) * img.height * img.channels);
  EXPECT_TRUE(in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::UINT8, img.pixels.data()));
  in->close();
  return img;
}

// Pixels (RGB) that differ between two images of the same size.
size_t differingPixels(const Image& a, const Image& b) {
  size_t n = 0;
  for (size_t i = 0; i + 2 < a.pixels.size(); i += static_cast<size_t>(a.channels))
    if (a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] || a.pixels[i + 2] != b.pixels[i + 2]) ++n;
  return n;
}

class SnapshotCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto zion = zionDataset();
    ASSERT_TRUE(zion.ok()) << zion.error().message;
    zion_ = zion->string();
  }
  CommandResult snapshot(const fs::path& out, const std::string& extra = "") const {
    return runVegstream("snapshot '" + zion_ + "' " + kPose + " --size 320x180 --validate --out '" + out.string() +
                        "' " + extra);
  }
  std::string zion_;
};

TEST_F(SnapshotCommand, WritesASettledStillOfTheSizeAskedWithValidationSilent) {
  const fs::path dir = testOutputDir();
  const fs::path out = dir / "still.png";
  const auto r = snapshot(out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did not settle"), std::string::npos) << r.err;
  // One line at the end says what was written.
  const auto at = r.err.find("snapshot written to " + out.string() + ": 320x180");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("plants drawn", at), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;

  const Image img = readPng(out);
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 180);
  ASSERT_GE(img.channels, 3);
  // Not one colour: sky above, ground below, and a spread of values in between.
  uint8_t lo = 255, hi = 0;
  for (size_t i = 0; i < img.pixels.size(); i += static_cast<size_t>(img.channels)) {
    lo = std::min(lo, img.pixels[i + 1]);
    hi = std::max(hi, img.pixels[i + 1]);
  }
  EXPECT_GT(hi - lo, 60) << "green channel " << int(lo) << " … " << int(hi);
  // Nothing but the PNG and its sidecar (tests/app/sun_frames_test.cpp reads it) is left beside it.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path() == out || e.path() == dir / "still.json") << e.path();
  EXPECT_TRUE(fs::exists(dir / "still.json"));
}

TEST_F(SnapshotCommand, PlantsChangeTheStillAndRunsAreIdentical) {
  const fs::path dir = testOutputDir();
  const fs::path a = dir / "a.png", b = dir / "b.png", bare = dir / "bare.png";
  const auto ra = snapshot(a), rb = snapshot(b), rbare = snapshot(bare, "--no-plants");
  ASSERT_EQ(ra.exitCode, 0) << ra.err;
  ASSERT_EQ(rb.exitCode, 0) << rb.err;
  ASSERT_EQ(rbare.exitCode, 0) << rbare.err;
  EXPECT_NE(rbare.err.find("no plants"), std::string::npos) << rbare.err;
  EXPECT_EQ(readWhole(a), readWhole(b)) << "two runs, the same bytes";
  const Image ia = readPng(a), ib = readPng(b), ibare = readPng(bare);
  ASSERT_EQ(ia.pixels.size(), ibare.pixels.size());
  EXPECT_EQ(differingPixels(ia, ib), 0u);
  // Grass 2 m under the camera covers a good part of the ground.
  EXPECT_GT(differingPixels(ia, ibare), 320u * 180u / 20u) << "plants drawn over the clearing";
}

// The trees' impostors kept between runs (--impostor-cache, render/impostor_atlas_cache.h): the
// first run captures and stores them, the second reads them back, a run with the cache off
// captures; the three stills are the same bytes. A damaged entry is one warning naming the file,
// the impostors captured again and stored whole, and still the same still; so is a directory that
// cannot be made.
TEST_F(SnapshotCommand, TheImpostorCacheKeepsTheStillTheSame) {
  const fs::path dir = testOutputDir(), cache = dir / "impostors";
  auto run = [&](const std::string& name, const std::string& cacheArg) {
    return runVegstream("-v snapshot '" + zion_ + "' " + kPose + " --size 160x90 --validate --out '" +
                        (dir / name).string() + "' --impostor-cache " + cacheArg);
  };
  const std::string cacheArg = "'" + cache.string() + "'";
  const auto first = run("first.png", cacheArg), second = run("second.png", cacheArg), off = run("off.png", "off");
  for (const auto* r : {&first, &second, &off}) ASSERT_EQ(r->exitCode, 0) << r->err;
  EXPECT_NE(first.err.find("impostors captured, then cached"), std::string::npos) << first.err;
  EXPECT_NE(second.err.find("impostors from the cache"), std::string::npos) << second.err;
  EXPECT_NE(off.err.find("(impostors captured)"), std::string::npos) << off.err;
  EXPECT_EQ(readWhole(dir / "first.png"), readWhole(dir / "second.png"));
  EXPECT_EQ(readWhole(dir / "first.png"), readWhole(dir / "off.png"));
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(cache)) files.push_back(e.path());
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].extension(), ".vsimpat");

  std::string bytes = readWhole(files[0]);
  const std::string whole = bytes;
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x40);
  std::ofstream(files[0], std::ios::binary | std::ios::trunc) << bytes;
  const auto damaged = run("damaged.png", cacheArg);
  ASSERT_EQ(damaged.exitCode, 0) << damaged.err;
  const auto warn = damaged.err.find("impostor cache " + files[0].string() + ": the pixels' zstd frame");
  ASSERT_NE(warn, std::string::npos) << damaged.err;
  EXPECT_EQ(damaged.err.find("impostor cache", warn + 1), std::string::npos) << "one warning: " << damaged.err;
  EXPECT_NE(damaged.err.find("impostors captured, then cached"), std::string::npos) << damaged.err;
  EXPECT_EQ(readWhole(dir / "first.png"), readWhole(dir / "damaged.png"));
  EXPECT_EQ(readWhole(files[0]), whole) << "stored again, whole";

  // A directory that cannot be made (under a file): one warning, and the still all the same.
  const fs::path under = dir / "first.png" / "impostors";
  const auto unusable = run("unusable.png", "'" + under.string() + "'");
  ASSERT_EQ(unusable.exitCode, 0) << unusable.err;
  EXPECT_NE(unusable.err.find("cannot create the impostor cache directory " + under.string()), std::string::npos)
      << unusable.err;
  EXPECT_NE(unusable.err.find("the impostors are captured without it"), std::string::npos) << unusable.err;
  EXPECT_EQ(readWhole(dir / "first.png"), readWhole(dir / "unusable.png"));
}

TEST_F(SnapshotCommand, UnderTightBudgetsItSettlesOnWhatFitsAndSaysSo) {
  // 300 m over Zion Canyon with room for a few tiles only: the error bound relaxes frame after
  // frame until the wants fit; the still is taken once nothing changes any more, with the pieces
  // that stay coarser named in a warning.
  const fs::path out = testOutputDir() / "tight.png";
  const auto r = runVegstream("snapshot '" + zion_ +
                              "' --lat 37.195 --lon -112.985 --alt 300 --heading 15 --pitch -12 --size 320x180 "
                              "--validate --gpu-budget-mb 1 --cpu-budget-mb 2 --out '" + out.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("drawn from coarser tiles"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--gpu-budget-mb"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("frames to settle"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("(2 frames to settle)"), std::string::npos) << "the bound relaxed over several frames";
  EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
  EXPECT_EQ(readPng(out).width, 320);
}

struct BadInput {
  const char* name;
  std::string args;  // {ZION}: the dataset; {OUT}: the test's output file
  const char* mentions;
};

void PrintTo(const BadInput& b, std::ostream* os) { *os << b.name; }

class SnapshotBadInput : public SnapshotCommand, public ::testing::WithParamInterface<BadInput> {};

TEST_P(SnapshotBadInput, OneLineExitTwoNothingWritten) {
  const fs::path dir = testOutputDir();
  const fs::path out = dir / "still.png";
  fs::create_directories(dir / "a_directory.png");
  std::string args = GetParam().args;
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{ZION}", zion_}, {"{OUT}", out.string()},
                                   {"{DIR}", dir.string()}})
    for (size_t at; (at = args.find(key)) != std::string::npos;) args.replace(at, key.size(), value);
  const auto r = runVegstream("snapshot " + args);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(countLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().mentions), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  // Nothing written: only the directory the test made is there, still empty.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path(), dir / "a_directory.png");
  EXPECT_TRUE(fs::is_empty(dir / "a_directory.png"));
}

const std::string kAt = "--lat 37.457 --lon -113.022 --alt 2 --heading 0 ";
INSTANTIATE_TEST_SUITE_P(
    Cases, SnapshotBadInput,
    ::testing::Values(
        BadInput{"lat_outside", "'{ZION}' --lat 40 --lon -113.022 --alt 2 --heading 0 --pitch -10 --out '{OUT}'",
                 "--lat 40: outside dataset"},
        BadInput{"lon_outside", "'{ZION}' --lat 37.457 --lon -100 --alt 2 --heading 0 --pitch -10 --out '{OUT}'",
                 "--lon -100: outside dataset"},
        BadInput{"lat_impossible", "'{ZION}' --lat 123 --lon -113.022 --alt 2 --heading 0 --pitch -10 --out '{OUT}'",
                 "--lat 123"},
        BadInput{"size_zero", "'{ZION}' " + kAt + "--pitch -10 --size 0x180 --out '{OUT}'", "--size 0x180"},
        BadInput{"size_negative", "'{ZION}' " + kAt + "--pitch -10 --size -320x180 --out '{OUT}'", "--size -320x180"},
        BadInput{"size_garbage", "'{ZION}' " + kAt + "--pitch -10 --size big --out '{OUT}'", "--size big"},
        BadInput{"size_too_large", "'{ZION}' " + kAt + "--pitch -10 --size 99999x90 --out '{OUT}'", "--size 99999x90"},
        BadInput{"pitch_too_high", "'{ZION}' " + kAt + "--pitch 95 --out '{OUT}'", "--pitch 95"},
        BadInput{"pitch_straight_down", "'{ZION}' " + kAt + "--pitch -90 --out '{OUT}'", "--pitch -90"},
        BadInput{"out_missing_directory", "'{ZION}' " + kAt + "--pitch -10 --out '{DIR}/no/such/dir/x.png'",
                 "no/such/dir does not exist"},
        BadInput{"out_is_a_directory", "'{ZION}' " + kAt + "--pitch -10 --out '{DIR}/a_directory.png'",
                 "is a directory"},
        BadInput{"out_not_png", "'{ZION}' " + kAt + "--pitch -10 --out '{DIR}/still.jpg'", "ending in .png"},
        BadInput{"unknown_dataset", "'{DIR}/no_dataset' " + kAt + "--pitch -10 --out '{OUT}'", "no_dataset"},
        BadInput{"alt_below_ground", "'{ZION}' --lat 37.457 --lon -113.022 --alt -5 --heading 0 --pitch -10 --out '{OUT}'",
                 "--alt -5"},
        BadInput{"alt_msl_under_the_ground",
                 "'{ZION}' " + kAt + "--alt-ref msl --pitch -10 --out '{OUT}'", "--alt 2 (above sea level)"},
        BadInput{"alt_ref_unknown", "'{ZION}' " + kAt + "--alt-ref sky --pitch -10 --out '{OUT}'", "--alt-ref"},
        BadInput{"msaa_three", "'{ZION}' " + kAt + "--pitch -10 --msaa 3 --out '{OUT}'", "--msaa 3"},
        BadInput{"unknown_device", "'{ZION}' " + kAt + "--pitch -10 --device no-such-gpu --out '{OUT}'",
                 "no-such-gpu"},
        BadInput{"plant_density", "'{ZION}' " + kAt + "--pitch -10 --plant-density -1 --out '{OUT}'",
                 "--plant-density"},
        BadInput{"missing_pose", "'{ZION}' --lat 37.457 --lon -113.022 --heading 0 --pitch -10 --out '{OUT}'",
                 "--alt"},
        BadInput{"datetime_month_13", "'{ZION}' " + kAt + "--pitch -10 --datetime 2026-13-01 --out '{OUT}'",
                 "--datetime \"2026-13-01\": month 13 does not exist"},
        BadInput{"datetime_without_zone", "'{ZION}' " + kAt + "--pitch -10 --datetime 2026-06-21T06:45 --out '{OUT}'",
                 "--datetime \"2026-06-21T06:45\": no zone"},
        BadInput{"exposure_nan", "'{ZION}' " + kAt + "--pitch -10 --exposure nan --out '{OUT}'",
                 "--exposure nan: must be a number of EV from -10 to 30"},
        BadInput{"aov_unknown", "'{ZION}' " + kAt + "--pitch -10 --aov depth,normals --out '{OUT}'",
                 "--aov depth,normals: no AOV named 'normals'; each must be one of depth, coverage, species"},
        BadInput{"aov_twice", "'{ZION}' " + kAt + "--pitch -10 --aov depth,depth --out '{OUT}'",
                 "--aov depth,depth: 'depth' must be named once"}),
    [](const auto& testInfo) { return std::string(testInfo.param.name); });

}  // namespace
}  // namespace vegstream::testing
