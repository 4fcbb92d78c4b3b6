// The name of a GPU pass's column (frame_columns.h).

#include "flight/frame_columns.h"

namespace vegstream::flight::column {

std::string gpuPassColumn(const std::string& pass) {
  std::string out = "gpu_";
  for (char ch : pass) {
    const char c = (ch >= 'A' && ch <= 'Z') ? static_cast<char>(ch - 'A' + 'a') : ch;
    out += ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) ? c : '_';
  }
  return out + "_ms";
}

}  // namespace vegstream::flight::column
