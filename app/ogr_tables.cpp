// Point tables through GDAL/OGR (ogr_tables.h): one GDAL dataset per file, written at a staged
// name beside the target, then all renamed into place together.

#include "app/ogr_tables.h"

#include "core/checked_write.h"

#include <atomic>
#include <fcntl.h>
#include <memory>
#include <mutex>
#include <system_error>
#include <unistd.h>

#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;

constexpr const char* kStdout = "/vsistdout/";

// GDAL's messages while one file is written, collected instead of printed (the handler is the
// calling thread's own); the first failure is kept for the error.
class GdalMessages {
 public:
  GdalMessages() { CPLPushErrorHandlerEx(&collect, this); }
  ~GdalMessages() { CPLPopErrorHandler(); }
  GdalMessages(const GdalMessages&) = delete;
  GdalMessages& operator=(const GdalMessages&) = delete;
  bool failed() const { return failed_; }
  std::string failure(const std::string& otherwise) const { return failed_ ? failure_ : otherwise; }

 private:
  static void CPL_STDCALL collect(CPLErr level, CPLErrorNum, const char* message) {
    auto* self = static_cast<GdalMessages*>(CPLGetErrorHandlerUserData());
    if (level < CE_Failure || self->failed_) return;
    self->failed_ = true;
    self->failure_ = message ? message : "unknown GDAL error";
  }
  bool failed_ = false;
  std::string failure_;
};

struct Driver {
  const char* name;       // GDAL's short name
  const char* extension;  // the staged file's (the CSV driver writes a directory without ".csv")
};
Driver driverOf(TableFormat f) {
  switch (f) {
    case TableFormat::GeoPackage: return {"GPKG", "gpkg"};
    case TableFormat::GeoJson: return {"GeoJSON", "geojson"};
    case TableFormat::Csv: return {"CSV", "csv"};
  }
  return {"", ""};
}

GDALDriver* driverFor(TableFormat f) {
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  return GetGDALDriverManager()->GetDriverByName(driverOf(f).name);
}

Error failure(const std::string& file, const std::string& what) {
  return makeError(ErrorKind::Io, file + ": " + what);
}

CPLStringList layerOptions(TableFormat f, const PointTable& t) {
  CPLStringList o;
  if (f == TableFormat::GeoJson) {
    o.SetNameValue("RFC7946", "YES");
    o.SetNameValue("COORDINATE_PRECISION", "10");
  } else if (f == TableFormat::GeoPackage) {
    o.SetNameValue("GEOMETRY_NAME", "geom");
    o.SetNameValue("FID", "fid");
    if (!t.description.empty()) o.SetNameValue("DESCRIPTION", t.description.c_str());
  } else {
    o.SetNameValue("SEPARATOR", "COMMA");
    o.SetNameValue("STRING_QUOTING", "IF_NEEDED");
    o.SetNameValue("LINEFORMAT", "LF");
  }
  return o;
}

// The layer of table t with its fields (CSV: "lon", "lat" first); nullptr on failure.
OGRLayer* createLayer(GDALDataset& ds, TableFormat f, const PointTable& t) {
  OGRSpatialReference wgs84;
  if (wgs84.importFromEPSG(4326) != OGRERR_NONE) return nullptr;
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = lon, y = lat
  const bool csv = f == TableFormat::Csv;
  OGRLayer* layer =
      ds.CreateLayer(t.name.c_str(), csv ? nullptr : &wgs84, csv ? wkbNone : wkbPoint, layerOptions(f, t).List());
  if (!layer) return nullptr;
  std::vector<std::pair<std::string, OGRFieldType>> fields;
  if (csv) fields = {{"lon", OFTReal}, {"lat", OFTReal}};
  for (const TableColumn& c : t.columns)
    fields.emplace_back(c.name, c.type == TableColumn::Type::Real ? OFTReal : OFTString);
  for (const auto& [name, type] : fields) {
    OGRFieldDefn field(name.c_str(), type);
    if (layer->CreateField(&field) != OGRERR_NONE) return nullptr;
  }
  return layer;
}

Status writeTable(GDALDataset& ds, TableFormat f, const PointTable& t, const std::string& file,
                  const GdalMessages& messages) {
  OGRLayer* layer = createLayer(ds, f, t);
  if (!layer) return failure(file, messages.failure("cannot create layer " + t.name));
  const bool csv = f == TableFormat::Csv, transaction = f == TableFormat::GeoPackage;
  if (transaction && layer->StartTransaction() != OGRERR_NONE)
    return failure(file, messages.failure("cannot start a transaction"));
  OGRFeature feature(layer->GetLayerDefn());
  std::vector<TableValue> values(t.columns.size());
  std::string text;
  const int first = csv ? 2 : 0;  // the columns' first field
  for (size_t i = 0; i < t.rowCount; ++i) {
    double lon = 0.0, lat = 0.0;
    t.row(i, lon, lat, values);
    feature.SetFID(OGRNullFID);
    if (csv) {
      feature.SetField(0, lon);
      feature.SetField(1, lat);
    } else {
      feature.SetGeometryDirectly(new OGRPoint(lon, lat));
    }
    for (size_t c = 0; c < values.size(); ++c) {
      if (const double* v = std::get_if<double>(&values[c])) {
        feature.SetField(first + int(c), *v);
      } else {
        text.assign(std::get<std::string_view>(values[c]));
        feature.SetField(first + int(c), text.c_str());
      }
    }
    if (layer->CreateFeature(&feature) != OGRERR_NONE)
      return failure(file, messages.failure("cannot write feature " + std::to_string(i) + " of " + t.name));
  }
  if (transaction && layer->CommitTransaction() != OGRERR_NONE)
    return failure(file, messages.failure("cannot commit layer " + t.name));
  return {};
}

// One GDAL dataset at gdalPath holding file.tables; errors name file.path.
Status writeDataset(TableFormat f, const std::string& gdalPath, const TableFile& file) {
  const std::string name = file.path.string();
  GdalMessages messages;
  GDALDriver* driver = driverFor(f);
  if (!driver) return failure(name, std::string("GDAL has no ") + driverOf(f).name + " driver");
  struct Close {
    void operator()(GDALDataset* d) const { GDALClose(d); }
  };
  std::unique_ptr<GDALDataset, Close> ds(driver->Create(gdalPath.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) return failure(name, messages.failure("cannot create the file"));
  for (const PointTable* t : file.tables)
    if (Status s = writeTable(*ds, f, *t, name, messages); !s) return s;
  ds.reset();  // flushes and closes: a failure there is reported through the handler
  if (messages.failed()) return failure(name, messages.failure(""));
  return {};
}

// "<name>.tmp-<pid>-<n>.<ext>" beside target.
fs::path stagedName(const fs::path& target, const char* extension) {
  static std::atomic<unsigned> counter{0};
  fs::path name = target.filename();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "." + extension;
  return target.parent_path() / name;
}

// A staged file and what SQLite may leave beside a GeoPackage.
void removeStaged(const fs::path& staged) {
  std::error_code ec;
  for (const char* suffix : {"", "-journal", "-wal", "-shm"}) fs::remove(fs::path(staged.string() + suffix), ec);
}

Status checkShape(TableFormat f, const TableFile& file) {
  if (file.tables.empty()) return makeError(ErrorKind::Internal, file.path.string() + ": no table to write");
  if (f != TableFormat::GeoPackage && file.tables.size() != 1)
    return makeError(ErrorKind::InvalidInput, file.path.string() + ": GeoJSON and CSV hold one table a file");
  if (f == TableFormat::GeoPackage && file.path == kStdout)
    return makeError(ErrorKind::InvalidInput, "a GeoPackage cannot be written to standard output");
  return {};
}

}  // namespace

Status writeTableFiles(TableFormat format, std::span<const TableFile> files) {
  for (const TableFile& file : files)
    if (Status s = checkShape(format, file); !s) return s;
  // Every file at its staged name first; standard output is written as it goes.
  std::vector<fs::path> staged(files.size());
  auto removeAll = [&] {
    for (const fs::path& p : staged)
      if (!p.empty()) removeStaged(p);
  };
  for (size_t i = 0; i < files.size(); ++i) {
    Status s;
    if (files[i].path == kStdout) {
      s = writeDataset(format, kStdout, files[i]);
    } else {
      staged[i] = stagedName(files[i].path, driverOf(format).extension);
      s = writeDataset(format, staged[i].string(), files[i]);
      if (s) s = syncPath(staged[i], files[i].path);
    }
    if (!s) {
      removeAll();
      return s;
    }
  }
  // Then every rename; a failing one takes back those done before it.
  for (size_t i = 0; i < files.size(); ++i) {
    if (staged[i].empty()) continue;
    std::error_code ec;
    fs::rename(staged[i], files[i].path, ec);
    if (!ec) continue;
    const Error e = failure(files[i].path.string(), "cannot move " + staged[i].string() + " into place: " + ec.message());
    for (size_t k = 0; k < i; ++k)
      if (!staged[k].empty()) fs::remove(files[k].path, ec);
    removeAll();
    return e;
  }
  return {};
}

}  // namespace vegstream::app
