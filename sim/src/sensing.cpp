#include "sensing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mm::sim::detail {
namespace {

/// A uniform deviate in (0, 1] from the 53 high bits.
double unit_interval(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 1.0) * 0x1.0p-53;
}

}  // namespace

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t name_hash(std::string_view name) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

noise_source::noise_source(std::uint64_t seed, std::string_view observer, std::string_view target)
    : key_(mix64(mix64(mix64(seed) ^ name_hash(observer)) ^ name_hash(target))) {}

void noise_source::standard_normals(std::uint64_t step, double (&out)[4]) const {
  const std::uint64_t base = mix64(key_ ^ mix64(step));
  for (int pair = 0; pair < 2; ++pair) {
    const double u1 = unit_interval(mix64(base + 2 * static_cast<std::uint64_t>(pair)));
    const double u2 = unit_interval(mix64(base + 2 * static_cast<std::uint64_t>(pair) + 1));
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * std::numbers::pi * u2;
    out[2 * pair] = r * std::cos(angle);
    out[2 * pair + 1] = r * std::sin(angle);
  }
}

void observation_ring::push(const observation& o) {
  if (buffer_.empty()) {
    buffer_.resize(capacity_);
    maxima_.resize(capacity_);
  }
  const std::size_t slots = buffer_.size();
  if (size_ < slots) {
    buffer_[(head_ + size_) % slots] = o;
    ++size_;
  } else {
    // The oldest entry leaves the window: so does its candidate for the maximum, if it is one.
    if (maxima_size_ > 0 && maxima_[maxima_head_].second == pushed_ - size_) {
      maxima_head_ = maxima_head_ + 1 == slots ? 0 : maxima_head_ + 1;
      --maxima_size_;
    }
    buffer_[head_] = o;
    head_ = (head_ + 1) % slots;
  }
  // Entries no faster than the new one can no longer be the maximum of any later window.
  while (maxima_size_ > 0 && maxima_[(maxima_head_ + maxima_size_ - 1) % slots].first <= o.speed) --maxima_size_;
  maxima_[(maxima_head_ + maxima_size_) % slots] = {o.speed, pushed_};
  ++maxima_size_;
  ++pushed_;
}

const observation& observation_ring::back() const { return buffer_[(head_ + size_ - 1) % buffer_.size()]; }

std::array<std::span<const observation>, 2> observation_ring::segments() const {
  // The ring's entries oldest first: from the head to the end of the buffer, then from its start.
  const std::size_t first = std::min(size_, buffer_.size() - head_);
  return {std::span(buffer_).subspan(head_, first), std::span(buffer_).first(size_ - first)};
}

void observation_ring::copy_to(std::vector<observation>& out) const { copy_last_to(size_, out); }

void observation_ring::copy_last_to(std::size_t count, std::vector<observation>& out) const {
  out.clear();
  out.reserve(count);
  std::size_t skip = size_ - std::min(count, size_);
  for (const std::span<const observation> part : segments()) {
    const std::size_t from = std::min(skip, part.size());
    out.insert(out.end(), part.begin() + static_cast<std::ptrdiff_t>(from), part.end());
    skip -= from;
  }
}

double observation_ring::max_speed_of_last(std::size_t count) const {
  // Every entry of the window that is not a candidate was dropped for a later, at least as fast
  // one, which is in the window too; the candidates' speeds fall from the oldest on.
  const std::uint64_t start = pushed_ - std::min(count, size_);
  const std::size_t slots = maxima_.size();
  for (std::size_t i = 0; i < maxima_size_; ++i) {
    const std::pair<double, std::uint64_t>& candidate = maxima_[(maxima_head_ + i) % slots];
    if (candidate.second >= start) return std::max(0.0, candidate.first);
  }
  return 0.0;
}

double observation_ring::max_speed() const { return max_speed_of_last(size_); }

double observation_ring::max_speed_by_scan() const {
  double fastest = 0.0;
  for (const std::span<const observation> part : segments()) {
    for (const observation& o : part) fastest = std::max(fastest, o.speed);
  }
  return fastest;
}

}  // namespace mm::sim::detail
