// Where the trees' impostors are kept (app/tree_cli.h): $XDG_CACHE_HOME when it is absolute,
// else ~/.cache, else nowhere; --impostor-cache DIR and off override it.
#include <cstdlib>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "app/tree_cli.h"

namespace vegstream::app {
namespace {

// Sets (or, with nullptr, unsets) an environment variable for the test's scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(TreeCli, TheImpostorCacheFollowsXdgThenHome) {
  {
    ScopedEnv xdg("XDG_CACHE_HOME", "/var/cache/me"), home("HOME", "/home/me");
    EXPECT_EQ(defaultImpostorCacheDir(), std::filesystem::path("/var/cache/me/vegstream/impostors"));
  }
  {  // a relative XDG_CACHE_HOME is ignored, as the XDG spec says
    ScopedEnv xdg("XDG_CACHE_HOME", "rel/cache"), home("HOME", "/home/me");
    EXPECT_EQ(defaultImpostorCacheDir(), std::filesystem::path("/home/me/.cache/vegstream/impostors"));
  }
  {
    ScopedEnv xdg("XDG_CACHE_HOME", nullptr), home("HOME", nullptr);
    EXPECT_EQ(defaultImpostorCacheDir(), std::nullopt);
  }
}

TEST(TreeCli, ImpostorCacheOptionOverridesTheDefault) {
  ScopedEnv xdg("XDG_CACHE_HOME", "/var/cache/me");
  scene::SceneOptions so;
  TreeCli cli;
  applyTreeOptions(cli, so);
  EXPECT_EQ(so.trees.impostorCacheDir, std::filesystem::path("/var/cache/me/vegstream/impostors"));
  cli.impostorCache = "off";
  scene::SceneOptions off;
  applyTreeOptions(cli, off);
  EXPECT_EQ(off.trees.impostorCacheDir, std::nullopt);
  cli.impostorCache = "/tmp/atlases";
  scene::SceneOptions dir;
  applyTreeOptions(cli, dir);
  EXPECT_EQ(dir.trees.impostorCacheDir, std::filesystem::path("/tmp/atlases"));
}

}  // namespace
}  // namespace vegstream::app
