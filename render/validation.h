#pragma once
// Validation-layer messages, counted. The context routes every VK_EXT_debug_utils message of
// warning or error severity here; tests fail on any, the program logs them.

#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace vegstream::render {

class ValidationLog {
 public:
  using Listener = std::function<void(const std::string& message, bool isError)>;

  void setListener(Listener listener) { listener_ = std::move(listener); }

  void report(const std::string& message, bool isError) {
    {
      std::lock_guard lock(mutex_);
      messages_.push_back(message);
      (isError ? errors_ : warnings_)++;
    }
    if (listener_) listener_(message, isError);
  }

  int errors() const {
    std::lock_guard lock(mutex_);
    return errors_;
  }
  int warnings() const {
    std::lock_guard lock(mutex_);
    return warnings_;
  }
  std::vector<std::string> messages() const {
    std::lock_guard lock(mutex_);
    return messages_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> messages_;
  int errors_ = 0;
  int warnings_ = 0;
  Listener listener_;
};

}  // namespace vegstream::render
