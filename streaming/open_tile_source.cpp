// openTileSource / readMetaFrom (open_tile_source.h).

#include "streaming/open_tile_source.h"

#include <algorithm>
#include <cctype>

#include "streaming/local_tile_source.h"

namespace vegstream::streaming {
namespace fs = std::filesystem;

bool isHttpLocation(const std::string& location) {
  std::string head = location.substr(0, 8);
  std::transform(head.begin(), head.end(), head.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return head.rfind("http://", 0) == 0 || head.rfind("https://", 0) == 0;
}

Result<std::shared_ptr<TileSource>> openTileSource(const std::string& location, const OpenSourceOptions& options) {
  if (isHttpLocation(location)) {
    HttpSourceOptions http = options.http;
    http.baseUrl = location;
    if (!http.log) http.log = options.log;
    if (!http.tasks) http.tasks = options.tasks;
    auto source = HttpTileSource::create(std::move(http));
    if (!source) return source.error();
    return std::shared_ptr<TileSource>(std::move(*source));
  }
  std::error_code ec;
  const fs::path dir(location);
  if (!fs::exists(dir, ec)) return makeError(ErrorKind::NotFound, "'" + location + "' does not exist");
  if (!fs::is_directory(dir, ec))
    return makeError(ErrorKind::NotFound, "'" + location + "' is not a dataset directory (nor an http(s) URL)");
  return std::shared_ptr<TileSource>(std::make_shared<LocalTileSource>(dir, options.localIoThreads, options.tasks));
}

Result<datasets::DatasetMeta> readMetaFrom(TileSource& source) {
  auto text = source.readText("dataset.json");
  if (!text) {
    if (text.error().kind == ErrorKind::NotFound)
      return makeError(ErrorKind::NotFound, source.describe() + " is not a vegstream dataset: " + text.error().message);
    return text.error();
  }
  auto meta = datasets::parseDatasetMeta(*text, datasetJsonName(source));
  if (!meta) return meta.error();
  // The streamer's GPU slots, the snapshot's mosaic and the canopy layer are laid out for
  // kTileSize: a dataset of other tiles is refused here, in one line, not over-read later.
  if (meta->tileSize != datasets::kTileSize)
    return makeError(ErrorKind::InvalidInput, "'" + datasetJsonName(source) + "': field 'tile_size' is " +
                                                  std::to_string(meta->tileSize) + "; vegstream streams tiles of " +
                                                  std::to_string(datasets::kTileSize) + " pixels only");
  return meta;
}

std::string datasetJsonName(const TileSource& source) {
  std::string name = source.describe();
  if (name.rfind("dir ", 0) == 0) return (fs::path(name.substr(4)) / "dataset.json").string();
  if (name.empty() || name.back() != '/') name += '/';
  return name + "dataset.json";
}

}  // namespace vegstream::streaming
