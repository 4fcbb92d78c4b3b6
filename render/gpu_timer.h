#pragma once
// Timestamp and pipeline-statistics queries for one frame slot. Usage per frame:
// begin(cmd) · beginPass/endPass … · end(cmd) · (after the slot's fence) read().

#include <string>
#include <vector>

#include "render/context.h"
#include "render/gpu_timing.h"

namespace vegstream::render {

class GpuTimer {
 public:
  GpuTimer(const Context& ctx, int maxPasses, const std::string& name);

  void begin(VkCommandBuffer cmd);
  void beginPass(VkCommandBuffer cmd, const std::string& pass);
  void endPass(VkCommandBuffer cmd);
  void end(VkCommandBuffer cmd);
  // Results of the last recorded frame; call only after its submission has completed.
  GpuTimings read() const;

 private:
  const Context* ctx_;
  QueryPool timestamps_;
  QueryPool statistics_;
  VkQueryPipelineStatisticFlags statisticFlags_ = 0;
  uint32_t maxQueries_;
  uint32_t used_ = 0;
  std::vector<std::string> passNames_;
  bool recorded_ = false;
};

}  // namespace vegstream::render
