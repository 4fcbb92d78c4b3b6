#pragma once
// GDAL / PROJ report problems through CPLError, which prints to stderr by default. The project
// reports every problem itself, as one line naming the file: while a GdalQuiet lives, GDAL's
// messages on this thread are kept instead of printed, and the last error's text is available
// for that line. Also registers GDAL's drivers once (ensureGdal).

#include <string>

namespace vegstream::geo {

// GDALAllRegister once per process; sets the process-wide options the project relies on
// (no PROJ network access, GDAL's HTTP retries as the streaming retry policy's).
void ensureGdal();

class GdalQuiet {
 public:
  GdalQuiet();
  ~GdalQuiet();
  GdalQuiet(const GdalQuiet&) = delete;
  GdalQuiet& operator=(const GdalQuiet&) = delete;

  // The last CE_Failure / CE_Fatal message GDAL raised on this thread since construction
  // ("" when none), one line.
  std::string lastError() const;
  // The last warning, one line ("" when none).
  std::string lastWarning() const;

 private:
  void* previous_ = nullptr;  // an enclosing GdalQuiet's messages
};

// "GDAL: <message>" of the last error, or `fallback` when GDAL said nothing.
std::string gdalReason(const GdalQuiet& quiet, const std::string& fallback);

}  // namespace vegstream::geo
