#include "core/text_file.h"

#include <fstream>
#include <sstream>

namespace vegstream {

Result<std::string> readTextFile(const std::filesystem::path& file, const std::string& missingHint) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return makeError(ErrorKind::NotFound, file.string() + ": " + missingHint);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(ErrorKind::Io, file.string() + ": could not read the file");
  return text.str();
}

}  // namespace vegstream
