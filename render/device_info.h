#pragma once
// What the program tells the user (and records) about the GPU it draws with. Plain data, so
// callers outside render/ never see a Vulkan type.

#include <string>
#include <vector>

namespace vegstream::render {

struct DeviceInfo {
  int index = -1;               // position in the driver's enumeration
  std::string name;             // VkPhysicalDeviceProperties::deviceName
  std::string type;             // "discrete", "integrated", "virtual", "cpu", "other"
  std::string driver;           // driver name and info, e.g. "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)"
  std::string apiVersion;       // "1.3.230"
  std::vector<int> msaaCounts;  // sample counts usable for colour+depth targets, e.g. {1, 4}
  bool software = false;        // a CPU rasteriser (lavapipe): per-pass GPU times mean nothing
  // Sample counts at which compute may store into the colour target (storage images; above 1
  // only with shaderStorageImageMultisample): where deferred terrain shading can run.
  std::vector<int> storageMsaaCounts;
  bool sampleRateShading = false;  // fragment stages run per sample when asked (the compute terrain's depth pass)
  // Many draws in one indirect call, each with its own first instance (the terrain's draw list;
  // without: one indirect call per draw).
  bool multiDrawIndirect = false;
  uint64_t deviceLocalBytes = 0;  // the largest device-local memory heap

  bool supportsMsaa(int samples) const;
  std::string msaaList() const;  // "1, 4"
  bool supportsDeferredTerrain(int samples) const;
  // The terrain rasterised in compute: the deferred shade's storage, and above one sample a
  // fragment stage run per sample (its depth samples written into the depth attachment).
  bool supportsComputeTerrain(int samples) const;
};

}  // namespace vegstream::render
