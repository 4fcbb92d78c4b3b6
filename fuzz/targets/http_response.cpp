// The HTTP tile source's handling of one response (streaming/http_tile_source.cpp endAttempt):
// how the attempt ended (datasets/http_retry_policy.h judgeAttempt, describeAttempt; the
// Content-Type test of datasets/http_limits.h), a 3xx's Location (redirectTarget), and — for a
// 2xx the policy accepts — the tile check of the body (streaming/tile_check.h) that decides
// whether it is cached. Input layout:
//   byte 0   Content-Type: one of kContentTypes, or (≥ 0xe0) the next (byte & 31) bytes as is
//   byte 1   HTTP status (kStatuses), and in its top bits the transfer's CURLcode
//   byte 2   the requested path (kPaths), the elevation encoding, whether Content-Length is
//            announced (and right), whether a tile was asked for, whether the body passed the cap
//   rest     the body (also a 3xx's Location, as text)
// The dataset's tile size is the one the body's image header states (so a seed decodes in full),
// 256 when none.

#include <iterator>
#include <string>

#include "datasets/dataset_format.h"
#include "datasets/http_limits.h"
#include "datasets/http_retry_policy.h"
#include "datasets/tile_codec.h"
#include "fuzz/targets.h"
#include "streaming/tile_check.h"

namespace vegstream::fuzz {
namespace {

constexpr const char* kContentTypes[] = {
    "",          "image/png", "image/jpeg", "image/webp", "application/octet-stream", "text/html; charset=utf-8",
    "text/plain", "application/json", "application/problem+json", "application/xml", "image/svg+xml",
    "IMAGE/PNG", "Text/HTML", ";", "application/x-protobuf", "image/png; charset=binary"};
constexpr long kStatuses[] = {200, 200, 200, 206, 204, 301, 302, 303, 307, 308, 304, 400, 403, 404, 408, 410,
                              429, 500, 502, 503, 0,   99,  199, 600, 999, 201, 203, 226, 300, 305, 418, 511};
constexpr CURLcode kCodes[] = {CURLE_OK, CURLE_PARTIAL_FILE, CURLE_OPERATION_TIMEDOUT, CURLE_WRITE_ERROR,
                               CURLE_COULDNT_CONNECT, CURLE_FILESIZE_EXCEEDED, CURLE_RECV_ERROR, CURLE_OK};
constexpr const char* kPaths[] = {"elevation/12/758/1608.png", "imagery/12/758/1608.jpg", "imagery/12/758/1608.png",
                                  "ndvi/12/758/1608.png",      "landcover/12/758/1608.png", "canopy/12/758/1608.png",
                                  "dataset.json",              "elevation/12/758/1608"};

}  // namespace

int httpResponse(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  size_t at = 3;
  std::string contentType;
  if (data[0] >= 0xe0) {
    const size_t n = std::min<size_t>(data[0] & 31u, size - at);
    contentType = asText(data + at, n);
    at += n;
  } else {
    contentType = kContentTypes[data[0] % std::size(kContentTypes)];
  }
  const auto body = asBytes(data + at, size - at);

  datasets::AttemptEnd end;
  end.httpStatus = kStatuses[data[1] % std::size(kStatuses)];
  end.code = kCodes[data[1] >> 5];
  end.contentType = contentType;
  end.bodyBytes = body.size();
  end.bodyCap = 16ull << 20;
  const int lengthMode = (data[2] >> 4) & 3;  // announced right, not announced, short, long
  end.contentLength = lengthMode == 0   ? static_cast<int64_t>(body.size())
                      : lengthMode == 1 ? -1
                      : lengthMode == 2 ? static_cast<int64_t>(body.size() / 2)
                                        : static_cast<int64_t>(body.size()) + 17;
  end.binaryExpected = (data[2] & 0x40) == 0;
  end.bodyExceeded = (data[2] & 0x80) != 0 && lengthMode == 3;

  const bool textual = datasets::textualContentType(contentType);
  const datasets::AttemptVerdict verdict = datasets::judgeAttempt(end);
  const std::string line = datasets::describeAttempt(end, "");
  VEGSTREAM_FUZZ_CHECK(!line.empty());
  if (verdict == datasets::AttemptVerdict::Ok) {
    // What the policy accepts: a whole 2xx body, never a document where a tile was asked for.
    VEGSTREAM_FUZZ_CHECK(end.httpStatus >= 200 && end.httpStatus < 300);
    VEGSTREAM_FUZZ_CHECK(!(end.binaryExpected && textual));
    VEGSTREAM_FUZZ_CHECK(!end.bodyExceeded);
  }

  if (datasets::isRedirectStatus(end.httpStatus)) {
    const auto target = datasets::redirectTarget("https://tiles.example.org:8443/zion/elevation/12/758/1608.png",
                                                 asText(body.data(), std::min<size_t>(body.size(), 4096)),
                                                 (data[2] & 0x08) != 0);
    checkResult(target);
    if (target) {
      // Followed only to http(s): the scheme, in any case (the URL libcurl resolved is absolute).
      std::string scheme = target->substr(0, target->find(':'));
      for (char& c : scheme) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
      VEGSTREAM_FUZZ_CHECK(scheme == "http" || scheme == "https");
    }
  }

  if (verdict == datasets::AttemptVerdict::Ok && end.binaryExpected) {
    datasets::DatasetMeta meta;
    const int side = statedSide(body);
    meta.tileSize = side > 0 && side <= datasets::kMaxTileSide ? side : datasets::kTileSize;
    meta.elevationEncoding =
        (data[2] & 0x08) != 0 ? datasets::ElevationEncoding::TerrainRgb : datasets::ElevationEncoding::Terrarium;
    const streaming::TileCheck check = streaming::tileCheckFor(meta, "https://tiles.example.org/zion");
    const Status s = check(kPaths[data[2] & 7], body);
    checkResult(s);
  }
  return 0;
}

}  // namespace vegstream::fuzz
