// Tile address templates (tile_template.h). TMS rows: OSGeo, "Tile Map Service Specification"
// (https://wiki.osgeo.org/wiki/Tile_Map_Service_Specification): row 0 is the southernmost.

#include "datasets/tile_template.h"

#include <algorithm>
#include <cctype>
#include <cstdint>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

Error badTemplate(const std::string& tmpl, const std::string& problem) {
  return makeError(ErrorKind::InvalidInput, concat("tile template '", tmpl, "' ", problem));
}

size_t occurrences(const std::string& text, const std::string& key) {
  size_t n = 0;
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + key.size())) ++n;
  return n;
}

}  // namespace

bool looksLikeHttpUrl(const std::string& text) {
  std::string head = text.substr(0, 8);
  std::transform(head.begin(), head.end(), head.begin(), [](unsigned char c) { return std::tolower(c); });
  return head.rfind("http://", 0) == 0 || head.rfind("https://", 0) == 0;
}

int flipTileRow(int row, int z) { return static_cast<int>((int64_t{1} << z) - 1 - row); }

Result<TileTemplate> parseTileTemplate(const std::string& text) {
  TileTemplate t;
  t.text = text;
  t.isUrl = looksLikeHttpUrl(text);
  const size_t ys = occurrences(text, "{y}"), tmsYs = occurrences(text, "{-y}");
  for (const char* key : {"{z}", "{x}"}) {
    const size_t n = occurrences(text, key);
    if (n == 0) return badTemplate(text, concat("has no ", key, "; expected e.g. DIR/{z}/{x}/{y}.png"));
    if (n > 1) return badTemplate(text, concat("has ", key, " twice"));
  }
  if (ys + tmsYs == 0) return badTemplate(text, "has no {y} (XYZ rows) or {-y} (TMS rows)");
  if (ys + tmsYs > 1) return badTemplate(text, "has more than one of {y} and {-y}");
  t.tmsRows = tmsYs == 1;
  // Any other placeholder is refused: it would reach the server or the disk as literal text.
  for (size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open + 1)) {
    const size_t close = text.find('}', open);
    const std::string key = close == std::string::npos ? text.substr(open) : text.substr(open, close - open + 1);
    if (key != "{z}" && key != "{x}" && key != "{y}" && key != "{-y}")
      return badTemplate(text, concat("has the placeholder '", key, "'; only {z}, {x}, {y} and {-y} are known"));
  }
  return t;
}

std::string expandTileTemplate(const TileTemplate& tmpl, const geo::TileId& id) {
  std::string out;
  out.reserve(tmpl.text.size() + 16);
  const std::string& s = tmpl.text;
  for (size_t i = 0; i < s.size();) {
    if (s.compare(i, 3, "{z}") == 0) {
      out += std::to_string(id.z), i += 3;
    } else if (s.compare(i, 3, "{x}") == 0) {
      out += std::to_string(id.x), i += 3;
    } else if (s.compare(i, 3, "{y}") == 0) {
      out += std::to_string(id.y), i += 3;
    } else if (s.compare(i, 4, "{-y}") == 0) {
      out += std::to_string(flipTileRow(id.y, id.z)), i += 4;
    } else {
      out += s[i++];
    }
  }
  return out;
}

}  // namespace vegstream::datasets
