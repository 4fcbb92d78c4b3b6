// `vegstream generate` (generate_command.h).

#include "app/generate_command.h"

#include "app/exit_codes.h"
#include "datasets/progress.h"

namespace vegstream::app {

int runGenerate(const datasets::SyntheticOptions& options, const Logger& log) {
  datasets::ProgressReporter progress("generate");
  auto meta = datasets::generateSyntheticDataset(options, log, progress);
  if (!meta) return reportError(log, meta.error());
  log->info("{}", progress.finish());
  log->info("dataset '{}' written to {}: zooms {} … {}, heights {:.1f} … {:.1f} m", meta->name, options.out.string(),
            meta->minZoom, meta->maxZoom, meta->minHeightM, meta->maxHeightM);
  return kExitOk;
}

}  // namespace vegstream::app
