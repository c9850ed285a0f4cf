#include "mm/maneuverability.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mm/geometry.hpp"
#include "union_cells.hpp"

namespace mm {

double maneuverability_index(const maneuver_samples& samples, family f, const sample_mask& colliding) {
  const index_range r = samples.grid(f);
  double total = 0.0;
  double unsafe = 0.0;
  for (std::size_t i = r.begin; i < r.end; ++i) {
    total += samples.area_weights[i];
    if (colliding.test(i)) unsafe += samples.area_weights[i];
  }
  if (total <= 0.0) return colliding.all_in(r.begin, r.end) ? 0.0 : 1.0;
  return std::clamp((total - unsafe) / total, 0.0, 1.0);
}

maneuverability_pair maneuverability_indices(const maneuver_samples& samples, const sample_mask& colliding) {
  return {maneuverability_index(samples, family::brake, colliding),
          maneuverability_index(samples, family::accelerate, colliding)};
}

sample_mask read_nodes_reference(const maneuver_samples& samples, const sample_mask& positive) {
  sample_mask read(samples.size());
  for (const family f : {family::brake, family::accelerate}) {
    const displacement_set& set = samples.set(f);
    if (set.degenerate) continue;
    const std::size_t columns = set.curvature_count;
    const std::size_t rows = set.acceleration_count;
    const auto node = [&](std::size_t ia, std::size_t ic) { return samples.grid(f).begin + ia * columns + ic; };
    const auto mark_if_different = [&](std::size_t a, std::size_t b) {
      if (positive.test(a) != positive.test(b)) {
        read.set(a);
        read.set(b);
      }
    };
    for (std::size_t ia = 0; ia < rows; ++ia) {
      for (std::size_t ic = 0; ic < columns; ++ic) {
        if (ic + 1 < columns) mark_if_different(node(ia, ic), node(ia, ic + 1));
        if (ia + 1 < rows) mark_if_different(node(ia, ic), node(ia + 1, ic));
        if (ia + 1 < rows && ic + 1 < columns) {
          const bool p00 = positive.test(node(ia, ic));
          const bool p10 = positive.test(node(ia, ic + 1));
          const bool p01 = positive.test(node(ia + 1, ic));
          const bool p11 = positive.test(node(ia + 1, ic + 1));
          if (p00 == p11 && p10 == p01 && p00 != p10) {
            for (const std::size_t m : {node(ia, ic), node(ia, ic + 1), node(ia + 1, ic), node(ia + 1, ic + 1)}) {
              read.set(m);
            }
          }
        }
      }
    }
  }
  return read;
}

void read_nodes(const maneuver_samples& samples, const sample_mask& positive, sample_mask& read) {
  read.clear(samples.size());
  for (const family f : {family::brake, family::accelerate}) {
    const displacement_set& set = samples.set(f);
    if (set.degenerate) continue;
    const std::size_t columns = set.curvature_count;
    const std::size_t rows = set.acceleration_count;
    const std::size_t first = samples.grid(f).begin;
    if (columns == 0 || rows == 0) continue;
    if (columns > 63) {
      read |= read_nodes_reference(samples, positive);
      continue;
    }
    // Bit c of a row word is the node of column c; a sign change between columns c and c + 1 is
    // bit c of row ^ (row >> 1), kept below the last column.
    const std::uint64_t edges = (std::uint64_t{1} << (columns - 1)) - 1;
    std::uint64_t below = positive.bits(first, columns);
    for (std::size_t ia = 0; ia < rows; ++ia) {
      const std::uint64_t row = below;
      const std::uint64_t across = (row ^ (row >> 1)) & edges;
      std::uint64_t marked = across | (across << 1);
      if (ia + 1 < rows) {
        below = positive.bits(first + (ia + 1) * columns, columns);
        const std::uint64_t up = row ^ below;
        marked |= up;
        read.add_bits(first + (ia + 1) * columns, columns, up);
      }
      read.add_bits(first + ia * columns, columns, marked);
    }
  }
}

double positive_fraction(double c0, double c1) {
  const bool p0 = c0 > 0.0;
  const bool p1 = c1 > 0.0;
  if (p0 == p1) return p0 ? 1.0 : 0.0;
  const double t = c0 / (c0 - c1);  // where the interpolant crosses zero
  return p0 ? t : 1.0 - t;
}

double positive_fraction(double c00, double c10, double c01, double c11) {
  // A cell with one sign at every corner is whole or empty (what the polygon below would give).
  const int positive_corners = (c00 > 0.0) + (c10 > 0.0) + (c01 > 0.0) + (c11 > 0.0);
  if (positive_corners == 4) return 1.0;
  if (positive_corners == 0) return 0.0;
  // Corners counter-clockwise.
  const std::array<vec2, 4> p{vec2{0.0, 0.0}, vec2{1.0, 0.0}, vec2{1.0, 1.0}, vec2{0.0, 1.0}};
  const std::array<double, 4> c{c00, c10, c11, c01};
  const auto positive = [&](std::size_t i) { return c[i] > 0.0; };
  const auto crossing = [&](std::size_t i) {
    const std::size_t k = (i + 1) % 4;
    return p[i] + (c[i] / (c[i] - c[k])) * (p[k] - p[i]);
  };
  const bool saddle = positive(0) == positive(2) && positive(1) == positive(3) && positive(0) != positive(1);
  if (saddle) {
    // Each corner of the diagonal is cut off by the segment between the crossings on its edges.
    const auto corner_triangle = [&](std::size_t i) {
      const std::size_t before = (i + 3) % 4;
      return 0.5 * norm(crossing(i) - p[i]) * norm(crossing(before) - p[i]);
    };
    const double centre = 0.25 * (c00 + c10 + c01 + c11);
    const std::size_t first_positive = positive(0) ? 0 : 1;
    const std::size_t first_negative = 1 - first_positive;
    if (centre > 0.0) return 1.0 - corner_triangle(first_negative) - corner_triangle(first_negative + 2);
    return corner_triangle(first_positive) + corner_triangle(first_positive + 2);
  }
  std::array<vec2, 8> polygon{};
  std::size_t n = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    if (positive(i)) polygon[n++] = p[i];
    if (positive(i) != positive((i + 1) % 4)) polygon[n++] = crossing(i);
  }
  double twice_area = 0.0;
  for (std::size_t i = 0; i < n; ++i) twice_area += cross(polygon[i], polygon[(i + 1) % n]);
  return std::clamp(0.5 * twice_area, 0.0, 1.0);
}

namespace {

/// A convex polygon in the unit cell: the part of the cell safe so far. A cut by one line adds at
/// most one vertex; the first 12 are kept in place (no allocation for a cell cut up to eight
/// times), more on the heap.
class polygon {
 public:
  polygon() = default;
  polygon(const vec2* first, const vec2* last) {
    for (; first != last; ++first) push_back(*first);
  }
  std::size_t size() const { return size_; }
  vec2 operator[](std::size_t i) const { return heap_.empty() ? local_[i] : heap_[i]; }
  void push_back(vec2 p) {
    if (heap_.empty() && size_ < local_.size()) {
      local_[size_++] = p;
      return;
    }
    if (heap_.empty()) heap_.assign(local_.begin(), local_.end());
    heap_.push_back(p);
    ++size_;
  }

 private:
  std::array<vec2, 12> local_;
  std::vector<vec2> heap_;
  std::size_t size_ = 0;
};

/// The part of convex `region` on the side of the line through a and b where `inside` lies
/// (Sutherland–Hodgman against one edge).
polygon clipped(const polygon& region, vec2 a, vec2 b, vec2 inside) {
  const vec2 along = b - a;
  const double side = cross(along, inside - a) < 0.0 ? -1.0 : 1.0;
  const auto height = [&](vec2 x) { return side * cross(along, x - a); };
  polygon out;
  for (std::size_t i = 0; i < region.size(); ++i) {
    const vec2 u = region[i];
    const vec2 v = region[(i + 1) % region.size()];
    const double hu = height(u);
    const double hv = height(v);
    if (hu >= 0.0) out.push_back(u);
    if ((hu >= 0.0) != (hv >= 0.0)) out.push_back(u + (hu / (hu - hv)) * (v - u));
  }
  return out;
}

double area(const polygon& region) {
  double twice = 0.0;
  for (std::size_t i = 0; i < region.size(); ++i) twice += cross(region[i], region[(i + 1) % region.size()]);
  return 0.5 * twice;
}

/// Σ of the weights of the cells between the rows and columns of the grid, in index order.
double total_cell_weight(const displacement_set& set) {
  const std::size_t cells = (set.acceleration_count - 1) * (set.curvature_count - 1);
  double total = 0.0;
  for (std::size_t c = 0; c < cells; ++c) total += set.cell_weights[c];
  return total;
}

constexpr std::array<vec2, 4> unit_square{vec2{0.0, 0.0}, vec2{1.0, 0.0}, vec2{1.0, 1.0}, vec2{0.0, 1.0}};

/// The area of `region` ∩ the safe regions of obstacles[first..]: each obstacle's region is one
/// convex polygon (cut by one chord, or a saddle by two) or, a saddle with its centre ≤ 0, two
/// disjoint corner triangles, whose parts are added.
double safe_area(const polygon& region, std::span<const cell_corners> obstacles, std::size_t first) {
  if (region.size() < 3) return 0.0;
  if (first == obstacles.size()) return area(region);
  const cell_corners& c = obstacles[first];
  const auto positive = [&](std::size_t i) { return c[i] > 0.0; };
  const auto crossing = [&](std::size_t i) {
    const std::size_t k = (i + 1) % 4;
    return unit_square[i] + (c[i] / (c[i] - c[k])) * (unit_square[k] - unit_square[i]);
  };
  const int positives = positive(0) + positive(1) + positive(2) + positive(3);
  if (positives == 4) return safe_area(region, obstacles, first + 1);
  if (positives == 0) return 0.0;
  const bool saddle = positive(0) == positive(2) && positive(1) == positive(3);
  if (!saddle) {
    // One chord, between the crossings on the two edges whose ends differ.
    std::array<vec2, 2> ends{};
    std::size_t n = 0;
    std::size_t inside = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      if (positive(i) != positive((i + 1) % 4)) ends[n++] = crossing(i);
      if (positive(i)) inside = i;
    }
    return safe_area(clipped(region, ends[0], ends[1], unit_square[inside]), obstacles, first + 1);
  }
  // A corner i is cut off by the chord between the crossings on its two edges (i − 1 and i).
  if (0.25 * (c[0] + c[1] + c[2] + c[3]) > 0.0) {
    polygon cut = region;
    for (std::size_t i = 0; i < 4; ++i) {
      if (!positive(i)) cut = clipped(cut, crossing(i), crossing((i + 3) % 4), unit_square[(i + 2) % 4]);
    }
    return safe_area(cut, obstacles, first + 1);
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    if (positive(i)) {
      sum += safe_area(clipped(region, crossing(i), crossing((i + 3) % 4), unit_square[i]), obstacles, first + 1);
    }
  }
  return sum;
}

}  // namespace

double safe_fraction(std::span<const cell_corners> obstacles) {
  if (obstacles.empty()) return 1.0;
  if (obstacles.size() == 1) {
    const cell_corners& c = obstacles.front();
    return positive_fraction(c[0], c[1], c[3], c[2]);
  }
  for (const cell_corners& c : obstacles) {
    if (!(c[0] > 0.0) && !(c[1] > 0.0) && !(c[2] > 0.0) && !(c[3] > 0.0)) return 0.0;
  }
  return std::clamp(safe_area(polygon(unit_square.data(), unit_square.data() + unit_square.size()), obstacles, 0), 0.0, 1.0);
}

double safe_fraction(std::span<const std::array<double, 2>> obstacles) {
  if (obstacles.empty()) return 1.0;
  if (obstacles.size() == 1) return positive_fraction(obstacles.front()[0], obstacles.front()[1]);
  double low = 0.0;
  double high = 1.0;
  for (const auto& [c0, c1] : obstacles) {
    const bool p0 = c0 > 0.0;
    const bool p1 = c1 > 0.0;
    if (p0 && p1) continue;
    if (!p0 && !p1) return 0.0;
    const double t = c0 / (c0 - c1);
    if (p0) {
      high = std::min(high, t);
    } else {
      low = std::max(low, t);
    }
  }
  return std::clamp(high - low, 0.0, 1.0);
}

double maneuverability_index_of_union(const displacement_set& set,
                                      std::span<const std::span<const double>> clearances) {
  if (clearances.empty()) return 1.0;
  if (clearances.size() == 1) return maneuverability_index(set, clearances.front());
  const std::size_t nodes = set.samples.size();
  const auto safe_node = [&](std::size_t k) {
    for (const std::span<const double> c : clearances) {
      if (!(c[k] > 0.0)) return false;
    }
    return true;
  };
  if (set.degenerate) {
    std::size_t safe = 0;
    for (std::size_t k = 0; k < nodes; ++k) safe += safe_node(k) ? 1 : 0;
    return static_cast<double>(safe) / static_cast<double>(nodes);
  }
  bool all_safe = true;
  for (std::size_t k = 0; k < nodes && all_safe; ++k) all_safe = safe_node(k);
  if (all_safe) return 1.0;
  const std::size_t columns = set.curvature_count;
  double total = 0.0;
  double safe = 0.0;
  if (columns == 1) {
    std::vector<std::array<double, 2>> ends;
    for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
      const double w = set.cell_weights[ia];
      total += w;
      ends.clear();
      for (const std::span<const double> c : clearances) {
        if (!(c[ia] > 0.0) || !(c[ia + 1] > 0.0)) ends.push_back({c[ia], c[ia + 1]});
      }
      safe += ends.empty() ? w : w * safe_fraction(std::span<const std::array<double, 2>>(ends));
    }
  } else {
    std::vector<cell_corners> corners;
    for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
      for (std::size_t ik = 0; ik + 1 < columns; ++ik) {
        const double w = set.cell_weights[ia * (columns - 1) + ik];
        const std::size_t lower = ia * columns + ik;
        const std::size_t upper = lower + columns;
        total += w;
        corners.clear();
        for (const std::span<const double> c : clearances) {
          const cell_corners cell{c[lower], c[lower + 1], c[upper + 1], c[upper]};
          if (!(cell[0] > 0.0) || !(cell[1] > 0.0) || !(cell[2] > 0.0) || !(cell[3] > 0.0)) corners.push_back(cell);
        }
        safe += corners.empty() ? w : w * safe_fraction(std::span<const cell_corners>(corners));
      }
    }
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

double maneuverability_index_of_union(const displacement_set& set,
                                      std::span<const std::span<const double>> clearances,
                                      std::span<const sample_mask> negative, std::size_t first,
                                      std::span<double* const> single_shares) {
  const std::size_t columns = set.curvature_count;
  const std::size_t rows = set.acceleration_count;
  const std::size_t count = clearances.size();
  if (count <= 1 || set.degenerate || columns < 2 || columns > 64 || rows < 2 || rows > 64 ||
      negative.size() != count) {
    return maneuverability_index_of_union(set, clearances);
  }
  const auto row_bits = [&](std::size_t j, std::size_t ia) { return negative[j].bits(first + ia * columns, columns); };
  bool all_safe = true;
  for (std::size_t j = 0; j < count && all_safe; ++j) {
    for (std::size_t ia = 0; ia < rows && all_safe; ++ia) all_safe = row_bits(j, ia) == 0;
  }
  if (all_safe) return 1.0;
  std::vector<std::uint64_t> touching(count);  // per obstacle: the cells of the row with a corner ≤ 0
  std::vector<cell_corners> corners(count);      // a cell's: those of the obstacles ≤ 0 at one of them
  const double total = total_cell_weight(set);
  double safe = 0.0;
  const std::uint64_t cells = (std::uint64_t{1} << (columns - 1)) - 1;
  for (std::size_t ia = 0; ia + 1 < rows; ++ia) {
    const std::uint64_t covered = detail::union_row_cells(negative, first, columns, ia, touching);
    std::uint64_t touched = 0;
    for (const std::uint64_t t : touching) touched |= t;
    const double* w = set.cell_weights.data() + ia * (columns - 1);
    // The cells that add to the safe area, in the order of `maneuverability_index_of_union`'s sum:
    // a covered cell adds w · 0.
    for (std::uint64_t adding = cells & ~covered; adding != 0; adding &= adding - 1) {
      const auto ik = static_cast<std::size_t>(std::countr_zero(adding));
      if (((touched >> ik) & 1U) == 0) {
        safe += w[ik];
        continue;
      }
      const std::size_t lower = ia * columns + ik;
      const std::size_t upper = lower + columns;
      std::size_t touching_cell = 0;
      std::size_t alone = count;
      for (std::size_t j = 0; j < count; ++j) {
        if (((touching[j] >> ik) & 1U) == 0) continue;
        const std::span<const double> c = clearances[j];
        corners[touching_cell++] = {c[lower], c[lower + 1], c[upper + 1], c[upper]};
        alone = touching_cell == 1 ? j : count;
      }
      double* const kept = alone < single_shares.size() && single_shares[alone] != nullptr
                               ? single_shares[alone] + ia * (columns - 1) + ik
                               : nullptr;
      if (kept != nullptr && !std::isnan(*kept)) {
        safe += w[ik] * *kept;
        continue;
      }
      const double share = safe_fraction(std::span<const cell_corners>(corners).first(touching_cell));
      if (kept != nullptr) *kept = share;
      safe += w[ik] * share;
    }
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

namespace {

/// The signs of a family's nodes as one word per grid row: bit k of `rows[ia]` is set when node
/// (ia, k) is positive; `all_positive` tells whether every node is positive. For grids of 2 to 64
/// rows and columns.
struct row_signs {
  std::array<std::uint64_t, 64> rows{};
  bool all_positive = true;
};

/// Fills `signs` from a mask holding the nodes' signs from index `first` on, in node order; false
/// (the grid is not one of `row_signs`) when it cannot.
bool signs_by_row(const displacement_set& set, const sample_mask& positive, std::size_t first, row_signs& signs) {
  const std::size_t columns = set.curvature_count;
  const std::size_t count = set.acceleration_count;
  if (columns < 2 || columns > 64 || count < 2 || count > 64 || positive.size() < first + count * columns) return false;
  const std::uint64_t full = columns == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << columns) - 1;
  for (std::size_t ia = 0; ia < count; ++ia) {
    const std::uint64_t bits = positive.bits(first + ia * columns, columns);
    signs.rows[ia] = bits;
    signs.all_positive = signs.all_positive && bits == full;
  }
  return true;
}

/// Visits the cells of grid row ia (between node rows ia and ia + 1) that have a positive corner,
/// in increasing ik: `whole(begin, end)` for each run [begin, end) of cells positive at every
/// corner, `part(ik, pattern)` for each other one (pattern bit 0 is c00, bit 1 c10, bit 2 c01,
/// bit 3 c11).
template <class Whole, class Part>
void for_each_positive_cell(const row_signs& signs, std::size_t ia, std::size_t columns, Whole&& whole, Part&& part) {
  const std::uint64_t lower = signs.rows[ia];
  const std::uint64_t upper = signs.rows[ia + 1];
  const std::uint64_t cells = (std::uint64_t{1} << (columns - 1)) - 1;
  const std::uint64_t every = lower & (lower >> 1) & upper & (upper >> 1) & cells;
  std::uint64_t touched = (lower | (lower >> 1) | upper | (upper >> 1)) & cells;
  while (touched != 0) {
    const auto ik = static_cast<std::size_t>(std::countr_zero(touched));
    if ((every >> ik) & 1U) {
      const auto end = ik + static_cast<std::size_t>(std::countr_one(every >> ik));
      whole(ik, end);
      touched &= end >= 64 ? 0 : ~std::uint64_t{0} << end;
    } else {
      part(ik, static_cast<unsigned>(((lower >> ik) & 3U) | (((upper >> ik) & 3U) << 2)));
      touched &= touched - 1;
    }
  }
}

/// `maneuverability_index` over the cells with a positive corner (the others add 0), from the
/// nodes' signs by row.
double interpolated_index(const displacement_set& set, std::span<const double> clearance, const row_signs& signs) {
  // Safe everywhere: every cell adds its whole weight to both sums, so the index is exactly 1.
  if (signs.all_positive) return 1.0;
  const std::size_t columns = set.curvature_count;
  const double total = total_cell_weight(set);
  double safe = 0.0;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    const double* w = set.cell_weights.data() + ia * (columns - 1);
    for_each_positive_cell(
        signs, ia, columns,
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t ik = begin; ik < end; ++ik) safe += w[ik];
        },
        [&](std::size_t ik, unsigned) {
          const std::size_t lower = ia * columns + ik;
          const std::size_t upper = lower + columns;
          safe += w[ik] * positive_fraction(clearance[lower], clearance[lower + 1], clearance[upper], clearance[upper + 1]);
        });
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

/// positive_fraction of ±1 corners, by pattern: bit 0 c00, bit 1 c10, bit 2 c01, bit 3 c11.
const std::array<double, 16>& sign_shares() {
  static const std::array<double, 16> share = [] {
    std::array<double, 16> table{};
    const auto sign = [](unsigned pattern, unsigned bit) { return (pattern >> bit) & 1U ? 1.0 : -1.0; };
    for (unsigned p = 0; p < 16; ++p) table[p] = positive_fraction(sign(p, 0), sign(p, 1), sign(p, 2), sign(p, 3));
    return table;
  }();
  return share;
}

/// `sign_index` over the cells with a positive corner, from the nodes' signs by row.
double sign_index_of(const displacement_set& set, const row_signs& signs) {
  if (signs.all_positive) return 1.0;
  const std::array<double, 16>& share = sign_shares();
  const std::size_t columns = set.curvature_count;
  const double total = total_cell_weight(set);
  double safe = 0.0;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    const double* w = set.cell_weights.data() + ia * (columns - 1);
    for_each_positive_cell(
        signs, ia, columns,
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t ik = begin; ik < end; ++ik) safe += w[ik];
        },
        [&](std::size_t ik, unsigned pattern) { safe += w[ik] * share[pattern]; });
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

}  // namespace

double maneuverability_index(const displacement_set& set, std::span<const double> clearance,
                             const sample_mask& positive, std::size_t first) {
  row_signs signs;
  if (!set.degenerate && signs_by_row(set, positive, first, signs)) return interpolated_index(set, clearance, signs);
  return maneuverability_index(set, clearance);
}

double sign_index(const displacement_set& set, const sample_mask& positive, std::size_t first) {
  row_signs signs;
  if (!set.degenerate && signs_by_row(set, positive, first, signs)) return sign_index_of(set, signs);
  // The node-by-node estimator, which reads only the signs: ±1 values.
  std::vector<double> unit(set.samples.size());
  for (std::size_t m = 0; m < unit.size(); ++m) unit[m] = positive.test(first + m) ? 1.0 : -1.0;
  return sign_index(set, unit);
}

double maneuverability_index(const displacement_set& set, std::span<const double> clearance) {
  if (set.degenerate) {
    std::size_t safe = 0;
    for (const double c : clearance) safe += c > 0.0 ? 1 : 0;
    return static_cast<double>(safe) / static_cast<double>(clearance.size());
  }
  const std::size_t columns = set.curvature_count;
  if (std::all_of(clearance.begin(), clearance.end(), [](double c) { return c > 0.0; })) return 1.0;
  double total = 0.0;
  double safe = 0.0;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    if (columns == 1) {
      const double w = set.cell_weights[ia];
      total += w;
      safe += w * positive_fraction(clearance[ia], clearance[ia + 1]);
      continue;
    }
    for (std::size_t ik = 0; ik + 1 < columns; ++ik) {
      const double w = set.cell_weights[ia * (columns - 1) + ik];
      const std::size_t lower = ia * columns + ik;
      const std::size_t upper = lower + columns;
      total += w;
      // x along κ, y along a. Most cells have one sign at every corner: decided here without the call.
      const double c00 = clearance[lower];
      const double c10 = clearance[lower + 1];
      const double c01 = clearance[upper];
      const double c11 = clearance[upper + 1];
      const int positive_corners = (c00 > 0.0) + (c10 > 0.0) + (c01 > 0.0) + (c11 > 0.0);
      if (positive_corners == 4) {
        safe += w;
      } else if (positive_corners != 0) {
        safe += w * positive_fraction(c00, c10, c01, c11);
      }
    }
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

double sign_index(const displacement_set& set, std::span<const double> clearance) {
  if (set.degenerate || set.curvature_count == 1) {
    // One sign per node is all the interpolation sees here too: the general estimator of ±1 values.
    std::vector<double> signs(clearance.size());
    for (std::size_t m = 0; m < signs.size(); ++m) signs[m] = clearance[m] > 0.0 ? 1.0 : -1.0;
    return maneuverability_index(set, signs);
  }
  const std::array<double, 16>& share = sign_shares();
  const std::size_t columns = set.curvature_count;
  if (std::all_of(clearance.begin(), clearance.end(), [](double c) { return c > 0.0; })) return 1.0;
  double total = 0.0;
  double safe = 0.0;
  for (std::size_t ia = 0; ia + 1 < set.acceleration_count; ++ia) {
    for (std::size_t ik = 0; ik + 1 < columns; ++ik) {
      const double w = set.cell_weights[ia * (columns - 1) + ik];
      const std::size_t lower = ia * columns + ik;
      const std::size_t upper = lower + columns;
      total += w;
      const unsigned pattern = (clearance[lower] > 0.0 ? 1U : 0U) | (clearance[lower + 1] > 0.0 ? 2U : 0U) |
                               (clearance[upper] > 0.0 ? 4U : 0U) | (clearance[upper + 1] > 0.0 ? 8U : 0U);
      if (pattern == 15U) {
        safe += w;
      } else if (pattern != 0U) {
        safe += w * share[pattern];
      }
    }
  }
  if (total <= 0.0) return 1.0;
  return std::clamp(safe / total, 0.0, 1.0);
}

std::vector<std::uint8_t> excluded_forecast_times(std::span<const double> forecast_times,
                                                  double time_to_collision) {
  std::vector<std::uint8_t> excluded(forecast_times.size(), 0);
  for (std::size_t i = 1; i < forecast_times.size(); ++i) {
    excluded[i] = forecast_times[i] > time_to_collision ? 1 : 0;
  }
  return excluded;
}

}  // namespace mm
