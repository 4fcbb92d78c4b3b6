#include "app/tree_cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <CLI/CLI.hpp>

#include "core/number_text.h"

namespace vegstream::app {
namespace {

constexpr double kMaxTreeHorizonM = 20000.0;  // as a species' horizon_m
constexpr double kMaxTreeBudgetMb = 1e6;
constexpr double kMinTreeDetail = 0.25, kMaxTreeDetail = 8.0;
constexpr double kMaxNearFadeM = 50.0;

}  // namespace

std::optional<std::filesystem::path> defaultImpostorCacheDir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg == '/') return std::filesystem::path(xdg) / "vegstream" / "impostors";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::filesystem::path(home) / ".cache" / "vegstream" / "impostors";
  return std::nullopt;
}

void addTreeOptions(CLI::App& cmd, TreeCli& out) {
  cmd.add_option("--trees", out.trees, "Draw the catalog's trees: on or off (default on)");
  cmd.add_option("--tree-shadows", out.shadows,
                 "The trees cast sun shadows (a cascaded shadow map) on the terrain, the grass and each other: on "
                 "or off (default on)");
  cmd.add_option("--tree-cores", out.cores,
                 "The crowns' opaque cores (foliage in shade inside each crown, drawn first so the cards behind "
                 "are never shaded): on or off, to compare (default on)");
  cmd.add_option("--tree-horizon-m", out.horizonM,
                 "How far trees are drawn, metres, at least the plants' horizon (default: the catalog's tree "
                 "horizon, 3000 in the default catalog)");
  cmd.add_option("--tree-detail", out.detail,
                 "Scales the trees' level-of-detail distances, 0.25 to 8: where full models give way to reduced "
                 "ones, those to impostors, and impostors end by size. 1 (default) sizes them by the view's pixels; "
                 "2 draws every level twice as far (finer trees, slower frames)");
  cmd.add_option("--tree-near-fade-m", out.nearFadeM,
                 "Trees dissolve within this many metres of the camera and are gone within half of it, so a flight "
                 "through a crown sees past the branches at the lens (slower frames there: the crowns' cores go "
                 "too); 0 to 50, 0 off (default " +
                     numberText(render::TreeLodDistances{}.nearFadeM) + ")");
  cmd.add_option("--tree-budget-mb", out.budgetMb,
                 "GPU memory for the trees (models, impostors, instances), MiB; when it binds the farthest trees "
                 "fall back to the terrain's colour (default " +
                     numberText(static_cast<double>(render::RendererOptions{}.treeBudgetBytes >> 20)) + ")");
  cmd.add_option("--impostor-cache", out.impostorCache,
                 "Where the trees' impostors (their models seen from 64 directions, drawn at start-up) are kept "
                 "between runs, keyed by the models, shaders and driver, at most 1 GiB: a directory, or off to "
                 "draw them at every start (default $XDG_CACHE_HOME/vegstream/impostors, else "
                 "~/.cache/vegstream/impostors)");
}

Status checkTreeOptions(const TreeCli& o, const vegetation::SpeciesCatalog& catalog) {
  auto bad = [](const std::string& m) { return makeError(ErrorKind::InvalidInput, m); };
  if (o.trees != "on" && o.trees != "off") return bad("--trees " + o.trees + ": must be on or off");
  if (o.shadows != "on" && o.shadows != "off") return bad("--tree-shadows " + o.shadows + ": must be on or off");
  if (o.cores != "on" && o.cores != "off") return bad("--tree-cores " + o.cores + ": must be on or off");
  if (o.horizonM) {
    const double plants = vegetation::farthestHorizon(catalog);
    if (!(std::isfinite(*o.horizonM) && *o.horizonM <= kMaxTreeHorizonM))
      return bad("--tree-horizon-m " + numberText(*o.horizonM) + ": must be a distance in metres, at most 20000");
    if (*o.horizonM < plants)
      return bad("--tree-horizon-m " + numberText(*o.horizonM) + ": shorter than the plants' horizon (" +
                 numberText(plants) + " m)");
  }
  if (o.detail && !(*o.detail >= kMinTreeDetail && *o.detail <= kMaxTreeDetail))
    return bad("--tree-detail " + numberText(*o.detail) + ": must be from 0.25 to 8");
  if (o.nearFadeM && !(*o.nearFadeM >= 0.0 && *o.nearFadeM <= kMaxNearFadeM))
    return bad("--tree-near-fade-m " + numberText(*o.nearFadeM) + ": must be a distance in metres from 0 to 50");
  if (o.budgetMb && !(*o.budgetMb > 0.0 && *o.budgetMb <= kMaxTreeBudgetMb))
    return bad("--tree-budget-mb " + numberText(*o.budgetMb) + ": must be more than 0 and at most 1000000 MiB");
  if (o.impostorCache) {
    if (o.impostorCache->empty()) return bad("--impostor-cache: must be a directory or off");
    std::error_code ec;
    if (*o.impostorCache != "off" && std::filesystem::exists(*o.impostorCache, ec) &&
        !std::filesystem::is_directory(*o.impostorCache, ec))
      return bad("--impostor-cache " + *o.impostorCache + ": not a directory");
  }
  return {};
}

void applyTreeOptions(const TreeCli& o, scene::SceneOptions& so) {
  so.trees.enabled = o.trees == "on";
  so.trees.shadows = o.shadows == "on";
  so.trees.cores = o.cores == "on";
  if (o.horizonM) so.trees.horizonM = *o.horizonM;
  if (o.detail) {
    const auto f = static_cast<float>(*o.detail);
    so.trees.lod.fullHeights *= f;
    so.trees.lod.reducedHeights *= f;
    so.trees.lod.impostorEndHeights *= f;
  }
  if (o.nearFadeM) so.trees.lod.nearFadeM = static_cast<float>(*o.nearFadeM);
  if (o.budgetMb) so.renderer.treeBudgetBytes = static_cast<uint64_t>(*o.budgetMb * 1024.0 * 1024.0);
  if (!o.impostorCache)
    so.trees.impostorCacheDir = defaultImpostorCacheDir();
  else if (*o.impostorCache != "off")
    so.trees.impostorCacheDir = std::filesystem::path(*o.impostorCache);
}

}  // namespace vegstream::app
