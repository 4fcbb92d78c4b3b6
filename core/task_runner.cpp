// ThreadPool and ManualTaskRunner (task_runner.h).

#include "core/task_runner.h"

#include <algorithm>

namespace vegstream {

ThreadPool::ThreadPool(int threads) {
  const unsigned hw = std::thread::hardware_concurrency();
  const int n = threads > 0 ? threads : std::max(1, static_cast<int>(hw));
  workers_.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
  for (auto& t : dedicated_) t.join();
}

void ThreadPool::post(Task task) {
  {
    std::lock_guard lock(mu_);
    queue_.push_back(std::move(task));
  }
  wake_.notify_one();
}

void ThreadPool::postLongRunning(Task task) {
  std::lock_guard lock(mu_);
  dedicated_.emplace_back(std::move(task));
}

void ThreadPool::work() {
  std::unique_lock lock(mu_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and everything queued has run
    Task task = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    task();
    task = nullptr;  // what it captured is released outside the lock
    lock.lock();
  }
}

void ManualTaskRunner::post(Task task) {
  std::lock_guard lock(mu_);
  queue_.push_back(std::move(task));
}

bool ManualTaskRunner::runOne() {
  Task task;
  {
    std::lock_guard lock(mu_);
    if (queue_.empty()) return false;
    task = std::move(queue_.front());
    queue_.pop_front();
  }
  task();
  return true;
}

std::size_t ManualTaskRunner::runAll() {
  std::size_t n = 0;
  while (runOne()) ++n;
  return n;
}

std::size_t ManualTaskRunner::pending() const {
  std::lock_guard lock(mu_);
  return queue_.size();
}

}  // namespace vegstream
