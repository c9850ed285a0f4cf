#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <stop_token>
#include <thread>
#include <vector>

namespace mm::sim::detail {

/// Helper threads kept for a whole run, so that the planning of every step is shared by the same
/// threads instead of threads started anew each step (thread start-up, and each new thread's empty
/// allocation cache, every 10 ms of simulated time).
class worker_pool {
 public:
  /// Starts `helpers` threads that wait for `run`.
  explicit worker_pool(std::size_t helpers);
  /// Stops and joins the helpers.
  ~worker_pool();
  worker_pool(const worker_pool&) = delete;
  worker_pool& operator=(const worker_pool&) = delete;

  std::size_t helpers() const { return threads_.size(); }
  /// Calls `task` once on every helper and once on the calling thread, and returns when all calls
  /// have returned. `task` must not throw.
  void run(const std::function<void()>& task);

 private:
  void serve(std::stop_token stop);

  std::mutex mutex_;
  std::condition_variable_any wake_;  ///< a new round (or stop) for the helpers
  std::condition_variable done_;      ///< the last helper of a round finished
  const std::function<void()>* task_ = nullptr;
  std::uint64_t round_ = 0;  ///< rounds started
  std::size_t busy_ = 0;     ///< helpers still in the current round
  std::vector<std::jthread> threads_;  ///< last: stopped and joined before the members above go
};

}  // namespace mm::sim::detail
