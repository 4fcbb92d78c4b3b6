// The GDAL raster source (datasets/raster_source.h), which `vegstream import` runs on user files:
// the bytes become a /vsimem/ file (no disk), opened through RasterSource::open as the importer
// opens a path, then read as the importer reads — a window at the top left (at most 64 × 64), a
// decimated window over the whole raster (at most 32 pixels a side), and an overview of at most
// 4096 pixels (checked, up to rounding) — so a header that claims billions of pixels costs
// nothing. The input's length parity turns the heights option (scale/offset, feet) on. GDAL
// itself is not instrumented: libFuzzer is guided by the project's code around it, the
// sanitizers see GDAL's heap only.

#include <algorithm>
#include <string>

#include <cpl_vsi.h>
#include <unistd.h>

#include "datasets/raster_source.h"
#include "fuzz/targets.h"

namespace vegstream::fuzz {
namespace {

void checkRaster(const Result<datasets::Raster>& r) {
  checkResult(r);
  if (!r) return;
  VEGSTREAM_FUZZ_CHECK(r->width > 0 && r->height > 0 && r->channels > 0);
  VEGSTREAM_FUZZ_CHECK(r->samples.size() ==
                       static_cast<size_t>(r->width) * static_cast<size_t>(r->height) * static_cast<size_t>(r->channels));
}

}  // namespace

int rasterSource(const uint8_t* data, size_t size) {
  static const std::string path = "/vsimem/vegstream-fuzz/" + std::to_string(::getpid()) + "/input.tif";
  // GDAL only reads the buffer (bTakeOwnership false): the input stays libFuzzer's.
  static GByte empty[1] = {0};  // an empty input still names a buffer
  VSILFILE* f = VSIFileFromMemBuffer(path.c_str(), size == 0 ? empty : const_cast<GByte*>(data),
                                     static_cast<vsi_l_offset>(size), FALSE);
  VEGSTREAM_FUZZ_CHECK(f != nullptr);
  VSIFCloseL(f);
  {
    datasets::SourceOptions options;
    options.heights = size % 2 == 1;
    auto src = datasets::RasterSource::open({path}, options);
    checkResult(src);
    if (src) {
      VEGSTREAM_FUZZ_CHECK(src->width() > 0 && src->height() > 0 && src->channels() > 0);
      (void)src->description();
      checkRaster(src->read(0, 0, std::min(src->width(), 64), std::min(src->height(), 64)));
      checkRaster(src->read(0, 0, src->width(), src->height(), 32));
      const auto overview = src->readOverview(4096);
      checkRaster(overview);
      // readOverview's bound: 4 096 pixels, but for each side's rounding up (< 2 × 4 096 + 2).
      if (overview)
        VEGSTREAM_FUZZ_CHECK(static_cast<size_t>(overview->width) * static_cast<size_t>(overview->height) <=
                             2 * 4096 + 2);
    }
  }
  VSIUnlink(path.c_str());
  return 0;
}

}  // namespace vegstream::fuzz
