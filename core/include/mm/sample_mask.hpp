#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mm {

/// A set of sample indices (a fixed-size bitset), e.g. the colliding maneuvers [CSS] of a sample grid.
class sample_mask {
 public:
  sample_mask() = default;
  explicit sample_mask(std::size_t size) : size_(size), words_((size + 63) / 64, 0) {}

  /// Every sample cleared, `size` of them, keeping the memory.
  void clear(std::size_t size) {
    size_ = size;
    words_.assign((size + 63) / 64, 0);
  }

  std::size_t size() const { return size_; }
  bool test(std::size_t i) const { return (words_[i / 64] >> (i % 64)) & 1U; }
  void set(std::size_t i) { words_[i / 64] |= std::uint64_t{1} << (i % 64); }
  void reset(std::size_t i) { words_[i / 64] &= ~(std::uint64_t{1} << (i % 64)); }

  /// Number of members.
  std::size_t count() const;
  bool none() const;
  /// True when every index in [begin, end) is a member.
  bool all_in(std::size_t begin, std::size_t end) const;

  sample_mask& operator|=(const sample_mask& other);
  /// Removes the members of `other` (of the same size).
  sample_mask& subtract(const sample_mask& other);
  /// Becomes the complement of `other` in [0, other.size()), keeping the memory.
  void assign_complement(const sample_mask& other);
  /// Members among the `count` indices from `begin` (count ≤ 64, begin + count ≤ size()): bit j is index begin + j.
  std::uint64_t bits(std::size_t begin, std::size_t count) const {
    if (count == 0) return 0;
    const std::size_t w = begin / 64;
    const std::size_t shift = begin % 64;
    std::uint64_t value = words_[w] >> shift;
    if (shift != 0 && shift + count > 64) value |= words_[w + 1] << (64 - shift);
    return count == 64 ? value : value & ((std::uint64_t{1} << count) - 1);
  }
  /// Adds index begin + j for every bit j set in `bits` (only bits below `count`, as `bits()` reads them).
  void add_bits(std::size_t begin, std::size_t count, std::uint64_t bits) {
    if (count == 0) return;
    if (count < 64) bits &= (std::uint64_t{1} << count) - 1;
    const std::size_t w = begin / 64;
    const std::size_t shift = begin % 64;
    words_[w] |= bits << shift;
    if (shift != 0 && shift + count > 64) words_[w + 1] |= bits >> (64 - shift);
  }
  friend sample_mask operator|(sample_mask a, const sample_mask& b) { return a |= b; }
  friend bool operator==(const sample_mask&, const sample_mask&) = default;

  std::span<const std::uint64_t> words() const { return words_; }

  /// Calls `visit(i)` for every member i, in increasing order.
  template <class Visit>
  void for_each(Visit&& visit) const {
    for (std::size_t w = 0; w < words_.size(); ++w) {
      std::uint64_t bits = words_[w];
      while (bits != 0) {
        visit(w * 64 + static_cast<std::size_t>(std::countr_zero(bits)));
        bits &= bits - 1;
      }
    }
  }

 private:
  std::size_t size_ = 0;
  std::vector<std::uint64_t> words_;
};

}  // namespace mm
