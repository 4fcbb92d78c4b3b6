// readTextFile (text_file.h): the checked opener's bytes as text.

#include "core/text_file.h"

namespace vegstream {

Result<std::string> readTextFile(const std::filesystem::path& file, const std::string& missingHint,
                                 const FileCeiling& ceiling) {
  return readRegularFile(file, ceiling, missingHint);
}

}  // namespace vegstream
