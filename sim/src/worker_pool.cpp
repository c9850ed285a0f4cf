#include "worker_pool.hpp"

namespace mm::sim::detail {

worker_pool::worker_pool(std::size_t helpers) {
  threads_.reserve(helpers);
  for (std::size_t i = 0; i < helpers; ++i) {
    threads_.emplace_back([this](std::stop_token stop) { serve(stop); });
  }
}

worker_pool::~worker_pool() {
  for (std::jthread& t : threads_) t.request_stop();
  threads_.clear();  // joins: each helper wakes on its stop request and returns
}

void worker_pool::run(const std::function<void()>& task) {
  {
    const std::lock_guard lock(mutex_);
    task_ = &task;
    busy_ = threads_.size();
    ++round_;
  }
  wake_.notify_all();
  task();
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return busy_ == 0; });
  task_ = nullptr;
}

void worker_pool::serve(std::stop_token stop) {
  std::uint64_t seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    if (!wake_.wait(lock, stop, [&] { return round_ != seen; })) return;  // stop requested
    seen = round_;
    const std::function<void()>* task = task_;
    lock.unlock();
    (*task)();
    lock.lock();
    if (--busy_ == 0) done_.notify_one();
  }
}

}  // namespace mm::sim::detail
