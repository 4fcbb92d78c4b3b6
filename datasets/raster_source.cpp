// Raster sources through GDAL (raster_source.h): opening, mosaicking, bands, masks, windows.

#include "datasets/raster_source.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <mutex>

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include "datasets/message.h"
#include "datasets/gdal_raster_io.h"
#include "geo/gdal_quiet.h"

namespace vegstream::datasets {

struct RasterSource::Shared {
  std::string label, gdalPath, vrtPath, driver;
  int width = 0, height = 0;
  std::vector<int> bands;
  std::vector<double> scale, offset;
  GeoReference georef;
  SourceOptions options;
  double verticalScale = 1.0;
  std::optional<std::string> datetime;
  std::string typeName;
  std::mutex mutex;
  std::vector<GDALDataset*> idle;  // handles no thread is using

  ~Shared() {
    geo::GdalQuiet quiet;  // closing may complain too; the reads already reported
    for (GDALDataset* d : idle) GDALClose(d);
    if (!vrtPath.empty()) VSIUnlink(vrtPath.c_str());
  }
};

namespace {
namespace fs = std::filesystem;

std::atomic<int> mosaicCount{0};
// A whole read holds at most this many samples (1 GiB of float).
constexpr double kMaxWholeSamples = 268435456.0;
// What GDAL is let allocate for a raster, checked at open before any read (its block cache holds
// whole blocks; each block it touches is an object): a file of a few hundred bytes can claim
// thousands of bands or a block of gigabytes (issue 42 item 1; fuzz/regressions/raster_source/).
constexpr size_t kMaxBands = 64;                // bands taken from one source
constexpr double kMaxBlockBytes = 268435456.0;  // 256 MiB: one GDAL block (a strip, a tile)
constexpr double kMaxBlocks = 16777216.0;       // blocks over every band taken
// Blocks a file names but does not hold (sparse or truncated files) are filled by GDAL on every
// read that touches them, and their claim costs the file nothing: a 410-byte GeoTIFF claiming
// 3.3 TB of missing strips took 11 s for one 2 x 3 547-pixel overview. The missing bytes over the
// bands taken may be at most 1 GiB plus 64 x the inputs' size on disk (fuzz/regressions/README.md).
constexpr double kMaxMissingBaseBytes = 1073741824.0;
constexpr double kMaxMissingPerFileByte = 64.0;

GDALDataset* openHandle(const std::string& path) {
  return GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr, nullptr,
                           nullptr);
}

// A handle of the shared pool, returned to it when done.
class Handle {
 public:
  explicit Handle(RasterSource::Shared& s) : s_(s) {
    std::lock_guard lock(s.mutex);
    if (!s.idle.empty()) {
      d_ = s.idle.back();
      s.idle.pop_back();
    }
  }
  ~Handle() {
    if (!d_) return;
    std::lock_guard lock(s_.mutex);
    s_.idle.push_back(d_);
  }
  GDALDataset* get() {
    if (!d_) d_ = openHandle(s_.gdalPath);
    return d_;
  }

 private:
  RasterSource::Shared& s_;
  GDALDataset* d_ = nullptr;
};

// A local input must be a regular file before GDAL sees it: a FIFO would block the open, a
// directory or a device is never a raster.
Status checkLocalFile(const std::string& input) {
  if (isUrl(input) || input.rfind("/vsi", 0) == 0) return {};
  std::error_code ec;
  if (!fs::exists(input, ec)) return makeError(ErrorKind::NotFound, concat(input, " does not exist"));
  if (!fs::is_regular_file(input, ec)) return makeError(ErrorKind::InvalidInput, concat(input, ": not a regular file"));
  return {};
}

Error openError(const std::string& input, const geo::GdalQuiet& quiet) {
  if (auto s = checkLocalFile(input); !s) return s.error();
  return makeError(ErrorKind::InvalidInput, concat(input, ": ", geo::gdalReason(quiet, "not a raster GDAL can read")));
}

// One dataset path for all inputs: the input itself, or a VRT mosaic of them in /vsimem/.
Result<std::string> mosaicPath(const std::vector<std::string>& inputs, std::string& vrtPath) {
  if (inputs.size() == 1) return gdalPathOf(inputs[0]);
  geo::GdalQuiet quiet;
  std::vector<GDALDatasetH> sources;
  const auto closeAll = [&] {
    for (GDALDatasetH h : sources) GDALClose(h);
  };
  for (const auto& in : inputs) {
    GDALDataset* d = openHandle(gdalPathOf(in));
    if (!d) {
      closeAll();
      return openError(in, quiet);
    }
    sources.push_back(GDALDataset::ToHandle(d));
  }
  vrtPath = "/vsimem/vegstream/mosaic-" + std::to_string(mosaicCount.fetch_add(1)) + ".vrt";
  int usage = 0;
  GDALDatasetH vrt =
      GDALBuildVRT(vrtPath.c_str(), static_cast<int>(sources.size()), sources.data(), nullptr, nullptr, &usage);
  const bool ok = vrt != nullptr;
  if (vrt) GDALClose(vrt);
  closeAll();
  if (!ok)
    return makeError(ErrorKind::InvalidInput, concat(inputs[0], " + ", inputs.size() - 1, " more: cannot mosaic them (",
                                                     geo::gdalReason(quiet, "different CRSs or band counts"), ")"));
  return vrtPath;
}

Status checkGeoreference(RasterSource::Shared& s, GDALDataset& d) {
  if (d.GetGeoTransform(s.georef.transform.data()) != CE_None) {
    if (d.GetGCPCount() > 0)
      return makeError(ErrorKind::Unsupported,
                       concat(s.label,
                              " is georeferenced by ground control points only; warp it onto a grid first "
                              "(gdalwarp)"));
    return makeError(ErrorKind::InvalidInput, concat(s.label, " has no georeference (no geotransform)"));
  }
  const auto& t = s.georef.transform;
  const double det = t[1] * t[5] - t[2] * t[4];
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    return makeError(ErrorKind::InvalidInput, concat(s.label, " has a degenerate georeference (zero pixel size)"));
  const OGRSpatialReference* srs = d.GetSpatialRef();
  if (srs && !srs->IsEmpty()) {
    const char* name = srs->GetName();
    s.georef.crsDescription = name ? name : "";
    if (s.options.heights) s.verticalScale = verticalUnitScale(*srs, s.verticalScale);
  }
  if (s.options.assumeCrs) {
    s.georef.crs = s.options.assumeCrs;
    return {};
  }
  if (!srs || srs->IsEmpty())
    return makeError(ErrorKind::Unsupported,
                     concat(s.label, " names no CRS; state it with ", s.options.crsFlag, " (e.g. EPSG:32612)"));
  char* wkt = nullptr;
  const char* const opts[] = {"FORMAT=WKT2_2019", nullptr};
  srs->exportToWkt(&wkt, opts);
  auto crs = geo::Crs::fromWkt(wkt ? wkt : "");
  CPLFree(wkt);
  if (!crs)
    return makeError(ErrorKind::Unsupported,
                     concat(s.label, ": ", crs.error().message, "; state its CRS with ", s.options.crsFlag));
  s.georef.crs = *crs;
  return {};
}

Status chooseBands(RasterSource::Shared& s, GDALDataset& d) {
  const int n = d.GetRasterCount();
  if (n == 0) return makeError(ErrorKind::InvalidInput, concat(s.label, " has no raster band"));
  s.bands = s.options.bands;
  for (int b : s.bands)
    if (b < 1 || b > n)
      return makeError(ErrorKind::InvalidInput, concat(s.options.flag, " ", s.label, ": band ", b,
                                                       " does not exist (the file has ", n, " bands)"));
  if (s.bands.empty())
    for (int b = 1; b <= n; ++b)
      if (d.GetRasterBand(b)->GetColorInterpretation() != GCI_AlphaBand) s.bands.push_back(b);
  if (s.bands.empty()) return makeError(ErrorKind::InvalidInput, concat(s.label, " has only an alpha band"));
  for (int b : s.bands) {
    GDALRasterBand* band = d.GetRasterBand(b);
    int has = 0;
    const double sc = band->GetScale(&has);
    s.scale.push_back(s.options.heights && has ? sc : 1.0);
    const double of = band->GetOffset(&has);
    s.offset.push_back(s.options.heights && has ? of : 0.0);
    if (s.options.heights) s.verticalScale = bandUnitScale(band->GetUnitType(), s.verticalScale);
  }
  s.typeName = GDALGetDataTypeName(d.GetRasterBand(s.bands[0])->GetRasterDataType());
  return {};
}

// The ceilings above, from the header alone: the bands taken, each band's block (all the
// file's bands when they are interleaved by pixel) and the blocks a whole read would touch.
Status checkBlocks(const RasterSource::Shared& s, GDALDataset& d) {
  if (s.bands.size() > kMaxBands)
    return makeError(ErrorKind::InvalidInput, concat(s.label, ": ", s.bands.size(), " bands, more than the ", kMaxBands,
                                                     " a source may have; name the bands to take"));
  const char* interleave = d.GetMetadataItem("INTERLEAVE", "IMAGE_STRUCTURE");
  const bool byPixel = interleave && std::string(interleave) == "PIXEL";
  double blocks = 0.0;
  for (int b : s.bands) {
    GDALRasterBand* band = d.GetRasterBand(b);
    int bx = 0, by = 0;
    band->GetBlockSize(&bx, &by);
    if (bx <= 0 || by <= 0) return makeError(ErrorKind::InvalidInput, concat(s.label, ": band ", b, " has no blocks"));
    const double bytes =
        double(bx) * by * GDALGetDataTypeSizeBytes(band->GetRasterDataType()) * (byPixel ? d.GetRasterCount() : 1);
    if (bytes > kMaxBlockBytes)
      return makeError(
          ErrorKind::InvalidInput,
          concat(s.label, ": its blocks are ", bx, " x ", by, " pixels (", static_cast<int64_t>(bytes / 1048576.0),
                 " MiB), more than the ", static_cast<int64_t>(kMaxBlockBytes / 1048576.0),
                 " MiB a block may hold; rewrite it tiled (gdal_translate -co TILED=YES)"));
    blocks += std::ceil(double(s.width) / bx) * std::ceil(double(s.height) / by);
  }
  if (blocks > kMaxBlocks)
    return makeError(ErrorKind::InvalidInput,
                     concat(s.label, ": ", static_cast<int64_t>(blocks), " blocks over its bands, more than the ",
                            static_cast<int64_t>(kMaxBlocks), " a source may have; rewrite it with larger tiles"));
  return {};
}

// The inputs' size on disk (or on the server, through GDAL's virtual file systems).
double inputBytes(const std::vector<std::string>& inputs) {
  double bytes = 0.0;
  for (const auto& in : inputs) {
    VSIStatBufL st;
    if (VSIStatL(gdalPathOf(in).c_str(), &st) == 0) bytes += static_cast<double>(st.st_size);
  }
  return bytes;
}

// The share of `band`'s pixels in blocks the file holds, from GDAL's coverage status (the GTiff
// driver reads it from the block offsets; a driver without it claims all). Asking costs a lookup
// per block, microseconds each but 35 s over the 6 million strips of a mutated GeoTIFF: past
// `samples` blocks, that many blocks spread evenly over the raster are asked instead.
double dataShare(GDALRasterBand& band, int width, int height, int samples) {
  int bx = 0, by = 0;
  band.GetBlockSize(&bx, &by);
  const int64_t across = (width + int64_t{bx} - 1) / bx, down = (height + int64_t{by} - 1) / by;
  const int64_t blocks = across * down;
  double percent = 100.0;
  if (blocks <= samples) {
    const int status = band.GetDataCoverageStatus(0, 0, width, height, 0, &percent);
    return (status & GDAL_DATA_COVERAGE_STATUS_UNIMPLEMENTED) ? 1.0 : std::clamp(percent, 0.0, 100.0) / 100.0;
  }
  double sum = 0.0;
  for (int k = 0; k < samples; ++k) {
    const int64_t block = k * blocks / samples;
    const int x = static_cast<int>(block % across) * bx, y = static_cast<int>(block / across) * by;
    const int status = band.GetDataCoverageStatus(x, y, std::min(bx, width - x), std::min(by, height - y), 0, &percent);
    if (status & GDAL_DATA_COVERAGE_STATUS_UNIMPLEMENTED) return 1.0;
    sum += std::clamp(percent, 0.0, 100.0) / 100.0;
  }
  return sum / samples;
}

// The bytes of the bands taken that lie in blocks the file does not hold (estimated from at most
// 4 096 blocks over all of them).
Status checkMissingBlocks(const RasterSource::Shared& s, GDALDataset& d, double fileBytes) {
  double missing = 0.0;
  const int samples = std::max(1, 4096 / static_cast<int>(s.bands.size()));
  for (int b : s.bands) {
    GDALRasterBand* band = d.GetRasterBand(b);
    missing += (1.0 - dataShare(*band, s.width, s.height, samples)) * double(s.width) * double(s.height) *
               GDALGetDataTypeSizeBytes(band->GetRasterDataType());
  }
  const double ceiling = kMaxMissingBaseBytes + kMaxMissingPerFileByte * fileBytes;
  if (missing <= ceiling) return {};
  return makeError(
      ErrorKind::InvalidInput,
      concat(s.label, ": ", static_cast<int64_t>(missing / 1048576.0), " MiB of its ", s.width, " x ", s.height,
             " pixels lie in blocks the file does not hold (a sparse or truncated file), more "
             "than the ",
             static_cast<int64_t>(ceiling / 1048576.0),
             " MiB read for one this size; rewrite it whole (gdal_translate) or crop it"));
}

}  // namespace

bool isUrl(const std::string& input) { return input.rfind("http://", 0) == 0 || input.rfind("https://", 0) == 0; }

std::string gdalPathOf(const std::string& input) { return isUrl(input) ? "/vsicurl/" + input : input; }

Result<RasterSource> RasterSource::open(const std::vector<std::string>& inputs, const SourceOptions& options) {
  if (inputs.empty()) return makeError(ErrorKind::InvalidInput, concat(options.flag, ": no input given"));
  for (const auto& in : inputs)
    if (auto st = checkLocalFile(in); !st) return st.error();
  geo::GdalQuiet quiet;
  auto s = std::make_shared<Shared>();
  s->options = options;
  s->label = inputs.size() == 1 ? inputs[0] : concat(inputs[0], " + ", inputs.size() - 1, " more");
  auto path = mosaicPath(inputs, s->vrtPath);
  if (!path) return path.error();
  s->gdalPath = *path;
  GDALDataset* d = openHandle(s->gdalPath);
  if (!d) return openError(inputs[0], quiet);
  s->idle.push_back(d);
  s->driver = d->GetDriver() ? d->GetDriver()->GetDescription() : "";
  s->width = d->GetRasterXSize();
  s->height = d->GetRasterYSize();
  if (s->width <= 0 || s->height <= 0) return makeError(ErrorKind::InvalidInput, concat(s->label, " has no pixels"));
  if (auto st = chooseBands(*s, *d); !st) return st.error();
  if (auto st = checkBlocks(*s, *d); !st) return st.error();
  if (auto st = checkMissingBlocks(*s, *d, inputBytes(inputs)); !st) return st.error();
  if (auto st = checkGeoreference(*s, *d); !st) return st.error();
  s->datetime = acquisitionDatetimeOf(*d);
  RasterSource r;
  r.s_ = std::move(s);
  return r;
}

const std::string& RasterSource::label() const { return s_->label; }
int RasterSource::width() const { return s_->width; }
int RasterSource::height() const { return s_->height; }
int RasterSource::channels() const { return static_cast<int>(s_->bands.size()); }
const GeoReference& RasterSource::georef() const { return s_->georef; }
const geo::Crs& RasterSource::crs() const { return *s_->georef.crs; }
const std::string& RasterSource::driver() const { return s_->driver; }
double RasterSource::verticalScale() const { return s_->verticalScale; }
std::optional<std::string> RasterSource::acquisitionDatetime() const { return s_->datetime; }

std::string RasterSource::description() const {
  return concat(s_->width, "x", s_->height, " px, ", s_->bands.size(), s_->bands.size() == 1 ? " band " : " bands ",
                s_->typeName, ", GDAL driver ", s_->driver);
}

Result<Raster> RasterSource::read(int x0, int y0, int w, int h, int maxSide) const {
  const int x1 = std::min(x0 + w, s_->width), y1 = std::min(y0 + h, s_->height);
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  w = x1 - x0;
  h = y1 - y0;
  if (w <= 0 || h <= 0) return makeError(ErrorKind::InvalidInput, concat(s_->label, ": empty window"));
  int bw = w, bh = h;
  if (maxSide > 0 && std::max(w, h) > maxSide) {
    const double f = static_cast<double>(std::max(w, h)) / maxSide;
    bw = std::max(1, static_cast<int>(std::ceil(w / f)));
    bh = std::max(1, static_cast<int>(std::ceil(h / f)));
  }
  if (static_cast<double>(bw) * bh * channels() > kMaxWholeSamples)
    return makeError(ErrorKind::InvalidInput, concat(s_->label, ": a window of ", bw, " x ", bh, " is too large"));
  Raster r;
  r.path = s_->label;
  r.width = bw;
  r.height = bh;
  r.channels = channels();
  r.georef = s_->georef;
  r.origin = {x0, y0};
  r.step = {static_cast<double>(w) / bw, static_cast<double>(h) / bh};
  r.samples.assign(static_cast<size_t>(bw) * static_cast<size_t>(bh) * static_cast<size_t>(r.channels), NAN);
  geo::GdalQuiet quiet;
  Handle handle(*s_);
  GDALDataset* d = handle.get();
  if (!d) return makeError(ErrorKind::InvalidInput, concat(s_->label, ": ", geo::gdalReason(quiet, "cannot reopen")));
  if (auto st = readWindow(*d, s_->bands, s_->scale, s_->offset, s_->options.nodataOverride,
                           s_->options.heights ? s_->verticalScale : 1.0, {x0, y0, w, h}, r);
      !st)
    return makeError(ErrorKind::InvalidInput,
                     concat(s_->label, ": ", st.error().message, " (", geo::gdalReason(quiet, "no reason given"), ")"));
  return r;
}

Result<Raster> RasterSource::readOverview(uint64_t maxPixels) const {
  const double pixels = static_cast<double>(s_->width) * static_cast<double>(s_->height);
  if (pixels <= static_cast<double>(maxPixels)) return read(0, 0, s_->width, s_->height);
  const double f = std::sqrt(pixels / static_cast<double>(maxPixels));
  // A raster far longer than wide is one pixel across before its long side is that short: the
  // long side is then held to maxPixels itself. Without it, a 1 x 20 000 000 raster was read as
  // 286 000 pixels for an overview of 4 096, 70 times the bound (found profiling the
  // raster_source fuzz target).
  const double longSide = std::min(std::max(s_->width, s_->height) / f, static_cast<double>(maxPixels));
  return read(0, 0, s_->width, s_->height, std::max(static_cast<int>(longSide), 1));
}

Result<Raster> readWholeRaster(const std::string& input, const SourceOptions& options) {
  auto s = RasterSource::open({input}, options);
  if (!s) return s.error();
  if (static_cast<double>(s->width()) * s->height() * s->channels() > kMaxWholeSamples)
    return makeError(ErrorKind::InvalidInput, concat(input, " has ", s->width(), " x ", s->height(),
                                                     " pixels: too many to hold at once; it must "
                                                     "be read window by window"));
  return s->read(0, 0, s->width(), s->height());
}

}  // namespace vegstream::datasets
