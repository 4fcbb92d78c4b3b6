#include "datasets/tiff_directory.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <fstream>

namespace vegstream::datasets {
namespace {

// GeoTIFF and GDAL tags are tiny (a few hundred bytes); anything far larger is corruption,
// and refusing it keeps a bad count from turning into a huge allocation.
constexpr uint64_t kMaxTagBytes = 1u << 20;
// Real files have a few dozen entries; 4096 bounds the work on a corrupt entry count.
constexpr uint64_t kMaxEntries = 4096;

// Size in bytes of one value of each TIFF field type; 0 for unknown types.
uint64_t typeSize(uint16_t type) {
  switch (type) {
    case 1:
    case 2:
    case 6:
    case 7: return 1;  // BYTE ASCII SBYTE UNDEFINED
    case 3:
    case 8: return 2;  // SHORT SSHORT
    case 4:
    case 9:
    case 11:
    case 13: return 4;  // LONG SLONG FLOAT IFD
    case 5:
    case 10:
    case 12:
    case 16:
    case 17:
    case 18: return 8;  // RATIONAL … IFD8
    default: return 0;
  }
}

class Reader {
 public:
  Reader(const std::filesystem::path& path, std::ifstream& in, uint64_t size) : path_(path), in_(in), size_(size) {}

  void setBigEndian(bool big) { big_ = big; }

  // Reads `n` bytes at `offset` into `out`; false when they lie outside the file.
  bool read(uint64_t offset, void* out, uint64_t n) {
    if (offset > size_ || n > size_ - offset) return false;
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
    return static_cast<bool>(in_);
  }

  // Unsigned integer of `n` bytes (1, 2, 4, 8) from a buffer, in the file's byte order.
  uint64_t uint(const unsigned char* p, int n) const {
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) {
      const int shift = big_ ? 8 * (n - 1 - i) : 8 * i;
      v |= static_cast<uint64_t>(p[i]) << shift;
    }
    return v;
  }

  Error invalid(const std::string& what) const {
    // Built by appending: GCC 12 at -O3 gives a false -Wrestrict on "'" + std::string.
    std::string msg(1, '\'');
    msg += path_.string();
    msg += "' ";
    msg += what;
    return makeError(ErrorKind::InvalidInput, std::move(msg));
  }

 private:
  const std::filesystem::path& path_;
  std::ifstream& in_;
  uint64_t size_;
  bool big_ = false;
};

double toNumber(const Reader& r, uint16_t type, const unsigned char* p) {
  switch (type) {
    case 1:
    case 7: return p[0];
    case 6: return static_cast<int8_t>(p[0]);
    case 3: return static_cast<double>(r.uint(p, 2));
    case 8: return static_cast<int16_t>(r.uint(p, 2));
    case 4:
    case 13: return static_cast<double>(r.uint(p, 4));
    case 9: return static_cast<int32_t>(r.uint(p, 4));
    case 16:
    case 18: return static_cast<double>(r.uint(p, 8));
    case 17: return static_cast<double>(static_cast<int64_t>(r.uint(p, 8)));
    case 11: return std::bit_cast<float>(static_cast<uint32_t>(r.uint(p, 4)));
    case 12: return std::bit_cast<double>(r.uint(p, 8));
    case 5:
    case 10: {
      const bool sign = type == 10;
      const uint64_t n = r.uint(p, 4), d = r.uint(p + 4, 4);
      const double num = sign ? static_cast<int32_t>(n) : static_cast<double>(n);
      const double den = sign ? static_cast<int32_t>(d) : static_cast<double>(d);
      return num / den;
    }
    default: return 0.0;
  }
}

}  // namespace

Result<TiffDirectory> readFirstTiffDirectory(const std::filesystem::path& path, std::span<const uint16_t> wanted) {
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot read '" + path.string() + "': " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorKind::Io, "cannot open '" + path.string() + "' for reading");
  Reader r(path, in, size);

  std::array<unsigned char, 16> header{};
  if (!r.read(0, header.data(), 8)) return r.invalid("is too short to be a TIFF file");
  if (header[0] == 'M' && header[1] == 'M') {
    r.setBigEndian(true);
  } else if (!(header[0] == 'I' && header[1] == 'I')) {
    return r.invalid("is not a TIFF file (no II/MM byte-order mark)");
  }
  const uint64_t magic = r.uint(&header[2], 2);
  const bool bigTiff = magic == 43;
  if (magic != 42 && !bigTiff) return r.invalid("is not a TIFF file (bad magic number)");
  uint64_t ifd = 0;
  if (bigTiff) {
    if (!r.read(0, header.data(), 16)) return r.invalid("is a truncated BigTIFF header");
    ifd = r.uint(&header[8], 8);
  } else {
    ifd = r.uint(&header[4], 4);
  }

  // Entry layout: classic = tag(2) type(2) count(4) value(4); BigTIFF = 2 2 8 8.
  const int countBytes = bigTiff ? 8 : 2;
  const uint64_t entrySize = bigTiff ? 20 : 12;
  const int fieldBytes = bigTiff ? 8 : 4;
  unsigned char buf[8] = {};
  if (!r.read(ifd, buf, static_cast<uint64_t>(countBytes)))
    return r.invalid("has its first image directory past the end of the file");
  const uint64_t entries = r.uint(buf, countBytes);
  if (entries == 0 || entries > kMaxEntries)
    return r.invalid("has a corrupt image directory (" + std::to_string(entries) + " entries)");

  TiffDirectory dir;
  std::vector<unsigned char> value;
  for (uint64_t e = 0; e < entries; ++e) {
    unsigned char entry[20] = {};
    if (!r.read(ifd + static_cast<uint64_t>(countBytes) + e * entrySize, entry, entrySize))
      return r.invalid("has a truncated image directory");
    const auto tag = static_cast<uint16_t>(r.uint(entry, 2));
    if (std::find(wanted.begin(), wanted.end(), tag) == wanted.end()) continue;
    const auto type = static_cast<uint16_t>(r.uint(entry + 2, 2));
    const uint64_t count = r.uint(entry + 4, fieldBytes);
    const uint64_t unit = typeSize(type);
    if (unit == 0 || count > kMaxTagBytes / unit)
      return r.invalid("has a corrupt TIFF tag " + std::to_string(tag) + " (type " + std::to_string(type) + ", count " +
                       std::to_string(count) + ")");
    const uint64_t bytes = unit * count;
    value.assign(bytes, 0);
    const unsigned char* field = entry + 4 + fieldBytes;
    if (bytes <= static_cast<uint64_t>(fieldBytes)) {
      std::memcpy(value.data(), field, bytes);  // small values sit in the entry itself
    } else if (!r.read(r.uint(field, fieldBytes), value.data(), bytes)) {
      return r.invalid("has TIFF tag " + std::to_string(tag) + " pointing past the end of the file");
    }
    TiffTagValue v;
    v.type = type;
    if (type == 2) {
      // TIFF ASCII is 7-bit; corrupt bytes would end up in citations and error messages, so
      // they become '?' (same length: GeoKey offsets into this string still hold).
      v.text.reserve(value.size());
      for (unsigned char c : value) {
        const bool printable = c == 0 || (c >= 0x20 && c < 0x7f);
        v.text.push_back(printable ? static_cast<char>(c) : '?');
      }
    } else {
      v.numbers.reserve(count);
      for (uint64_t i = 0; i < count; ++i) v.numbers.push_back(toNumber(r, type, &value[i * unit]));
    }
    dir.tags[tag] = std::move(v);
  }
  return dir;
}

}  // namespace vegstream::datasets
