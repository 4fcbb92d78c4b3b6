#pragma once
// Where tests write, so that ctest can run them in parallel (issue 16).
//
// ctest runs every test in its own process (gtest_discover_tests), two or more at a time, and a
// suite's SetUpTestSuite runs again in each of them. So:
// - testOutputDir(): VEGSTREAM_TEST_TMP/<program>/<Suite>.<Test>, emptied for the running test.
// - cachedFixture(name, key, make): an expensive input (an imported dataset) made once and then
//   shared, read-only, by every process: VEGSTREAM_TEST_TMP/fixtures/<name>.<key>. The key
//   names the build that made it (programKey(): a hash of the test program, which holds the
//   making code and its arguments, the vegstream libraries being static; vegstreamKey(): that
//   and a hash of the vegstream executable, for what the command line makes), so a rebuilt
//   importer, or changed arguments, never meet a dataset an older build made.
// A suite's SetUpTestSuite runs in every test process, and GoogleTest skips the tests of a suite
// whose SetUpTestSuite failed: fixtures are asked for in SetUp, where a failure fails the test.

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/result.h"

namespace vegstream::testing {

// A name safe as one path component ("Cases/FlyBadInput.x/0" → "Cases_FlyBadInput.x_0").
inline std::string pathComponent(std::string s) {
  for (char& c : s)
    if (c == '/' || c == '\\' || c == ' ') c = '_';
  return s;
}

// VEGSTREAM_TEST_TMP/<program>: programs of one folder share VEGSTREAM_TEST_TMP and may repeat
// a suite name.
inline std::filesystem::path programTmp() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return std::filesystem::path(VEGSTREAM_TEST_TMP) / (ec ? std::string("tests") : self.filename().string());
}

// The running test's own directory: emptied by the first call in a test, the same directory
// after. Only inside a test (its body, SetUp, TearDown).
inline std::filesystem::path testOutputDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (info == nullptr) {
    ADD_FAILURE() << "testOutputDir() outside a test (in SetUpTestSuite, every test process runs it)";
    return programTmp() / "no-test";
  }
  const std::filesystem::path dir =
      programTmp() / pathComponent(std::string(info->test_suite_name()) + "." + info->name());
  static const ::testing::TestInfo* emptiedFor = nullptr;  // tests run one after the other
  if (emptiedFor != info) {
    std::filesystem::remove_all(dir);
    emptiedFor = info;
  }
  std::filesystem::create_directories(dir);
  return dir;
}

// 64-bit FNV-1a of a file's bytes, in hex; "missing" when it cannot be read (a key that still
// differs from every real one).
inline std::string fileKey(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "missing";
  uint64_t h = 1469598103934665603ull;
  char buf[1 << 16];
  while (in.read(buf, sizeof(buf)) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) h = (h ^ static_cast<unsigned char>(buf[i])) * 1099511628211ull;
    if (!in) break;
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

// Key of fixtures made by this test program's own code (the vegstream libraries are static, so
// the program holds the importer that made them): "<program>-<hash>".
inline const std::string& programKey() {
  static const std::string key = programTmp().filename().string() + "-" + fileKey("/proc/self/exe");
  return key;
}

// Key of fixtures made by running the vegstream executable with arguments this program chose:
// "<program>-<hash of the program><hash of vegstream>" (a changed argument is a changed program).
inline const std::string& vegstreamKey() {
  static const std::string key = programKey() + fileKey(VEGSTREAM_EXE);
  return key;
}

// Key of fixtures made by the vegstream executable alone, from the command-line `arguments`:
// "vegstream-<hash of vegstream><hash of the arguments>". The test program does not enter it, so
// every program of a folder (they share VEGSTREAM_TEST_TMP) uses the one made first.
inline std::string executableKey(const std::string& arguments) {
  uint64_t h = 1469598103934665603ull;
  for (const char c : arguments) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
  return "vegstream-" + fileKey(VEGSTREAM_EXE) + hex;
}

// The fixture `name` of build `key` ("<maker>-<hash>"), made by `make(dir)` (which creates dir;
// its parent exists) when no process made it before. One maker at a time (flock: the other
// processes wait for it instead of making it again), into a staging directory renamed into
// place when complete, so a crashed maker never leaves a half-made fixture where a complete one
// is looked for. Making one removes those an older build of the same maker made (a build tree
// holds one build of each program). Tests must not change a fixture: copy it first.
inline Result<std::filesystem::path> cachedFixture(const std::string& name, const std::string& key,
                                                   const std::function<Status(const std::filesystem::path&)>& make) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(VEGSTREAM_TEST_TMP) / "fixtures";
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) return makeError(ErrorKind::Io, "cannot create " + root.string() + ": " + ec.message());
  const std::string id = pathComponent(name) + "." + key;
  const fs::path final = root / id;
  const fs::path lockPath = root / (id + ".lock");
  const int lock = ::open(lockPath.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock < 0) return makeError(ErrorKind::Io, "cannot open " + lockPath.string() + ": " + std::strerror(errno));
  struct Unlock {
    int fd;
    ~Unlock() { ::close(fd); }  // closing releases the flock
  } unlock{lock};
  while (::flock(lock, LOCK_EX) != 0)
    if (errno != EINTR)
      return makeError(ErrorKind::Io, "cannot lock " + lockPath.string() + ": " + std::strerror(errno));
  if (fs::is_directory(final)) return final;

  const fs::path staging = root / (id + ".staging.pid" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  Status made = make(staging);
  if (!made.ok()) {
    fs::remove_all(staging, ec);
    return makeError(made.error().kind, "making the test fixture " + name + ": " + made.error().message);
  }
  if (!fs::is_directory(staging))
    return makeError(ErrorKind::Internal, "making the test fixture " + name + " wrote no " + staging.string());
  const std::string maker = key.substr(0, key.rfind('-') + 1), stale = pathComponent(name) + "." + maker;
  for (const auto& e : fs::directory_iterator(root, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(stale, 0) == 0 && n.find(".staging.") == std::string::npos && n != id && n != id + ".lock")
      fs::remove_all(e.path(), ec);
  }
  fs::rename(staging, final, ec);
  if (ec) {
    const std::string why = ec.message();
    // Made beside the lock by someone else (a process of an older tree without it): use theirs.
    fs::remove_all(staging, ec);
    if (fs::is_directory(final)) return final;
    return makeError(ErrorKind::Io, "cannot rename " + staging.string() + " to " + final.string() + ": " + why);
  }
  return final;
}

}  // namespace vegstream::testing
