#pragma once

#include <cstddef>

namespace mm::detail {

/// A hash of a list of indices: an assignment of forecast indices (spec §9), or (j, i, rough). For
/// the memos of rooms by assignment, which are looked up far more often than they are walked.
struct index_hash {
  template <class Indices>
  std::size_t operator()(const Indices& indices) const {
    std::size_t h = indices.size();
    for (const std::size_t i : indices) h = (h ^ i) * 0x100000001b3ULL + (h >> 29);
    return h;
  }
};

}  // namespace mm::detail
