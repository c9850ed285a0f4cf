#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "mm/forecast.hpp"

namespace mm::sim::detail {

/// SplitMix64's finaliser: a bijective 64-bit mixer (Steele, Lea, Flood 2014).
std::uint64_t mix64(std::uint64_t x);

/// FNV-1a 64-bit hash of a name.
std::uint64_t name_hash(std::string_view name);

/// Counter-based Gaussian noise: the noise of the observation of `target` by `observer` at step
/// k depends only on (seed, observer name, target name, k). So it does not change when agents are
/// added, removed, reordered, or skipped while out of range.
class noise_source {
 public:
  noise_source(std::uint64_t seed, std::string_view observer, std::string_view target);

  /// Four independent standard normal deviates for step `step` (Box–Muller on four uniforms).
  void standard_normals(std::uint64_t step, double (&out)[4]) const;

 private:
  std::uint64_t key_;
};

/// The most recent observations of one target, oldest first, in a fixed-capacity ring
/// (allocated on the first push).
class observation_ring {
 public:
  explicit observation_ring(std::size_t capacity = 2) : capacity_(capacity < 1 ? 1 : capacity) {}

  void push(const observation& o);
  void clear() {
    size_ = 0;
    head_ = 0;
    maxima_size_ = 0;
  }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const observation& back() const;
  /// Oldest first.
  void copy_to(std::vector<observation>& out) const;
  /// The last `count` entries (count ≤ size()), oldest first: what a ring of capacity `count` fed
  /// the same observations would `copy_to`.
  void copy_last_to(std::size_t count, std::vector<observation>& out) const;
  /// Largest observed speed in the ring and 0 [m/s]: max(0, speeds), in O(1).
  double max_speed() const;
  /// The same over the last `count` entries (count ≤ size()): from the sliding window's candidates,
  /// the first one pushed at or after the window's start.
  double max_speed_of_last(std::size_t count) const;
  /// The same by a scan of the ring (the reference of `max_speed`).
  double max_speed_by_scan() const;

 private:
  /// The entries oldest first, as the two contiguous parts of the buffer (the second may be empty).
  std::array<std::span<const observation>, 2> segments() const;
  std::size_t capacity_;
  std::vector<observation> buffer_;
  std::size_t head_ = 0;  ///< index of the oldest
  std::size_t size_ = 0;
  /// The sliding window's maximum: (speed, push number) of the entries that no later entry is at
  /// least as fast as, oldest first, so decreasing; the first is the largest speed in the ring. A
  /// ring of `capacity_` slots (`maxima_head_`: the first).
  std::vector<std::pair<double, std::uint64_t>> maxima_;
  std::size_t maxima_head_ = 0;
  std::size_t maxima_size_ = 0;
  std::uint64_t pushed_ = 0;  ///< pushes so far: the oldest entry is push number pushed_ − size_
};

}  // namespace mm::sim::detail
