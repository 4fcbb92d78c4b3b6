#pragma once
// Shared by the mutation tests: each test's own scratch directory, and the check that a reader
// given a mutated input ended well — a value or an error value, never an exception.

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/result.h"

namespace vegstream::testing {

// VEGSTREAM_TEST_TMP/<suite>_<name>/, made fresh (other tests run in parallel, in their own).
inline std::filesystem::path ownTestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(VEGSTREAM_TEST_TMP) / (std::string(info->test_suite_name()) + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Everything written to stderr (fd 2: libpng, libjpeg, OIIO write there directly) between
// construction and text(), kept in `file`. A reader that prints its own lines would break the
// command line's one message per mistake. The test is single-threaded while this is alive.
class StderrCapture {
 public:
  explicit StderrCapture(std::filesystem::path file) : file_(std::move(file)) {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int fd = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 2);
    ::close(fd);
  }
  ~StderrCapture() { restore(); }
  // Restores stderr and returns what was written meanwhile.
  std::string text() {
    restore();
    std::ifstream in(file_);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
    saved_ = -1;
  }
  std::filesystem::path file_;
  int saved_ = -1;
};

// Tally of one reader's outcomes over the mutations (the test prints it, and checks that the
// mutations exercised both ends: some inputs still read, most are refused).
struct Outcomes {
  int ok = 0, refused = 0, threw = 0;
};

// Calls `read` (returning a Result), counting the outcome. An exception is a test failure naming
// the mutation; an error must be a user error (the input is at fault) with a message.
template <typename Read>
void expectValueOrError(Read&& read, const std::string& mutation, Outcomes& tally) {
  try {
    const auto r = read();
    if (r.ok()) {
      ++tally.ok;
      return;
    }
    ++tally.refused;
    EXPECT_FALSE(r.error().message.empty()) << mutation;
    EXPECT_TRUE(r.error().isUserError()) << mutation << ": " << r.error().message;
  } catch (const std::exception& e) {
    ++tally.threw;
    ADD_FAILURE() << "threw " << e.what() << " on: " << mutation;
  } catch (...) {
    ++tally.threw;
    ADD_FAILURE() << "threw a non-std exception on: " << mutation;
  }
}

}  // namespace vegstream::testing
