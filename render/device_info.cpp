#include "render/device_info.h"

#include <algorithm>

namespace vegstream::render {

bool DeviceInfo::supportsDeferredTerrain(int samples) const {
  return std::find(storageMsaaCounts.begin(), storageMsaaCounts.end(), samples) != storageMsaaCounts.end();
}

bool DeviceInfo::supportsComputeTerrain(int samples) const {
  return supportsDeferredTerrain(samples) && (samples == 1 || sampleRateShading);
}

bool DeviceInfo::supportsMsaa(int samples) const {
  return std::find(msaaCounts.begin(), msaaCounts.end(), samples) != msaaCounts.end();
}

std::string DeviceInfo::msaaList() const {
  std::string out;
  for (int s : msaaCounts) out += (out.empty() ? "" : ", ") + std::to_string(s);
  return out;
}

}  // namespace vegstream::render
