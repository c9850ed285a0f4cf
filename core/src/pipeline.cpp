#include "pipeline.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mm/assignment_search.hpp"
#include "mm/collision_sets.hpp"
#include "mm/maneuverability.hpp"
#include "mm/number_text.hpp"
#include "mm/road_constraint.hpp"
#include "index_hash.hpp"
#include "union_cells.hpp"

namespace mm::detail {
namespace {

/// True when the obstacle can come within reach of any maneuver within T_c (spec §9): the ego's
/// farthest travel plus the obstacle's, plus both bounding radii and the margin.
bool can_interact(const ego_state& ego, const forecast_obstacle& obstacle, const planner_config& config) {
  const double ego_travel =
      travelled_distance(ego.speed, ego.limits.max_acceleration, config.displacement_horizon, ego.limits.speed_cap) +
      speed_after(ego.speed, ego.limits.max_acceleration, config.displacement_horizon, ego.limits.speed_cap) *
          (config.collision_window - config.displacement_horizon);
  const double obstacle_travel = obstacle.motion.speed * config.collision_window;
  const double reach = ego_travel + obstacle_travel + bounding_radius(ego.shape) +
                       bounding_radius(obstacle.shape) + config.safety_margin;
  return squared_norm(obstacle.motion.pose.position - ego.pose.position) < reach * reach;
}

plan_result invalid(std::string error) {
  plan_result result;
  result.status = plan_status::invalid_input;
  result.error = std::move(error);
  return result;
}

/// True when every forecast time is evaluated: for the map's column, the sets drawn, or the reference.
bool whole_column_wanted(const planner_config& config, const pipeline_options& options) {
  return config.map_column || config.record_samples || options.reference;
}

/// True when `u` is proven collision-free in continuous time (`verified_collision_free`, or its
/// reference) with every obstacle under each of its forecast indices `candidates[j]` (sorted): one
/// proof per forecast time, with the obstacles that may be forecast with it. A forecast that does
/// not turn (ω = 0) is the same under every τ, so such an obstacle is proven once, at τ = 0.
bool verified_under_every_forecast(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                                   std::span<const std::vector<std::size_t>> candidates, std::span<const double> taus,
                                   const collision_window& window, bool reference, proof_steps stepping) {
  std::vector<forecast_obstacle> those;
  std::vector<double> those_tau;
  for (std::size_t i = 0; i < taus.size(); ++i) {
    those.clear();
    those_tau.clear();
    for (std::size_t j = 0; j < obstacles.size(); ++j) {
      if (i > 0 && obstacles[j].motion.yaw_rate == 0.0) continue;
      if (!std::binary_search(candidates[j].begin(), candidates[j].end(), i)) continue;
      those.push_back(obstacles[j]);
      those_tau.push_back(taus[i]);
    }
    if (those.empty()) continue;
    const bool free =
        reference ? verified_collision_free_reference(ego, u, those, those_tau, window, verification_resolution, stepping)
                  : verified_collision_free(ego, u, those, those_tau, window, verification_resolution, stepping);
    if (!free) return false;
  }
  return true;
}

/// True when `u` is proven collision-free in continuous time (`verified_collision_free`, or its
/// reference) with each obstacle alone, obstacle j forecast with `forecast_times[j]`: one proof per
/// obstacle, each stepping by its own clearance rather than by the smallest of them all. As sound as
/// the proof with all of them at once, and neither proves everything the other does (docs/method.md
/// §4.6); with one obstacle it is that proof.
bool verified_with_each(const ego_state& ego, const maneuver& u, std::span<const forecast_obstacle> obstacles,
                        std::span<const double> forecast_times, const collision_window& window, bool reference,
                        proof_steps stepping) {
  for (std::size_t j = 0; j < obstacles.size(); ++j) {
    const auto one = obstacles.subspan(j, 1);
    const auto tau = forecast_times.subspan(j, 1);
    const bool free =
        reference ? verified_collision_free_reference(ego, u, one, tau, window, verification_resolution, stepping)
                  : verified_collision_free(ego, u, one, tau, window, verification_resolution, stepping);
    if (!free) return false;
  }
  return true;
}

/// True when `u` is proven collision-free (`verified_with_each`) with each obstacle alone under
/// each of its forecast indices `candidates[j]`: then `verified_with_each` proves it under every
/// assignment of those forecast times. The obstacles are taken in `order`; one that does not turn
/// (ω = 0) has the same forecast under every τ and is proven once, at τ = 0.
bool verified_with_each_under_every_forecast(const ego_state& ego, const maneuver& u,
                                             std::span<const forecast_obstacle> obstacles,
                                             std::span<const std::vector<std::size_t>> candidates,
                                             std::span<const double> taus, std::span<const std::size_t> order,
                                             const collision_window& window, bool reference, proof_steps stepping) {
  for (const std::size_t j : order) {
    for (const std::size_t i : candidates[j]) {
      if (i > 0 && obstacles[j].motion.yaw_rate == 0.0) break;
      const double tau = taus[i];
      if (!verified_with_each(ego, u, obstacles.subspan(j, 1), std::span(&tau, 1), window, reference, stepping)) {
        return false;
      }
    }
  }
  return true;
}

/// The corners a cell of four reads, for each pattern of its corners ≤ 0 (bit q: corner q,
/// counter-clockwise): the ends of every edge whose ends differ in sign, or all four of a saddle,
/// each once, in the order of the edges (q, q + 1).
struct cell_reads {
  std::array<std::uint8_t, 4> corner{};
  std::uint8_t count = 0;
};
constexpr std::array<cell_reads, 16> cell_read_table = [] {
  std::array<cell_reads, 16> table{};
  for (unsigned negative = 1; negative + 1 < 16; ++negative) {
    cell_reads& reads = table[negative];
    const bool saddle = negative == 0b0101U || negative == 0b1010U;
    const auto add = [&](unsigned q) {
      for (std::size_t r = 0; r < reads.count; ++r) {
        if (reads.corner[r] == q) return;
      }
      reads.corner[reads.count++] = static_cast<std::uint8_t>(q);
    };
    for (unsigned q = 0; q < 4; ++q) {
      const unsigned next = (q + 1) % 4;
      if (saddle || ((negative >> q) & 1U) != ((negative >> next) & 1U)) {
        add(q);
        add(next);
      }
    }
  }
  return table;
}();

/// The clearances of every relevant obstacle under an assignment of forecast times, and how to
/// turn them into indices. The reference holds ±1 per sample (collides or not) and counts; the fast
/// path holds a `clearance_field` per obstacle and makes exact only the values the interpolating
/// indices read (`make_read_values_exact`; with several obstacles `union_indices`, each obstacle
/// interpolated on its own).
class evaluator {
 public:
  evaluator(const maneuver_samples& samples, bool reference) : samples_(samples), reference_(reference) {}

  /// Reference: the collision sets of obstacle j, per forecast time, as ±1 clearances.
  void add_reference(std::vector<clearance_set> sets) { reference_sets_.push_back(std::move(sets)); }
  /// Fast path: the clearance field of the next obstacle, computing the forecast times `wanted`
  /// (empty: every one).
  /// Room for the fields of `count` obstacles, so that adding them moves none.
  void reserve_fields(std::size_t count) { fields_.reserve(count); }
  void add_field(const ego_sweep& sweep, const forecast_obstacle& obstacle, std::span<const double> taus,
                 std::span<const std::uint8_t> wanted, clearance_field::raster_scratch& scratch) {
    fields_.emplace_back(sweep, obstacle, taus, clearance_cap, wanted, scratch);
  }
  /// Fast path: the road constraint (spec §5), after every obstacle's field: one more part of every
  /// combined set, the same under every forecast time.
  void add_road(const ego_sweep& sweep, const drivable_area& area) { road_.emplace(sweep, area, clearance_cap); }
  /// Reference: the road constraint as ±1 clearances (`road_clearances_reference`'s signs).
  void add_road_reference(clearance_set set) { road_reference_ = std::move(set); }

  /// A buffer for a column that is not kept.
  clearance_set& scratch_column() { return scratch_set_; }

  /// The combined set of the obstacles, obstacle j at forecast index index[j] (the union of the
  /// [CSS]): the reference's sample-wise minimum of ±1; on the fast path the signs (±cap), with one
  /// obstacle its exact values wherever the indices read them (`indices` of several read each
  /// obstacle's own, `union_indices`).
  clearance_set combined(std::span<const std::size_t> index) {
    clearance_set c;
    combine_into(index, c);
    return c;
  }

  /// The combined set of `parts`, each an (obstacle, forecast index) pair, as `combined` (the robust
  /// policy's: every obstacle under each of its non-excluded forecast times).
  clearance_set combined_of(std::span<const std::pair<std::size_t, std::size_t>> parts) {
    clearance_set c;
    combined_parts(parts, c);
    return c;
  }

  /// max(MI−, MI+) with obstacle j alone at forecast index i; `rough` as in `room_of`. Remembered,
  /// with the forecast index of an obstacle whose clearances do not depend on it taken as 0.
  double room_alone(std::size_t j, std::size_t i, bool rough) {
    if (!forecast_matters(j)) i = 0;
    const std::array<std::size_t, 3> key{j, i, rough ? 1u : 0u};
    if (const auto it = rooms_alone_.find(key); it != rooms_alone_.end()) return it->second;
    const std::pair<std::size_t, std::size_t> part{j, i};
    combined_parts(std::span(&part, 1), scratch_set_, rough, true);
    const double r = rough && !reference_ ? rough_room() : room(scratch_set_, rough);
    rooms_alone_.emplace(key, r);
    return r;
  }

  /// MI− and MI+ (spec §6) of `c`, the set combined last (`combined`, `column`, or the scratch
  /// set): the reference counts safe samples' areas; the fast path interpolates, reading the signs
  /// from `positive_`, which holds those of `c` — or, `rough`, from those signs alone (`sign_index`;
  /// `c` is then not read, nor written by a rough `combined_parts`). With several obstacles that are
  /// not inert, the indices of the union, found when `c` was combined (`union_indices`): `c` then
  /// holds only signs (±cap).
  maneuverability_pair indices(const clearance_set& c, bool rough = false) const {
    if (reference_) return maneuverability_indices(samples_, colliding(c));
    if (!rough && union_indices_) return *union_indices_;
    const index_range b = samples_.grid(family::brake);
    const index_range a = samples_.grid(family::accelerate);
    if (rough) {
      return {sign_index(samples_.brake, positive_, b.begin), sign_index(samples_.accelerate, positive_, a.begin)};
    }
    return {maneuverability_index(samples_.brake, std::span(c).subspan(b.begin, b.size()), positive_, b.begin),
            maneuverability_index(samples_.accelerate, std::span(c).subspan(a.begin, a.size()), positive_, a.begin)};
  }

  double room(const clearance_set& c, bool rough = false) const {
    const maneuverability_pair mi = indices(c, rough);
    return std::max(mi.brake, mi.accelerate);
  }

  /// max(MI−, MI+) under an assignment, remembered: obstacles whose forecast time changes nothing
  /// (inert, or not turning) count as forecast index 0, so assignments that differ only there are
  /// computed once. `rough` (fast path): from the signs alone, the boundary through the middle of
  /// every edge whose ends differ — what the fast forecast-time search ranks assignments by; the
  /// assignment it selects is then evaluated with values.
  double room_of(std::span<const std::size_t> index, bool rough) {
    const std::vector<std::size_t>& key = room_key(index, rough);
    if (const auto it = rooms_.find(key); it != rooms_.end()) return it->second;
    if (!rough) {
      if (const auto it = column_rooms_.find(key); it != column_rooms_.end()) return it->second;
    }
    combine_into(index, scratch_set_, rough, true);
    const double r = rough && !reference_ ? rough_room() : room(scratch_set_, rough);
    rooms_.emplace(key, r);
    return r;
  }

  /// The rough room of the set combined last (`room(…, true)`), remembered by its signs: the climb
  /// meets many assignments whose combined collisions are the same samples (on the roundabout's
  /// inputs a third to a half of them are distinct).
  double rough_room() {
    scratch_words_.assign(positive_.words().begin(), positive_.words().end());
    if (const auto it = rough_rooms_.find(scratch_words_); it != rough_rooms_.end()) return it->second;
    const double r = room(scratch_set_, true);
    rough_rooms_.emplace(scratch_words_, r);
    return r;
  }

  /// The combined set of every obstacle at forecast index i (a column of the map) into `c`, and its
  /// indices; its room is remembered for `room_of`.
  maneuverability_pair column(std::size_t i, clearance_set& c) {
    std::vector<std::size_t>& same = scratch_column_index_;
    same.assign(reference_ ? reference_sets_.size() : fields_.size(), i);
    combine_into(same, c);
    const maneuverability_pair mi = indices(c);
    column_rooms_.emplace(room_key(same, false), std::max(mi.brake, mi.accelerate));
    return mi;
  }

  /// False when obstacle j's clearances are the same under every forecast time (fast path: it is
  /// inert, or does not turn); the reference's sets are kept per forecast time.
  bool forecast_matters(std::size_t j) const {
    return reference_ || (!fields_[j].inert() && !fields_[j].forecast_independent());
  }

  /// Fast path: true when some obstacle's clearances depend on its forecast time (it turns, and
  /// is not inert).
  bool depends_on_forecast_time() const {
    for (std::size_t j = 0; j < fields_.size(); ++j) {
      if (forecast_matters(j)) return true;
    }
    return false;
  }

  /// True when obstacle j collides with some sample under one of the forecast indices `which`
  /// (the reference's sets are ±1: negative where a sample collides).
  bool collides_under_any(std::size_t j, std::span<const std::size_t> which) const {
    for (const std::size_t i : which) {
      if (reference_) {
        for (const double c : reference_sets_[j][i]) {
          if (c < 0.0) return true;
        }
      } else if (fields_[j].collides(i)) {
        return true;
      }
    }
    return false;
  }

  /// The work of every clearance field so far, and the assignments whose room was computed.
  void add_work(plan_work& work) const {
    for (const clearance_field& field : fields_) {
      const clearance_field::work& w = field.statistics();
      work.bound_checks += w.bound_checks;
      work.distance_evaluations += w.distance_evaluations;
      work.refinements += w.refinements;
      work.translation_minima += w.translation_minima;
    }
    std::size_t assignments = 0;
    for (const auto& [key, room] : rooms_) {
      // A rough room's key ends in `rough_key`; the same assignment's room, if computed too, is not counted again.
      if (key.empty() || key.back() != rough_key) {
        ++assignments;
      } else if (!rooms_.contains(std::vector<std::size_t>(key.begin(), key.end() - 1))) {
        ++assignments;
      }
    }
    work.assignments_evaluated += assignments;
    if (road_) work.bound_checks += road_->bound_checks();
  }

  sample_mask colliding(const clearance_set& c) const {
    sample_mask mask(samples_.size());
    for (std::size_t m = 0; m < c.size(); ++m) {
      if (!(c[m] > 0.0)) mask.set(m);
    }
    return mask;
  }

 private:
  /// The key of `rooms_` for an assignment: obstacles whose forecast time changes nothing (inert, or
  /// not turning) at forecast index 0, and `rough_key` appended for a rough room (fast path).
  const std::vector<std::size_t>& room_key(std::span<const std::size_t> index, bool rough) {
    std::vector<std::size_t>& key = scratch_key_;
    key.assign(index.begin(), index.end());
    for (std::size_t j = 0; j < key.size(); ++j) {
      if (!forecast_matters(j)) key[j] = 0;
    }
    if (!reference_ && rough) key.push_back(rough_key);
    return key;
  }

  /// `combined` into `c`, with the parts list in a buffer kept between calls; `rough` and
  /// `room_only` as in `combined_parts`.
  void combine_into(std::span<const std::size_t> index, clearance_set& c, bool rough = false, bool room_only = false) {
    scratch_parts_.clear();
    for (std::size_t j = 0; j < index.size(); ++j) scratch_parts_.emplace_back(j, index[j]);
    combined_parts(scratch_parts_, c, rough, room_only);
  }

  /// The combined set of `parts` (obstacle, forecast index) into `c`, as `combined`; `rough` (fast
  /// path): the signs of the sampled collisions only, into `positive_` (`c` is left as it was);
  /// `room_only` (fast path): only `indices` will be asked for, so where several parts are live,
  /// whose indices `union_indices` gives, `c` is left as it was too.
  void combined_parts(std::span<const std::pair<std::size_t, std::size_t>> parts, clearance_set& c,
                      bool rough = false, bool room_only = false) {
    if (reference_) {
      c.assign(samples_.size(), std::numeric_limits<double>::infinity());
      for (const auto& [j, i] : parts) {
        const clearance_set& part = reference_sets_[j][i];
        for (std::size_t m = 0; m < c.size(); ++m) c[m] = std::min(c[m], part[m]);
      }
      if (road_reference_) {
        for (std::size_t m = 0; m < c.size(); ++m) c[m] = std::min(c[m], (*road_reference_)[m]);
      }
      return;
    }
    // The signs of the sampled collisions, ±cap: the values come where the indices read them.
    negative_.clear(samples_.size());
    for (const auto& [j, i] : parts) {
      if (!fields_[j].inert()) negative_ |= fields_[j].collisions(i);
    }
    if (road_ && road_->collides()) negative_ |= road_->collisions();
    positive_.assign_complement(negative_);
    union_indices_.reset();
    if (rough) return;  // the signs are all a rough room reads
    // Inert obstacles are +cap everywhere: they change no sign and no index.
    live_parts_.clear();
    for (const auto& part : parts) {
      if (!fields_[part.first].inert()) live_parts_.push_back(part);
    }
    // The road is live where some sample leaves it (its values are its sampled minima: one without
    // a sampled exit is positive everywhere, and changes no sign and no index).
    if (road_ && road_->collides()) live_parts_.emplace_back(road_part(), 0);
    // Several obstacles: the indices now (their reads may make samples collide), the signs after.
    if (live_parts_.size() >= 2) union_indices_ = union_indices(live_parts_);
    if (room_only && union_indices_) return;
    c.assign(samples_.size(), clearance_cap);
    negative_.for_each([&](std::size_t m) { c[m] = -clearance_cap; });
    if (live_parts_.size() == 1) make_read_values_exact(live_parts_.front(), c);
  }

  /// MI− and MI+ under several obstacles that are not inert (`live`;
  /// `maneuverability_index_of_union`, each obstacle interpolated on its own), making exact every value they read: for each obstacle with a
  /// sampled collision, the ends of its sign-changing edges (and the four corners of its saddle
  /// cells) in every cell that no obstacle is ≤ 0 at all four corners of. A value read ≤ 0 where
  /// the obstacle's sampled set had none (a contact between sample times) makes that sample
  /// collide — in `negative_` and `positive_` too — and the cells around it are looked at again.
  maneuverability_pair union_indices(std::span<const std::pair<std::size_t, std::size_t>> live) {
    union_parts_.clear();
    for (const auto& [j, i] : live) {
      if (part_collides(j, i)) union_parts_.emplace_back(j, i);
    }
    const std::size_t count = union_parts_.size();
    union_spans_.clear();
    if (union_negative_.size() < count) union_negative_.resize(count);
    for (std::size_t p = 0; p < count; ++p) {
      const auto [j, i] = union_parts_[p];
      union_spans_.push_back(part_set(j, i));
      union_negative_[p] = part_collisions(j, i);
    }
    for (bool flipped = true; flipped;) {
      flipped = false;
      for (const family f : {family::brake, family::accelerate}) flipped |= read_union_cells(f);
    }
    const std::span<const sample_mask> negative = std::span(union_negative_).first(count);
    maneuverability_pair mi;
    const std::size_t brake_cells = samples_.set(family::brake).cell_weights.size();
    const std::size_t cells = brake_cells + samples_.set(family::accelerate).cell_weights.size();
    union_shares_.clear();
    for (const auto& [j, i] : union_parts_) {
      std::vector<double>& shares = single_shares_[(static_cast<std::uint64_t>(j) << 32) | i];
      if (shares.empty()) shares.assign(cells, std::numeric_limits<double>::quiet_NaN());
      union_shares_.push_back(shares.data());
    }
    for (const family f : {family::brake, family::accelerate}) {
      const index_range r = samples_.grid(f);
      union_family_spans_.clear();
      for (const std::span<const double> all : union_spans_) union_family_spans_.push_back(all.subspan(r.begin, r.size()));
      if (f == family::accelerate) {
        for (double*& shares : union_shares_) shares += brake_cells;
      }
      (f == family::brake ? mi.brake : mi.accelerate) =
          maneuverability_index_of_union(samples_.set(f), union_family_spans_, negative, r.begin, union_shares_);
    }
    return mi;
  }

  /// One pass of `union_indices` over the cells of family f, a grid row at a time on the words of
  /// the obstacles' sign masks; true when a value read was ≤ 0 where the obstacle's mask had the
  /// sample positive.
  bool read_union_cells(family f) {
    const displacement_set& set = samples_.set(f);
    if (set.degenerate) return false;  // counts signs only
    const std::size_t first = samples_.grid(f).begin;
    const std::size_t columns = set.curvature_count;
    const std::size_t rows = set.acceleration_count;
    const std::size_t count = union_parts_.size();
    bool flipped = false;
    const auto make_exact = [&](std::size_t p, std::size_t m) {
      const auto [j, i] = union_parts_[p];
      if (part_is_exact(j, i, m)) return;
      if (!(part_exact(j, i, m) > 0.0) && !union_negative_[p].test(m)) {
        flipped = true;
        union_negative_[p].set(m);
        negative_.set(m);
        positive_.reset(m);
      }
    };
    if (columns < 2 || columns > 64) {
      // Node by node: along one column (two corners a cell), or rows longer than a word.
      const std::size_t across = columns == 1 ? 1 : columns - 1;
      const std::size_t corners = columns == 1 ? 2 : 4;
      for (std::size_t ia = 0; ia + 1 < rows; ++ia) {
        for (std::size_t ik = 0; ik < across; ++ik) {
          const std::size_t lower = first + ia * columns + ik;
          const std::size_t upper = lower + columns;
          const std::array<std::size_t, 4> node =
              columns == 1 ? std::array<std::size_t, 4>{lower, upper, 0, 0}
                           : std::array<std::size_t, 4>{lower, lower + 1, upper + 1, upper};
          // Per obstacle, its corners ≤ 0 as bits (counter-clockwise).
          union_touching_.assign(count, 0);
          bool covered = false;
          for (std::size_t p = 0; p < count; ++p) {
            for (std::size_t q = 0; q < corners; ++q) union_touching_[p] |= union_negative_[p].test(node[q]) ? 1U << q : 0U;
            covered = covered || union_touching_[p] == (1U << corners) - 1;
          }
          if (covered) continue;
          for (std::size_t p = 0; p < count; ++p) {
            read_cell(p, static_cast<unsigned>(union_touching_[p]), corners, node, make_exact);
          }
        }
      }
      return flipped;
    }
    union_touching_.resize(count);
    for (std::size_t ia = 0; ia + 1 < rows; ++ia) {
      const std::uint64_t covered =
          union_row_cells(std::span(union_negative_).first(count), first, columns, ia, union_touching_);
      for (std::size_t p = 0; p < count; ++p) {
        std::uint64_t touched = union_touching_[p] & ~covered;
        if (touched == 0) continue;
        const std::uint64_t lower = union_negative_[p].bits(first + ia * columns, columns);
        const std::uint64_t upper = union_negative_[p].bits(first + (ia + 1) * columns, columns);
        while (touched != 0) {
          const auto ik = static_cast<std::size_t>(std::countr_zero(touched));
          touched &= touched - 1;
          // Counter-clockwise: (ia, ik), (ia, ik + 1), (ia + 1, ik + 1), (ia + 1, ik).
          const unsigned bits = static_cast<unsigned>(((lower >> ik) & 1U) | (((lower >> (ik + 1)) & 1U) << 1) |
                                                      (((upper >> (ik + 1)) & 1U) << 2) | (((upper >> ik) & 1U) << 3));
          const std::size_t at = first + ia * columns + ik;
          read_cell(p, bits, 4, {at, at + 1, at + columns + 1, at + columns}, make_exact);
        }
      }
    }
    return flipped;
  }

  /// Makes exact what obstacle p's part of a cell reads: the ends of its sign-changing edges, or
  /// every corner of a saddle. `negative` bit q is set when corner q (counter-clockwise) is ≤ 0.
  template <class MakeExact>
  static void read_cell(std::size_t p, unsigned negative, std::size_t corners, const std::array<std::size_t, 4>& node,
                        MakeExact&& make_exact) {
    if (corners == 4) {
      const cell_reads& reads = cell_read_table[negative];
      for (std::size_t r = 0; r < reads.count; ++r) make_exact(p, node[reads.corner[r]]);
      return;
    }
    const unsigned all = (1U << corners) - 1;
    if (negative == 0 || negative == all) return;
    for (std::size_t q = 0; q < corners; ++q) {
      const std::size_t next = (q + 1) % corners;
      if (((negative >> q) & 1U) != ((negative >> next) & 1U)) {
        make_exact(p, node[q]);
        make_exact(p, node[next]);
      }
    }
  }

  /// One obstacle that is not inert, obstacle j at forecast index i (`live`): replaces the
  /// placeholders (±cap) by its exact clearances wherever the interpolating indices read a value
  /// (`read_nodes`: both ends of every grid edge whose ends differ in sign, and saddle cells).
  /// Elsewhere a cell reads signs only (`positive_fraction`). A sample that overlaps the obstacle at
  /// no sample time but whose exact clearance is ≤ 0 (a contact between sample times) collides: its
  /// other neighbours are read in turn, until the boundary is where the exact values put it. `c`
  /// holds the signs of `positive_` (+cap there, −cap elsewhere), which follows the signs of the
  /// values made exact.
  void make_read_values_exact(std::pair<std::size_t, std::size_t> live, clearance_set& c) {
    const std::size_t j = live.first;
    const std::size_t i = live.second;
    const std::size_t size = c.size();
    valued_.clear(size);
    std::size_t positives = positive_.count();
    for (bool changed = true; changed;) {
      changed = false;
      if (positives == 0 || positives == size) return;  // one sign everywhere: nothing is read
      read_nodes(samples_, positive_, read_);
      read_.subtract(valued_);
      valued_ |= read_;
      read_.for_each([&](std::size_t m) {
        c[m] = part_exact(j, i, m);
        if (positive_.test(m) && !(c[m] > 0.0)) {
          positive_.reset(m);
          --positives;
          changed = true;
        }
      });
    }
  }

  /// The part index of the road constraint: one past the obstacles'.
  std::size_t road_part() const { return fields_.size(); }
  /// What the combination reads of part (j, i): obstacle j under forecast index i, or the road.
  bool part_collides(std::size_t j, std::size_t i) const {
    return j == road_part() ? road_->collides() : fields_[j].collides(i);
  }
  const sample_mask& part_collisions(std::size_t j, std::size_t i) const {
    return j == road_part() ? road_->collisions() : fields_[j].collisions(i);
  }
  std::span<const double> part_set(std::size_t j, std::size_t i) const {
    return j == road_part() ? road_->set() : fields_[j].set(i);
  }
  bool part_is_exact(std::size_t j, std::size_t i, std::size_t m) const {
    return j == road_part() ? road_->is_exact(m) : fields_[j].is_exact(i, m);
  }
  double part_exact(std::size_t j, std::size_t i, std::size_t m) {
    return j == road_part() ? road_->exact(m) : fields_[j].exact(i, m);
  }

  const maneuver_samples& samples_;
  bool reference_;
  std::vector<std::vector<clearance_set>> reference_sets_;
  std::vector<clearance_field> fields_;  ///< reserved for every obstacle first (`reserve_fields`): never moved
  std::optional<road_field> road_;       ///< fast path: the road constraint, when it binds
  std::optional<clearance_set> road_reference_;  ///< reference: the road constraint's ±1, when it binds
  std::unordered_map<std::vector<std::size_t>, double, index_hash> rooms_;  ///< keyed by the assignment (and `rough_key` when rough)
  std::unordered_map<std::array<std::size_t, 3>, double, index_hash> rooms_alone_;  ///< `room_alone`, keyed by (j, i, rough)
  std::unordered_map<std::vector<std::size_t>, double, index_hash> column_rooms_;  ///< the rooms of the map's column, keyed as `rooms_`
  std::unordered_map<std::vector<std::uint64_t>, double, index_hash> rough_rooms_;  ///< `rough_room`, keyed by the signs' words
  std::vector<std::uint64_t> scratch_words_;  ///< scratch of `rough_room`: the key
  static constexpr std::size_t rough_key = std::numeric_limits<std::size_t>::max();
  std::vector<std::pair<std::size_t, std::size_t>> scratch_parts_;  ///< buffers kept between calls
  std::vector<std::size_t> scratch_key_;
  std::vector<std::size_t> scratch_column_index_;
  clearance_set scratch_set_;
  sample_mask negative_;  ///< scratch of combined_parts: the samples of a sampled collision
  sample_mask positive_;  ///< the positive samples of the set combined last (`combined_parts`)
  sample_mask read_;      ///< scratch of make_read_values_exact: the samples whose values are read next
  sample_mask valued_;    ///< scratch of make_read_values_exact: the samples with their exact value
  std::vector<std::pair<std::size_t, std::size_t>> live_parts_;  ///< scratch of combined_parts: (j, i) not inert
  std::optional<maneuverability_pair> union_indices_;  ///< of the set combined last, when several obstacles are live
  std::vector<std::pair<std::size_t, std::size_t>> union_parts_;  ///< scratch of union_indices: (j, i) with a collision
  std::vector<std::span<const double>> union_spans_;             ///< their sets, every sample
  std::vector<std::span<const double>> union_family_spans_;      ///< their sets over one family's grid
  std::vector<sample_mask> union_negative_;  ///< their samples ≤ 0: the sampled collisions and the values read ≤ 0
  std::vector<std::uint64_t> union_touching_;  ///< scratch of read_union_cells: per obstacle, the cells (or corners) it is ≤ 0 at
  /// Per part (j << 32 | i): the safe share of each cell (brake's cells, then accelerate's) where it
  /// alone is ≤ 0 at a corner, NaN until a union needs it (`maneuverability_index_of_union`); its
  /// read values are exact and final, so the share is the same in every union.
  std::unordered_map<std::uint64_t, std::vector<double>> single_shares_;
  std::vector<double*> union_shares_;  ///< scratch of union_indices: single_shares_ of its parts, in their order
};

}  // namespace

bool planning_cache::holds(const ego_state& ego, double horizon, const sampling_resolution& resolution) const {
  return valid && speed == ego.speed && limits == ego.limits && radius == bounding_radius(ego.shape) &&
         horizon_ == horizon && resolution_.accelerations == resolution.accelerations &&
         resolution_.curvatures == resolution.curvatures;
}

void planning_cache::keep(const ego_state& ego, double horizon, const sampling_resolution& resolution) {
  valid = true;
  speed = ego.speed;
  limits = ego.limits;
  radius = bounding_radius(ego.shape);
  horizon_ = horizon;
  resolution_ = resolution;
}

plan_result run_pipeline(const plan_input& in, const pipeline_options& options, planning_cache* cache) {
  if (auto error = validation_error(in)) return invalid(std::move(*error));
  const planner_config& config = in.config;
  const ego_state& ego = in.ego;
  const std::vector<double> taus = forecast_times(config);
  const std::size_t tau_count = taus.size();

  plan_result result;
  result.forecast_times = taus;
  const maneuver nominal = clamp_to_limits(in.nominal, ego.speed, ego.limits);

  // Obstacles: estimate, keep those that can interact (the others cost nothing, spec §9).
  std::vector<forecast_obstacle> relevant;
  std::vector<std::size_t> relevant_track;
  for (std::size_t j = 0; j < in.obstacles.size(); ++j) {
    const obstacle_track& track = in.obstacles[j];
    obstacle_assessment assessment;
    assessment.id = track.id;
    assessment.motion = track.motion ? *track.motion : estimate_motion(track, config.history_window, in.time);
    assessment.time_to_collision = no_collision;
    const forecast_obstacle obstacle{assessment.motion, track.shape};
    assessment.relevant = can_interact(ego, obstacle, config);
    if (assessment.relevant) {
      relevant.push_back(obstacle);
      relevant_track.push_back(j);
    }
    result.obstacles.push_back(assessment);
  }
  const std::size_t n = relevant.size();

  collision_window window{config.displacement_horizon, config.collision_window, options.max_time_step,
                          config.safety_margin};
  for (std::size_t k = 0; k < n; ++k) {
    const double step = tunneling_time_step(ego, relevant[k], window);
    if (step < smallest_collision_time_step) {
      // Micrometre footprints or speeds far beyond any road user's: refused, rather than sampled
      // at millions of times (or more than a count holds).
      const std::size_t j = relevant_track[k];
      return invalid("obstacles[" + std::to_string(j) + "] (id " + std::to_string(in.obstacles[j].id) +
                     "): the collision time step the tunneling bound of spec §5 needs with it is " +
                     number_text(step, 3) + " s; expected at least " + number_text(smallest_collision_time_step, 3) +
                     " s: footprints of road users (not of micrometres) and speeds of road users (the ego's top "
                     "speed and the obstacle's estimated speed add up to " +
                     number_text(tunneling_relative_speed(ego, relevant[k], window), 3) + " m/s)");
    }
    window.time_step = std::min(window.time_step, step);
  }
  // The road constraint (spec §5) binds an ego that starts on the drivable area; its footprint must
  // not pass over a boundary segment between two sample times.
  const drivable_area* road =
      in.drivable_area && starts_on_drivable_area(*in.drivable_area, ego) ? in.drivable_area.get() : nullptr;
  result.on_drivable_area = road != nullptr;
  if (road != nullptr) {
    const double step = road_time_step(ego, window);
    if (step < smallest_collision_time_step) {
      return invalid("ego: the collision time step the road constraint needs (its smallest dimension over its top "
                     "speed) is " + number_text(step, 3) + " s; expected at least " +
                     number_text(smallest_collision_time_step, 3) + " s: a footprint and a speed of a road user");
    }
    window.time_step = std::min(window.time_step, step);
  }
  window.time_step = std::min(window.time_step, config.collision_window);
  result.collision_time_step = window.time_step;
  // The tunneling bound can shorten the step below config.max_time_step: the pairs held stay bounded.
  if (const double maneuvers = sampled_maneuver_count(options.resolution),
      times = sample_time_count(config.collision_window, window.time_step);
      maneuvers * times > largest_sample_time_pairs) {
    return invalid("config.collision_window = " + number_text(config.collision_window, 3) +
                   " s at the collision time step of " + number_text(window.time_step, 3) +
                   " s the tunneling bound of spec §5 needs with the relevant obstacles: " + number_text(times, 3) +
                   " sample times for " + number_text(maneuvers, 3) +
                   " sampled maneuvers exceed the 5e8 pairs a planning step may hold; expected a shorter window, "
                   "a coarser resolution, or road users that are larger or slower");
  }

  if (n == 0 && road == nullptr && !options.reference && !config.record_samples) {
    // Nothing can reach the ego: every index is 1 and the nominal maneuver is safe (spec §9: far
    // obstacles cost nothing). The same result as the general path, without sampling anything.
    result.time_to_collision = no_collision;
    if (config.map_column) {
      result.mi_brake.assign(tau_count, 1.0);
      result.mi_accelerate.assign(tau_count, 1.0);
    }
    result.excluded = excluded_forecast_times(taus, result.time_to_collision);
    result.selected_family = select_family(1.0, 1.0);
    if (config.policy.kind == forecast_policy_kind::constant) {
      result.forecast_index = constant_forecast_index(taus, config.policy.constant_forecast_time, result.excluded);
    } else if (config.policy.kind == forecast_policy_kind::robust) {
      result.robust = true;  // as the general path: safe under every forecast time
      result.forecast_index = tau_count - 1;
    }
    result.forecast_time = taus[result.forecast_index];
    result.command = nominal;
    result.mode = planning_mode::nominal;
    return result;
  }

  // TTC per obstacle (spec §6): obstacle j may be forecast with τ_i ≤ TTC_j (and always τ_0 = 0).
  std::vector<double> ttc(n, no_collision);
  for (std::size_t j = 0; j < n; ++j) {
    ttc[j] = time_to_collision(ego, nominal, relevant[j], window);
    result.obstacles[relevant_track[j]].time_to_collision = ttc[j];
  }
  result.time_to_collision = n == 0 ? no_collision : *std::min_element(ttc.begin(), ttc.end());
  result.excluded = excluded_forecast_times(taus, result.time_to_collision);
  assignment_problem problem;
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<std::size_t> allowed;
    allowed.reserve(tau_count);
    for (std::size_t i = 0; i < tau_count; ++i) {
      if (i == 0 || taus[i] <= ttc[j]) allowed.push_back(i);
    }
    problem.candidates.push_back(std::move(allowed));
  }
  // The obstacles by their TTC, the soonest first (ties in input order): the order in which u_nom is
  // proven against each alone, where the first that fails ends the proof.
  std::vector<std::size_t> by_urgency(n);
  for (std::size_t j = 0; j < n; ++j) by_urgency[j] = j;
  std::stable_sort(by_urgency.begin(), by_urgency.end(), [&](std::size_t x, std::size_t y) { return ttc[x] < ttc[y]; });
  // A command must keep to the road over the whole of [0, T_h], not only at the sample times.
  const auto on_road = [&](const maneuver& u) {
    if (road == nullptr) return true;
    return options.reference ? stays_on_drivable_area_reference(*road, ego, u, window, verification_resolution)
                             : stays_on_drivable_area(*road, ego, u, window, verification_resolution);
  };

  if (config.decision_only && !whole_column_wanted(config, options) &&
      options.assignment_search == assignment_search_kind::coordinate_ascent &&
      verified_with_each_under_every_forecast(ego, nominal, relevant, problem.candidates, taus, by_urgency, window,
                                              false, proof_steps::speed_bound) &&
      on_road(nominal)) {
    // u_nom is proven safe with each obstacle under each of its forecast times: rule 1 (spec §8) applies
    // it under whatever assignment the indices would select (`nominal_free` proves it there), so the
    // command and mode are those of the full step; no index is computed.
    result.indices_computed = false;
    result.command = nominal;
    result.mode = planning_mode::nominal;
    result.work.relevant_obstacles = n;
    return result;
  }

  // The fast indices read only the weights of the cells between nodes; the reference counts nodes,
  // and the end points are only drawn (`record_samples`).
  const bool full_samples = options.reference || config.record_samples;
  // A planner's cache keeps the sampled sets (and the sweep built on them) while the ego's speed,
  // limits and footprint radius, the horizon and the resolution stay the same; only the
  // nominal-curvature columns change. Everything is then what sampling anew would give, bit for bit.
  const bool reuse = cache != nullptr && !full_samples;
  std::optional<maneuver_samples> fresh;
  if (reuse) {
    if (cache->holds(ego, config.displacement_horizon, options.resolution)) {
      set_nominal_curvature(cache->samples, ego, nominal.curvature, config.displacement_horizon, false);
    } else {
      // Sampled again; the sweep on them keeps its tree of blocks when only the speed changed
      // (`ego_sweep::restart`, checked below).
      cache->samples =
          sample_maneuvers(ego, nominal.curvature, config.displacement_horizon, options.resolution, false, false);
      cache->keep(ego, config.displacement_horizon, options.resolution);
    }
  } else {
    fresh = sample_maneuvers(ego, nominal.curvature, config.displacement_horizon, options.resolution, full_samples,
                             full_samples);
  }
  const maneuver_samples& samples = reuse ? cache->samples : *fresh;
  evaluator evaluate(samples, options.reference);
  std::optional<clearance_field::raster_scratch> own_raster;
  clearance_field::raster_scratch& raster = reuse ? cache->raster : own_raster.emplace();

  const bool constant_policy = config.policy.kind == forecast_policy_kind::constant;
  std::vector<std::size_t> assignment(n, 0);
  if (constant_policy) {
    const auto fixed = static_cast<std::size_t>(std::lround(config.policy.constant_forecast_time / config.forecast_step));
    for (std::size_t j = 0; j < n; ++j) {
      const auto& c = problem.candidates[j];
      assignment[j] = *std::prev(std::upper_bound(c.begin(), c.end(), fixed));  // capped at TTC_j
    }
  }

  // Which forecast times are evaluated: every one for the map's column; otherwise only those the
  // decision reads — the constant policy's (capped at TTC), or every obstacle's candidates under
  // ADJ. Each evaluated set is the same, bit for bit, whichever others are evaluated.
  const bool whole_column = whole_column_wanted(config, options);
  std::vector<std::uint8_t> wanted;
  const auto wanted_of = [&](std::size_t j) -> std::span<const std::uint8_t> {
    if (whole_column) return {};
    wanted.assign(tau_count, 0);
    if (constant_policy) {
      wanted[assignment[j]] = 1;
    } else {
      for (const std::size_t i : problem.candidates[j]) wanted[i] = 1;
    }
    return wanted;
  };

  // Clearances per obstacle and forecast time (spec §5).
  std::optional<ego_sweep> own_sweep;
  const ego_sweep* sweep = nullptr;
  if (!options.reference && (n > 0 || road != nullptr)) {
    if (!reuse) {
      sweep = &own_sweep.emplace(ego, samples, window);
    } else if (cache->sweep && cache->sweep->try_restart(ego, window)) {
      sweep = &*cache->sweep;
    } else {
      sweep = &cache->sweep.emplace(ego, samples, window);
    }
  }
  if (!options.reference) evaluate.reserve_fields(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (options.reference) {
      std::vector<clearance_set> sets;
      for (const sample_mask& mask : collision_sets_reference(ego, samples, relevant[j], taus, window, options.proof_resolution)) {
        clearance_set c(samples.size());
        for (std::size_t m = 0; m < c.size(); ++m) c[m] = mask.test(m) ? -1.0 : 1.0;
        sets.push_back(std::move(c));
      }
      evaluate.add_reference(std::move(sets));
    } else {
      evaluate.add_field(*sweep, relevant[j], taus, wanted_of(j), raster);
    }
  }
  if (road != nullptr) {
    if (options.reference) {
      clearance_set set = road_clearances_reference(*road, ego, samples.maneuvers, window, clearance_cap);
      for (double& c : set) c = c > 0.0 ? 1.0 : -1.0;
      evaluate.add_road_reference(std::move(set));
    } else {
      evaluate.add_road(*sweep, *road);
    }
  }

  // The map column: every obstacle forecast with τ_i (spec §6). When no obstacle's clearances
  // depend on its forecast time (none turns, or those that do cannot come near), every τ_i gives
  // the same set, bit for bit: it is computed once. Without the map, ADJ with one obstacle still
  // needs the indices of the forecast times it may select.
  // The column's combined sets themselves are kept only to be drawn (`record_samples`).
  const bool keep_columns = whole_column && config.record_samples;
  std::vector<clearance_set> clearance_by_forecast;
  if (keep_columns) clearance_by_forecast.reserve(tau_count);
  const bool column_constant = !options.reference && !evaluate.depends_on_forecast_time();
  const bool adjustable_alone = !constant_policy && n == 1;
  std::vector<double> mi_brake;
  std::vector<double> mi_accelerate;
  if (whole_column || adjustable_alone) {
    std::optional<maneuverability_pair> first;
    for (std::size_t i = 0; i < tau_count; ++i) {
      if (!whole_column && result.excluded[i] != 0) {
        mi_brake.push_back(0.0);  // never read: excluded from selection
        mi_accelerate.push_back(0.0);
        continue;
      }
      maneuverability_pair mi;
      if (column_constant && first) {
        if (keep_columns) clearance_by_forecast.push_back(clearance_by_forecast.back());
        mi = *first;
      } else {
        clearance_set& c = keep_columns ? clearance_by_forecast.emplace_back() : evaluate.scratch_column();
        mi = evaluate.column(i, c);
        first = mi;
      }
      mi_brake.push_back(mi.brake);
      mi_accelerate.push_back(mi.accelerate);
    }
  }
  if (whole_column) {
    result.mi_brake = mi_brake;  // copies: ADJ below still reads them
    result.mi_accelerate = mi_accelerate;
  }

  // Spec §8 rules 1–3 on the samples outside `unsafe`, family `f` first, each candidate (the
  // nominal maneuver first) passing `verify`: collision-free in continuous time, not only at the
  // sample times, since a minimal-effort choice lies at the edge of the safe set, where a corner can
  // clip between samples (docs/method.md §4.5). Proven by the speed bound first, which keeps a few
  // centimetres more than the margin from the forecasts; only when no candidate passes, again with
  // the translation bound, which proves passes down to the margin; nothing when neither does.
  using verifier = std::function<bool(const maneuver&, proof_steps)>;
  const auto choose = [&](const sample_mask& unsafe, family f, const verifier& verify, const verifier& verify_nominal) {
    choice_input choice;
    choice.samples = &samples;
    choice.colliding = &unsafe;
    choice.selected_family = f;
    choice.nominal = nominal;
    choice.initial_speed = ego.speed;
    choice.weights = config.effort;
    choice.urgent_steering = config.urgent_steering;
    std::optional<maneuver_decision> decision;
    for (const proof_steps stepping : {proof_steps::speed_bound, proof_steps::translation_bound}) {
      choice.verify = [&verify, stepping](const maneuver& u) { return verify(u, stepping); };
      choice.nominal_safe = verify_nominal(nominal, stepping);
      decision = choose_maneuver(choice);
      if (decision) break;
    }
    return decision;
  };

  // The robust policy (docs/method.md, "The robust policy"): the maneuvers safe with every obstacle
  // under each of its non-excluded forecast times, one set; ADJ below when none of them is safe and
  // verified. An obstacle whose forecast does not depend on τ (fast path: inert or not turning)
  // counts once.
  sample_mask colliding;
  bool robust_decided = false;
  if (config.policy.kind == forecast_policy_kind::robust) {
    std::vector<std::pair<std::size_t, std::size_t>> parts;
    for (std::size_t j = 0; j < n; ++j) {
      if (!evaluate.forecast_matters(j)) {
        parts.emplace_back(j, 0);
        continue;
      }
      for (const std::size_t i : problem.candidates[j]) parts.emplace_back(j, i);
    }
    const clearance_set every = evaluate.combined_of(parts);
    const sample_mask robust_colliding = evaluate.colliding(every);
    const maneuverability_pair mi = evaluate.indices(every);
    const family robust_family = select_family(mi.brake, mi.accelerate);
    const auto under_every_forecast = [&](const maneuver& u, proof_steps stepping) {
      return verified_under_every_forecast(ego, u, relevant, problem.candidates, taus, window, options.reference,
                                           stepping) &&
             on_road(u);
    };
    // u_nom also by each obstacle alone under each of its forecast times, as `decision_only` proves it
    // (with one obstacle these are the proofs above).
    const auto nominal_under_every_forecast = [&](const maneuver& u, proof_steps stepping) {
      return (verified_under_every_forecast(ego, u, relevant, problem.candidates, taus, window, options.reference,
                                            stepping) ||
              (n > 1 && verified_with_each_under_every_forecast(ego, u, relevant, problem.candidates, taus, by_urgency,
                                                                window, options.reference, stepping))) &&
             on_road(u);
    };
    if (const auto decision = choose(robust_colliding, robust_family, under_every_forecast, nominal_under_every_forecast)) {
      robust_decided = true;
      colliding = robust_colliding;
      result.robust = true;
      result.command = decision->command;
      result.mode = decision->mode;
      result.mi_brake_selected = mi.brake;
      result.mi_accelerate_selected = mi.accelerate;
      result.selected_family = robust_family;
      for (std::size_t j = 0; j < n; ++j) {
        result.obstacles[relevant_track[j]].forecast_index = problem.candidates[j].back();
      }
      if (n == 0) {
        result.forecast_index = tau_count - 1;  // nothing to exclude: safe under every forecast time
      } else {
        const auto most_urgent = static_cast<std::size_t>(std::min_element(ttc.begin(), ttc.end()) - ttc.begin());
        result.forecast_index = problem.candidates[most_urgent].back();
      }
      result.forecast_time = taus[result.forecast_index];
    }
  }

  if (!robust_decided) {
    // Forecast times (spec §7, §9).
    // The fast search climbs by rough rooms (signs only) and ranks the best of what it met by their
    // rooms; the exhaustive one, the reference, by the rooms alone.
    problem.room = [&](std::span<const std::size_t> index) { return evaluate.room_of(index, false); };
    if (!options.reference) {
      problem.rough_room = [&](std::span<const std::size_t> index) { return evaluate.room_of(index, true); };
      problem.rough_room_alone = [&](std::size_t j, std::size_t i) { return evaluate.room_alone(j, i, true); };
    }
    problem.room_alone = [&](std::size_t j, std::size_t i) { return evaluate.room_alone(j, i, false); };

    if (constant_policy) {
      // The assignment is fixed above.
    } else if (n == 1) {
      assignment[0] = adjustable_forecast_index(mi_brake, mi_accelerate, result.excluded);
    } else if (n > 1) {
      if (options.assignment_search == assignment_search_kind::exhaustive) {
        // An obstacle that does not turn (ω = 0) has the same forecast under every τ: assignments that
        // differ only in its forecast time have the same room, and the tie rule (the smallest index
        // vector) puts it at τ = 0. Searching that alone gives the same result (eight pedestrians:
        // one assignment instead of 17⁸).
        for (std::size_t j = 0; j < n; ++j) {
          if (relevant[j].motion.yaw_rate == 0.0) problem.candidates[j] = {0};
        }
        const std::size_t count = assignment_count(problem);
        if (count > config.max_exhaustive_assignments) {
          return invalid("config.max_exhaustive_assignments = " + std::to_string(config.max_exhaustive_assignments) +
                         ": the exhaustive forecast-time search over " + std::to_string(n) + " obstacles needs " +
                         std::to_string(count) + " assignments; raise the limit or use the coordinate-ascent search");
        }
        assignment = exhaustive_assignment_search(problem).forecast_index;
      } else {
        // An obstacle that collides with no maneuver under any of its forecast times leaves the safe
        // sets (spec §9), and every room (each obstacle is interpolated on its own, and one without a
        // collision is not read), the same whatever its forecast time: the fast search holds it at τ = 0.
        // So does an obstacle that does not turn, whose clearances are the same under every forecast
        // time: τ = 0 is where the exhaustive search's tie rule (the smallest index vector) puts it.
        for (std::size_t j = 0; j < n; ++j) {
          if (!evaluate.forecast_matters(j) || !evaluate.collides_under_any(j, problem.candidates[j])) {
            problem.candidates[j] = {0};
          }
        }
        assignment = coordinate_ascent_assignment_search(problem).forecast_index;
      }
    }
    const clearance_set assigned = evaluate.combined(assignment);
    colliding = evaluate.colliding(assigned);
    const maneuverability_pair selected = evaluate.indices(assigned);
    result.mi_brake_selected = selected.brake;
    result.mi_accelerate_selected = selected.accelerate;
    result.selected_family = select_family(selected.brake, selected.accelerate);
    if (n > 0) {
      const auto most_urgent = static_cast<std::size_t>(std::min_element(ttc.begin(), ttc.end()) - ttc.begin());
      result.forecast_index = assignment[most_urgent];
    } else if (config.policy.kind == forecast_policy_kind::constant) {
      result.forecast_index = constant_forecast_index(taus, config.policy.constant_forecast_time, result.excluded);
    }
    result.forecast_time = taus[result.forecast_index];
    for (std::size_t j = 0; j < n; ++j) result.obstacles[relevant_track[j]].forecast_index = assignment[j];

    // The maneuver (spec §8).
    std::vector<double> assigned_tau(n);
    for (std::size_t j = 0; j < n; ++j) assigned_tau[j] = taus[assignment[j]];
    const auto with_all = [&](const maneuver& u, proof_steps stepping) {
      return options.reference ? verified_collision_free_reference(ego, u, relevant, assigned_tau, window,
                                                                   verification_resolution, stepping)
                               : verified_collision_free(ego, u, relevant, assigned_tau, window,
                                                         verification_resolution, stepping);
    };
    const auto assigned_free = [&](const maneuver& u, proof_steps stepping) { return with_all(u, stepping) && on_road(u); };
    // u_nom (rule 1) by the proof with all obstacles at once or by one with each alone: the second is
    // what `decision_only` proves under every assignment, so that its shortcut decides as this does
    // (with one obstacle the two are the same proof).
    const auto nominal_free = [&](const maneuver& u, proof_steps stepping) {
      return (with_all(u, stepping) ||
              (n > 1 && verified_with_each(ego, u, relevant, assigned_tau, window, options.reference, stepping))) &&
             on_road(u);
    };
    if (const auto decision = choose(colliding, result.selected_family, assigned_free, nominal_free)) {
      result.command = decision->command;
      result.mode = decision->mode;
    } else {
      std::vector<double> first_collision;
      if (options.reference) {
        first_collision = first_collision_times(ego, samples.maneuvers, relevant, assigned_tau, window);
      } else {
        // When each maneuver first overlaps an obstacle, from the raster of each obstacle's assigned
        // forecast time (the collisions' own test, recorded when it hits).
        first_collision.assign(samples.size(), no_collision);
        for (std::size_t j = 0; j < n; ++j) {  // n > 0: there is a sweep
          std::vector<std::uint8_t> only(tau_count, 0);
          only[assignment[j]] = 1;
          const clearance_field field(*sweep, relevant[j], taus, clearance_cap, only, raster,
                                      clearance_field::recording::first_overlaps);
          for (std::size_t m = 0; m < samples.size(); ++m) {
            first_collision[m] = std::min(first_collision[m], field.first_overlap(assignment[j], m));
          }
        }
      }
      // The maneuvers the first two keys leave tied (the latest first collision, the strongest
      // braking among those: every maneuver of that acceleration once the ego is inside the margin)
      // are run against the obstacles' bodies alone, without the margin, for the third key.
      const double latest = *std::max_element(first_collision.begin(), first_collision.end());
      double hardest = std::numeric_limits<double>::infinity();
      for (std::size_t m = 0; m < samples.size(); ++m) {
        if (first_collision[m] == latest) hardest = std::min(hardest, samples.maneuvers[m].acceleration);
      }
      std::vector<std::size_t> tied;
      std::vector<maneuver> contenders;
      for (std::size_t m = 0; m < samples.size(); ++m) {
        if (first_collision[m] == latest && samples.maneuvers[m].acceleration == hardest) {
          tied.push_back(m);
          contenders.push_back(samples.maneuvers[m]);
        }
      }
      std::vector<double> first_contact(samples.size(), no_collision);
      if (tied.size() > 1) {
        collision_window bodies = window;
        bodies.margin = 0.0;
        const std::vector<double> contact = first_collision_times(ego, contenders, relevant, assigned_tau, bodies);
        for (std::size_t k = 0; k < tied.size(); ++k) first_contact[tied[k]] = contact[k];
      }
      const maneuver_decision last_resort =
          near_crash_maneuver(samples, first_collision, first_contact, nominal.curvature);
      result.command = last_resort.command;
      result.mode = last_resort.mode;
    }
  }

  result.work.relevant_obstacles = n;
  evaluate.add_work(result.work);

  if (config.record_samples) {
    sample_snapshot snapshot;
    snapshot.maneuvers = samples.maneuvers;
    snapshot.families = samples.families;
    snapshot.area_weights = samples.area_weights;
    const std::size_t first_column = samples.nominal_column(family::brake).begin;
    for (std::size_t m = 0; m < samples.size(); ++m) {
      snapshot.end_points.push_back(to_world(ego.pose, samples.end_points[m]));
      snapshot.on_nominal_curvature.push_back(m >= first_column ? 1 : 0);
      snapshot.safe_selected.push_back(colliding.test(m) ? 0 : 1);
    }
    for (const clearance_set& c : clearance_by_forecast) {
      std::vector<std::uint8_t> safe(samples.size());
      for (std::size_t m = 0; m < samples.size(); ++m) safe[m] = c[m] > 0.0 ? 1 : 0;
      snapshot.safe_by_forecast.push_back(std::move(safe));
    }
    result.samples = std::move(snapshot);
  }
  return result;
}

}  // namespace mm::detail
