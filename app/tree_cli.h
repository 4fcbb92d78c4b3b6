#pragma once
// The tree options that `fly`, `record` and `snapshot` share (issue 20): --trees on|off,
// --tree-shadows on|off, --tree-cores on|off, --tree-horizon-m, --tree-detail, --tree-near-fade-m,
// --tree-budget-mb, --impostor-cache. One definition, so the commands spell and check them alike.

#include <filesystem>
#include <optional>
#include <string>

#include "core/result.h"
#include "scene/scene.h"

namespace CLI {
class App;
}

namespace vegstream::app {

struct TreeCli {
  std::string trees = "on";         // --trees on|off
  std::string shadows = "on";       // --tree-shadows on|off
  std::string cores = "on";         // --tree-cores on|off
  std::optional<double> horizonM;   // --tree-horizon-m M (default: the catalog's tree horizon)
  std::optional<double> detail;     // --tree-detail F, 0.25 … 8: the level-of-detail distances × F
  std::optional<double> nearFadeM;  // --tree-near-fade-m M, 0 … 50 (0: off; default render::TreeLodDistances)
  std::optional<double> budgetMb;   // --tree-budget-mb MB, > 0 (default render::RendererOptions)
  std::optional<std::string> impostorCache;  // --impostor-cache DIR|off (default defaultImpostorCacheDir())
};

// Where the impostors are kept when --impostor-cache is not given: $XDG_CACHE_HOME/vegstream/impostors
// (an absolute XDG_CACHE_HOME only, as the XDG spec says), else $HOME/.cache/vegstream/impostors;
// none when neither is set.
std::optional<std::filesystem::path> defaultImpostorCacheDir();

void addTreeOptions(CLI::App& cmd, TreeCli& out);

// Checks the values against each other and the catalog: InvalidInput, one message naming the
// option ("--tree-horizon-m 100: shorter than the plants' horizon (150 m)").
Status checkTreeOptions(const TreeCli& cli, const vegetation::SpeciesCatalog& catalog);

// Sets the scene's tree options (checked values).
void applyTreeOptions(const TreeCli& cli, scene::SceneOptions& so);

}  // namespace vegstream::app
