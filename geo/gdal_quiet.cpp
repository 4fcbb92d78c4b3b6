// GDAL's error messages kept per thread instead of printed (gdal_quiet.h).

#include "geo/gdal_quiet.h"

#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>

namespace vegstream::geo {
namespace {

struct Kept {
  std::string error, warning;
};
thread_local Kept* kept = nullptr;

void CPL_STDCALL keep(CPLErr level, CPLErrorNum /*num*/, const char* message) {
  if (!kept || !message) return;
  std::string text(message);
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  if (level >= CE_Failure)
    kept->error = text;
  else if (level == CE_Warning)
    kept->warning = text;
}

}  // namespace

void ensureGdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // Never reach for PROJ's CDN grids: the same inputs transform the same on every machine.
    CPLSetConfigOption("PROJ_NETWORK", "OFF");
    // /vsicurl/ (COG by HTTP range requests): retries on 429/5xx with back-off, like the
    // streaming retry policy (streaming/http_retry_policy.h: 3 retries from 0.25 s).
    if (!CPLGetConfigOption("GDAL_HTTP_MAX_RETRY", nullptr)) CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "3");
    if (!CPLGetConfigOption("GDAL_HTTP_RETRY_DELAY", nullptr)) CPLSetConfigOption("GDAL_HTTP_RETRY_DELAY", "0.25");
  });
}

GdalQuiet::GdalQuiet() {
  ensureGdal();
  previous_ = kept;
  kept = new Kept;
  CPLPushErrorHandler(keep);
  CPLErrorReset();
}

GdalQuiet::~GdalQuiet() {
  CPLPopErrorHandler();
  delete kept;
  kept = static_cast<Kept*>(previous_);
}

std::string GdalQuiet::lastError() const { return kept ? kept->error : std::string(); }
std::string GdalQuiet::lastWarning() const { return kept ? kept->warning : std::string(); }

std::string gdalReason(const GdalQuiet& quiet, const std::string& fallback) {
  const std::string e = quiet.lastError();
  return e.empty() ? fallback : "GDAL: " + e;
}

}  // namespace vegstream::geo
