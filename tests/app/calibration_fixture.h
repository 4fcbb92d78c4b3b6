#pragma once
// Helpers of the colour-calibration tests (issue 41 item 1): 8-bit RGB GeoTIFFs made from the
// shared samples with GDAL, imported by this build's vegstream, and the species *kind* the
// default catalog picks per imagery pixel (deterministic: the best species, no random draw).

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gdal.h>
#include <gtest/gtest.h>

#include "datasets/dataset_reader.h"
#include "scene/dataset_calibration.h"
#include "tests/support/run_command.h"
#include "tests/support/test_dirs.h"
#include "vegetation/species_catalog.h"
#include "vegetation/species_choice.h"

namespace vegstream::testing {

namespace fs = std::filesystem;

// A window of a raster's bands as floats, with its geotransform and CRS.
struct BandWindow {
  int width = 0, height = 0;
  std::vector<std::vector<float>> bands;
  std::array<double, 6> transform{};
  std::string wkt;
};

inline BandWindow readBands(const std::vector<std::string>& files, int x0, int y0, int w, int h) {
  GDALAllRegister();
  BandWindow out{w, h, {}, {}, {}};
  for (const auto& f : files) {
    GDALDatasetH ds = GDALOpen(f.c_str(), GA_ReadOnly);
    EXPECT_NE(ds, nullptr) << f;
    if (!ds) return out;
    std::vector<float> v(static_cast<size_t>(w) * static_cast<size_t>(h));
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, x0, y0, w, h, v.data(), w, h, GDT_Float32, 0, 0), CE_None);
    if (out.bands.empty()) {
      GDALGetGeoTransform(ds, out.transform.data());
      out.wkt = GDALGetProjectionRef(ds);
      out.transform[0] += x0 * out.transform[1];
      out.transform[3] += y0 * out.transform[5];
    }
    out.bands.push_back(std::move(v));
    GDALClose(ds);
  }
  return out;
}

// Writes 3-band Byte RGB (interleaved 0 … 255 floats, rounded and clamped) as a GeoTIFF.
inline void writeRgbTiff(const fs::path& file, const BandWindow& grid, const std::vector<float>& rgb) {
  GDALAllRegister();
  GDALDriverH drv = GDALGetDriverByName("GTiff");
  GDALDatasetH ds = GDALCreate(drv, file.c_str(), grid.width, grid.height, 3, GDT_Byte, nullptr);
  ASSERT_NE(ds, nullptr) << file;
  std::array<double, 6> t = grid.transform;
  GDALSetGeoTransform(ds, t.data());
  GDALSetProjection(ds, grid.wkt.c_str());
  const size_t n = static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height);
  for (int c = 0; c < 3; ++c) {
    std::vector<uint8_t> b(n);
    for (size_t i = 0; i < n; ++i)
      b[i] = static_cast<uint8_t>(std::lround(std::fmin(std::fmax(rgb[i * 3 + static_cast<size_t>(c)], 0.0f), 255.0f)));
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, c + 1), GF_Write, 0, 0, grid.width, grid.height, b.data(), grid.width,
                           grid.height, GDT_Byte, 0, 0),
              CE_None);
  }
  GDALClose(ds);
}

inline Status importDataset(const std::string& args, const fs::path& out) {
  const auto r = runVegstream("import " + args + " --out '" + out.string() + "'");
  if (r.exitCode != 0) return makeError(ErrorKind::Internal, "vegstream import " + args + ": " + r.err);
  return {};
}

// The kinds a species can grow as, and bare.
enum class Kind { Grass = 0, Gravel = 1, Flowers = 2, Tree = 3, Bare = 4 };
inline constexpr const char* kKindNames[] = {"grass", "gravel", "flowers", "tree", "bare"};

inline Kind kindOf(const vegetation::SpeciesCatalog& catalog, int species) {
  if (species < 0 || catalog.species[static_cast<size_t>(species)].bare) return Kind::Bare;
  return static_cast<Kind>(catalog.species[static_cast<size_t>(species)].kind);
}

// The kind of the best species at one 8-bit sRGB pixel through `catalog`'s calibration.
inline Kind kindAt(const vegetation::SpeciesCatalog& catalog, const uint8_t* p) {
  const glm::vec3 linear(vegetation::srgbDecode(p[0] / 255.0f), vegetation::srgbDecode(p[1] / 255.0f),
                         vegetation::srgbDecode(p[2] / 255.0f));
  return kindOf(catalog, vegetation::speciesCandidatesAt(catalog, linear).first);
}

// Per max-zoom imagery tile of `dataset`, every `step`-th pixel in both directions (the cells),
// in tile order: the kind there, −1 where there is no imagery.
inline std::vector<int> kindMap(const fs::path& dataset, const vegetation::SpeciesCatalog& catalog,
                                const std::vector<geo::TileId>& tiles, int step) {
  auto reader = datasets::DatasetReader::open(dataset);
  EXPECT_TRUE(reader.ok()) << (reader ? "" : reader.error().message);
  std::vector<int> out;
  if (!reader) return out;
  for (const geo::TileId& id : tiles) {
    auto tile = reader->colorTile(id);
    EXPECT_TRUE(tile.ok());
    for (int y = step / 2; y < 256; y += step)
      for (int x = step / 2; x < 256; x += step) {
        if (!tile.ok() || !*tile) {
          out.push_back(-1);
          continue;
        }
        const uint8_t* p = &(**tile).rgba[(static_cast<size_t>(y) * 256 + static_cast<size_t>(x)) * 4];
        out.push_back(p[3] == 0 ? -1 : static_cast<int>(kindAt(catalog, p)));
      }
  }
  return out;
}

// The catalog as it chose before issue 41: no calibration (the identity) and no excess-green term.
inline vegetation::SpeciesCatalog uncalibratedCatalog(const vegetation::SpeciesCatalog& catalog) {
  vegetation::SpeciesCatalog out = catalog;
  out.calibration = {};
  for (auto& s : out.species) s.score.exgWeight = 0.0f;
  return out;
}

inline std::vector<geo::TileId> maxZoomTiles(const fs::path& dataset, int zoom) {
  std::vector<geo::TileId> out;
  for (const auto& x : fs::directory_iterator(dataset / "imagery" / std::to_string(zoom)))
    for (const auto& y : fs::directory_iterator(x.path()))
      out.push_back({zoom, std::stoi(x.path().filename().string()), std::stoi(y.path().stem().string())});
  std::sort(out.begin(), out.end(), [](const geo::TileId& a, const geo::TileId& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  });
  return out;
}

}  // namespace vegstream::testing
