#pragma once
// The coordinate reference systems vegstream reads. GeoTIFFs and user options name a CRS by
// EPSG code; only the few that real DEM / imagery deliveries use are supported, and anything
// else is refused with a message that names the code (never a silent guess).

#include <functional>
#include <string>
#include <string_view>

#include "core/result.h"

namespace vegstream::geo {

struct Crs {
  enum class Kind {
    Geographic,   // x = longitude, y = latitude, degrees (WGS 84; NAD83 read as WGS 84)
    WebMercator,  // EPSG:3857 metres (spherical formula on the WGS 84 semi-major axis)
    Utm,          // WGS 84 / UTM zone `utmZone`, hemisphere `north`, metres
  };

  Kind kind = Kind::Geographic;
  int epsg = 4326;    // the canonical code (aliases such as 900913 are stored as 3857)
  int utmZone = 0;    // 1 … 60 for Kind::Utm, 0 otherwise
  bool north = true;  // UTM hemisphere: false = false northing of 10 000 km

  // "WGS 84 / UTM zone 12N (EPSG:32612)" — for messages and dataset.json.
  std::string name() const;
  // "EPSG:32612".
  std::string code() const;

  bool operator==(const Crs&) const = default;
};

// Receives one human-readable sentence per thing the caller should know but that is not an
// error (e.g. NAD83 read as WGS 84). Callers usually forward it to their logger.
using WarningSink = std::function<void(const std::string&)>;

// EPSG:4326, 4269 (NAD83, treated as WGS 84 with a warning to `warn`), 3857 (aliases 900913
// and 3785), 32601–32660 and 32701–32760. Anything else: ErrorKind::Unsupported naming the
// code.
Result<Crs> crsFromEpsg(int epsg, const WarningSink& warn = {});

// "EPSG:4326", "epsg:32612" or "4326" (surrounding blanks ignored). Text that is not an EPSG
// code: ErrorKind::InvalidInput naming the text; a code vegstream cannot read: as crsFromEpsg.
Result<Crs> parseCrs(std::string_view text, const WarningSink& warn = {});

// Constructors for code that makes its own data (the synthetic generator, tests).
Crs wgs84Crs();
Crs webMercatorCrs();
Crs utmCrs(int zone, bool north);  // zone in 1 … 60 (asserted)

// The standard UTM zone (1 … 60) of a point, with the Norway / Svalbard exceptions: the zone
// a dataset centred there would naturally be delivered in. Latitude within ±90 (asserted).
int standardUtmZone(double latDeg, double lonDeg);

}  // namespace vegstream::geo
