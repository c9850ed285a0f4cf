#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "mm/sample_mask.hpp"

namespace mm::detail {

/// The cells of grid row ia (between node rows ia and ia + 1) of a family of 2 to 64 columns whose
/// nodes start at sample `first`, from each obstacle's mask of the samples where its clearance is
/// ≤ 0 (`negative`): bit ik of `touching[j]` is set when obstacle j is ≤ 0 at some corner of cell
/// ik. Returns the cells that some obstacle is ≤ 0 at all four corners of (spec §6, §9: they add
/// nothing to the union's safe area, and nothing in them is read).
inline std::uint64_t union_row_cells(std::span<const sample_mask> negative, std::size_t first, std::size_t columns,
                                     std::size_t ia, std::span<std::uint64_t> touching) {
  const std::uint64_t cells = (std::uint64_t{1} << (columns - 1)) - 1;
  std::uint64_t covered = 0;
  for (std::size_t j = 0; j < negative.size(); ++j) {
    const std::uint64_t lower = negative[j].bits(first + ia * columns, columns);
    const std::uint64_t upper = negative[j].bits(first + (ia + 1) * columns, columns);
    touching[j] = (lower | (lower >> 1) | upper | (upper >> 1)) & cells;
    covered |= lower & (lower >> 1) & upper & (upper >> 1) & cells;
  }
  return covered;
}

}  // namespace mm::detail
