#include "mm/sample_mask.hpp"

namespace mm {

std::size_t sample_mask::count() const {
  std::size_t n = 0;
  for (const std::uint64_t w : words_) n += static_cast<std::size_t>(std::popcount(w));
  return n;
}

bool sample_mask::none() const {
  for (const std::uint64_t w : words_) {
    if (w != 0) return false;
  }
  return true;
}

bool sample_mask::all_in(std::size_t begin, std::size_t end) const {
  for (std::size_t i = begin; i < end; ++i) {
    if (!test(i)) return false;
  }
  return true;
}

sample_mask& sample_mask::operator|=(const sample_mask& other) {
  for (std::size_t w = 0; w < words_.size(); ++w) words_[w] |= other.words_[w];
  return *this;
}

sample_mask& sample_mask::subtract(const sample_mask& other) {
  for (std::size_t w = 0; w < words_.size(); ++w) words_[w] &= ~other.words_[w];
  return *this;
}

void sample_mask::assign_complement(const sample_mask& other) {
  size_ = other.size_;
  words_.resize(other.words_.size());
  for (std::size_t w = 0; w < words_.size(); ++w) words_[w] = ~other.words_[w];
  if (size_ % 64 != 0) words_.back() &= (std::uint64_t{1} << (size_ % 64)) - 1;
}

}  // namespace mm
