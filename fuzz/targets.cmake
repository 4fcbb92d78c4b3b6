# The fuzz targets' sources and what they link (fuzz/targets.h), shared by the libFuzzer build
# (fuzz/CMakeLists.txt, clang, VEGSTREAM_FUZZ) and the GCC regression test (tests/fuzz,
# fuzz_regressions).
find_package(CURL REQUIRED)  # the HTTP policy's headers name libcurl's types
set(VEGSTREAM_FUZZ_DIR ${PROJECT_SOURCE_DIR}/fuzz)
set(VEGSTREAM_FUZZ_TARGET_SOURCES
  ${VEGSTREAM_FUZZ_DIR}/targets/support.cpp
  ${VEGSTREAM_FUZZ_DIR}/targets/json_readers.cpp
  ${VEGSTREAM_FUZZ_DIR}/targets/tile_decoders.cpp
  ${VEGSTREAM_FUZZ_DIR}/targets/raster_source.cpp
  ${VEGSTREAM_FUZZ_DIR}/targets/http_response.cpp
  ${VEGSTREAM_FUZZ_DIR}/targets/tile_contract.cpp)
set(VEGSTREAM_FUZZ_TARGET_DEPS
  vegstream_streaming vegstream_datasets vegstream_flight vegstream_vegetation vegstream_geo vegstream_core
  GDAL::GDAL CURL::libcurl)
# target:function, as in fuzz/targets.h kTargets.
set(VEGSTREAM_FUZZ_TARGETS
  dataset_json:datasetJson flight_path:flightPath species_catalog:speciesCatalog recording_json:recordingJson
  summary_json:summaryJson elevation_tile:elevationTile imagery_tile:imageryTile raster_source:rasterSource
  http_response:httpResponse tile_contract:tileContract)
