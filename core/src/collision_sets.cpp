#include "mm/collision_sets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

#include "mm/interval_separation.hpp"

namespace mm {
namespace {

/// Calls `visit` on the indices of [lo, hi) where a maximum over an extent can be: over an ascending
/// range each of the extents' maxima is at one of its ends (the rounded differences and magnitudes
/// are monotonic on either side of the centre), so two instead of all.
template <class Visit>
void for_extremes(bool ascending, std::size_t lo, std::size_t hi, Visit&& visit) {
  if (ascending) {
    visit(lo);
    visit(hi - 1);
  } else {
    for (std::size_t i = lo; i < hi; ++i) visit(i);
  }
}

}  // namespace


double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window) {
  const placement e = maneuver_placement(ego.pose, unit_vector(ego.pose.heading), ego.speed, u, t, window.horizon,
                                         ego.limits.speed_cap);
  return signed_distance(place(ego.shape, e.position, e.direction),
                         place(obstacle.shape, forecast_pose(obstacle.motion, tau, t))) -
         window.margin;
}

std::vector<ego_sweep::grid_view> ego_sweep::grids_of(const maneuver_samples& samples) {
  // The two families' grids stacked by acceleration (they share their curvatures).
  const displacement_set& brake = samples.brake;
  const displacement_set& accelerate = samples.accelerate;
  const index_range brake_grid = samples.grid(family::brake);
  const index_range accelerate_grid = samples.grid(family::accelerate);
  const auto rows_of = [&](const displacement_set& set, std::size_t first, std::size_t stride, grid_view& g) {
    for (std::size_t ia = 0; ia < set.acceleration_count; ++ia) {
      g.row_start.push_back(first + ia * stride);
      g.accelerations.push_back(samples.maneuvers[first + ia * stride].acceleration);
      g.shape_accelerations.push_back(evenly_spaced_acceleration(set, ia));
    }
  };
  const auto curvatures_of = [&](std::size_t first, std::size_t count) {
    std::vector<double> k;
    for (std::size_t j = 0; j < count; ++j) k.push_back(samples.maneuvers[first + j].curvature);
    return k;
  };
  std::vector<grid_view> grids;
  if (brake_grid.size() > 0 && accelerate_grid.size() > 0 &&
      curvatures_of(brake_grid.begin, brake.curvature_count) ==
          curvatures_of(accelerate_grid.begin, accelerate.curvature_count)) {
    grid_view both;
    rows_of(brake, brake_grid.begin, brake.curvature_count, both);
    rows_of(accelerate, accelerate_grid.begin, accelerate.curvature_count, both);
    both.curvatures = curvatures_of(brake_grid.begin, brake.curvature_count);
    grids.push_back(std::move(both));
  } else {
    for (const displacement_set* set : {&brake, &accelerate}) {
      const index_range r = samples.grid(set->fam);
      if (r.size() == 0) continue;
      grid_view g;
      rows_of(*set, r.begin, set->curvature_count, g);
      g.curvatures = curvatures_of(r.begin, set->curvature_count);
      grids.push_back(std::move(g));
    }
  }
  for (grid_view& g : grids) {
    g.ascending = std::is_sorted(g.accelerations.begin(), g.accelerations.end()) &&
                  std::is_sorted(g.curvatures.begin(), g.curvatures.end());
  }
  return grids;
}

bool ego_sweep::same_shape(const std::vector<grid_view>& a, const std::vector<grid_view>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t g = 0; g < a.size(); ++g) {
    if (a[g].row_start != b[g].row_start || a[g].curvatures.size() != b[g].curvatures.size() ||
        a[g].ascending != b[g].ascending || a[g].shape_accelerations != b[g].shape_accelerations) {
      return false;
    }
  }
  return true;
}

ego_sweep::ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window)
    : ego_(ego), samples_(samples), window_(window), sample_count_(samples.size()) {
  ego_radius_ = bounding_radius(ego.shape);
  grids_ = grids_of(samples);
  order_.reserve(sample_count_);
  blocks_.reserve(2 * sample_count_);
  for (std::size_t g = 0; g < grids_.size(); ++g) roots_.push_back(add_block(grids_[g], g, 0, grids_[g].row_start.size(), 0, grids_[g].curvatures.size()));
  grid_blocks_ = blocks_.size();
  grid_order_ = order_.size();
  grid_roots_ = roots_.size();
  start(ego, window, start_kind::fresh);
}

bool ego_sweep::try_restart(const ego_state& ego, const collision_window& window) {
  if (!(ego.limits == ego_.limits) || bounding_radius(ego.shape) != ego_radius_ || window.horizon != window_.horizon ||
      samples_.size() != sample_count_) {
    return false;
  }
  // The tree's shape does not depend on the speed (`add_block` splits by the shape accelerations)
  // as long as the grids keep their rows and columns: another resolution of as many samples (4 × 5
  // and 6 × 3 per family, with their nominal-curvature columns) needs a new tree, at any speed.
  std::vector<grid_view> grids = grids_of(samples_);
  if (!same_shape(grids, grids_)) return false;
  if (ego.speed == ego_.speed) {
    // The same speed, limits, horizon and grids: the same samples, whose placements are kept.
    start(ego, window, start_kind::same_speed);
    return true;
  }
  // Sampled again at a new speed: the blocks' curvature extents are taken anew, and where the
  // rows' accelerations moved too (a slow ego's rows follow the arc length,
  // `available_displacements`), all their extents.
  bool rows_moved = false;
  for (std::size_t g = 0; g < grids.size(); ++g) rows_moved = rows_moved || grids[g].accelerations != grids_[g].accelerations;
  grids_ = std::move(grids);
  // A block not looked at since an earlier restart keeps what that one made stale.
  const std::uint8_t now_stale = rows_moved ? stale_all : stale_curvatures;
  for (std::size_t b = 0; b < grid_blocks_; ++b) stale_extents_[b] = std::max(stale_extents_[b], now_stale);
  start(ego, window, rows_moved ? start_kind::new_rows : start_kind::new_speed);
  return true;
}

void ego_sweep::restart(const ego_state& ego, const collision_window& window) {
  if (!try_restart(ego, window)) {
    throw std::invalid_argument(
        "ego_sweep::restart: the limits, footprint radius, horizon, sample count or grids' shape differ");
  }
}

void ego_sweep::start(const ego_state& ego, const collision_window& window, start_kind kind) {
  // The placements in the ego's frame depend only on the speed, the samples and the sample times
  // (those of the previous start's window): a restart at the same speed with the same times keeps
  // them, except the nominal-curvature columns' (rewritten).
  const bool same_times = kind == start_kind::same_speed && window.time_step == window_.time_step &&
                          window.duration == window_.duration;
  ego_ = ego;
  window_ = window;
  times_ = sample_times(window.duration, window.time_step);
  start_rotation_ = unit_vector(ego.pose.heading);
  const double horizon = window.horizon;
  const double cap = ego.limits.speed_cap;
  if (!straight_) straight_ = std::make_unique_for_overwrite<straight_part[]>(sample_count_);
  // At the same speed the grids' straight parts in the ego's frame are kept; only their placement in
  // the world is new.
  if (kind == start_kind::same_speed && straight_known_.size() == sample_count_) {
    const std::size_t grids = samples_.brake.samples.size() + samples_.accelerate.samples.size();
    for (std::size_t m = 0; m < sample_count_; ++m) {
      straight_known_[m] = m < grids && straight_known_[m] != unknown ? local_only : unknown;
    }
  } else {
    straight_known_.assign(sample_count_, unknown);
  }
  // The grids' samples come first and do not change on a restart at the same speed; the
  // nominal-curvature columns follow.
  const std::size_t kept = kind == start_kind::same_speed ? samples_.brake.samples.size() + samples_.accelerate.samples.size() : 0;
  sample_speed_.resize(kept);
  sample_point_speed_.resize(kept);
  sample_speed_.reserve(sample_count_);
  sample_point_speed_.reserve(sample_count_);
  for (std::size_t m = kept; m < sample_count_; ++m) {
    const maneuver& u = samples_.maneuvers[m];
    const double v = mm::largest_speed(ego, u, horizon);
    sample_speed_.push_back(v);
    sample_point_speed_.push_back(mm::largest_point_speed(v, u.curvature, ego_radius_));
  }
  time_count_ = times_.size();
  const std::size_t placements = times_.size() * sample_count_;
  if (same_times) {
    std::fill(local_known_.begin() + static_cast<std::ptrdiff_t>(placement_index(0, kept)), local_known_.end(), 0);
  } else {
    if (local_known_.size() != placements || local_generation_ == std::numeric_limits<std::uint8_t>::max()) {
      local_known_.assign(placements, 0);
      local_generation_ = 0;
      local_ = std::make_unique_for_overwrite<stored[]>(placements);
    }
    ++local_generation_;
  }
  if (ordered_known_.size() != placements || ordered_.size() != times_.size() ||
      ordered_generation_ == std::numeric_limits<std::uint8_t>::max()) {
    ordered_known_.assign(placements, 0);
    ordered_generation_ = 0;
    ordered_.clear();
    ordered_.resize(times_.size());
  }
  ++ordered_generation_;
  // The arc lengths' rows: the grids' are kept at the same speed (their samples are), the
  // nominal-curvature columns' found anew, and their cached arc lengths forgotten.
  if (kind == start_kind::same_speed && travel_row_.size() == sample_count_) {
    assign_travel_rows(kept);
  } else {
    assign_travel_rows(0);
    grid_travel_rows_ = 0;
    const std::size_t grids = samples_.brake.samples.size() + samples_.accelerate.samples.size();
    for (std::size_t m = 0; m < grids && m < sample_count_; ++m) {
      grid_travel_rows_ = std::max<std::size_t>(grid_travel_rows_, travel_row_[m] + 1);
    }
  }
  const std::size_t travel_size = row_acceleration_.size() * time_count_;
  if (travel_known_.size() != travel_size || local_generation_ == 1) {
    // New rows, or the stamps began again: nothing cached is valid under the new stamp.
    travel_known_.assign(travel_size, 0);
    travel_.resize(travel_size);
  } else {
    std::fill(travel_known_.begin() + static_cast<std::ptrdiff_t>(grid_travel_rows_ * time_count_), travel_known_.end(), 0);
  }
  largest_speed_ = speed_after(ego.speed, ego.limits.max_acceleration, horizon, cap);
  largest_point_speed_ = largest_speed_ * (1.0 + max_curvature(ego.speed, ego.limits) * ego_radius_);
  // Every sample's reference point lies within its arc length of the start, and no sample travels
  // farther than the one at a_max.
  reach_radius_.clear();
  reach_radius_.reserve(times_.size());
  for (const double t : times_) {
    double travel = travelled_distance(ego.speed, ego.limits.max_acceleration, std::min(t, horizon), cap);
    if (t > horizon) travel += largest_speed_ * (t - horizon);
    reach_radius_.push_back(travel * (1.0 + 1e-12) + 1e-9);
  }
  straight_reach_ = {travelled_distance(ego.speed, ego.limits.max_acceleration, horizon, cap) * (1.0 + 1e-12) + 1e-9,
                     largest_speed_ * (1.0 + 1e-12)};
  // The nominal-curvature columns' blocks, after the grids' (which depend only on what `restart`
  // requires to be unchanged, and the grids' values). Their shape and accelerations are the
  // families' acceleration nodes, which a restart keeps unless the rows moved (`try_restart`): it
  // takes only their one curvature anew (a single column: no curvature spread, the largest |κ| is
  // |κ_nom|).
  if (kind != start_kind::fresh && kind != start_kind::new_rows && blocks_.size() > grid_blocks_) {
    const double curvature = std::abs(samples_.nominal_curvature);
    for (std::size_t b = grid_blocks_; b < blocks_.size(); ++b) blocks_[b].largest_curvature = curvature;
  } else {
    blocks_.resize(grid_blocks_);
    ranges_.resize(grid_blocks_);
    order_.resize(grid_order_);
    roots_.resize(grid_roots_);
    grid_view nominal;
    for (const family f : {family::brake, family::accelerate}) {
      const index_range r = samples_.nominal_column(f);
      const displacement_set& set = f == family::brake ? samples_.brake : samples_.accelerate;
      for (std::size_t m = r.begin; m < r.end; ++m) {
        nominal.row_start.push_back(m);
        nominal.accelerations.push_back(samples_.maneuvers[m].acceleration);
        nominal.shape_accelerations.push_back(evenly_spaced_acceleration(set, m - r.begin));
      }
    }
    if (!nominal.row_start.empty()) {
      nominal.curvatures = {samples_.nominal_curvature};
      nominal.ascending = std::is_sorted(nominal.accelerations.begin(), nominal.accelerations.end());
      roots_.push_back(add_block(nominal, grids_.size(), 0, nominal.row_start.size(), 0, 1));
    }
  }
  stale_extents_.resize(blocks_.size(), 0);
  straight_spread_.resize(blocks_.size());
  straight_spread_known_.assign(blocks_.size(), 0);
}

void ego_sweep::fill_extents(const grid_view& grid, const block_range& r, block& b) {
  const std::size_t rc = (r.r0 + r.r1 - 1) / 2;
  const std::size_t cc = (r.c0 + r.c1 - 1) / 2;
  b.centre = static_cast<std::uint32_t>(grid.sample(rc, cc));
  const double a_centre = grid.accelerations[rc];
  b.acceleration_spread = 0.0;
  b.top_acceleration = a_centre;
  b.largest_deceleration = 0.0;
  for_extremes(grid.ascending, r.r0, r.r1, [&](std::size_t row) {
    b.acceleration_spread = std::max(b.acceleration_spread, std::abs(grid.accelerations[row] - a_centre));
    b.top_acceleration = std::max(b.top_acceleration, grid.accelerations[row]);
    b.largest_deceleration = std::max(b.largest_deceleration, std::abs(grid.accelerations[row]));
  });
  fill_curvature_extents(grid, r, b);
}

void ego_sweep::fill_curvature_extents(const grid_view& grid, const block_range& r, block& b) {
  const double k_centre = grid.curvatures[(r.c0 + r.c1 - 1) / 2];
  b.curvature_spread = 0.0;
  b.largest_curvature = 0.0;
  for_extremes(grid.ascending, r.c0, r.c1, [&](std::size_t c) {
    b.curvature_spread = std::max(b.curvature_spread, std::abs(grid.curvatures[c] - k_centre));
    b.largest_curvature = std::max(b.largest_curvature, std::abs(grid.curvatures[c]));
  });
}

std::uint32_t ego_sweep::add_block(const grid_view& grid, std::size_t grid_index, std::size_t r0, std::size_t r1,
                                   std::size_t c0, std::size_t c1) {
  const auto index = static_cast<std::uint32_t>(blocks_.size());
  blocks_.emplace_back();
  const block_range range{static_cast<std::uint32_t>(grid_index), static_cast<std::uint32_t>(r0),
                          static_cast<std::uint32_t>(r1), static_cast<std::uint32_t>(c0), static_cast<std::uint32_t>(c1)};
  ranges_.push_back(range);
  block b;
  b.begin = static_cast<std::uint32_t>(order_.size());
  fill_extents(grid, range, b);
  if (r1 - r0 == 1 && c1 - c0 == 1) {
    order_.push_back(b.centre);
  } else {
    // Halve the side with the larger spread of acceleration: longitudinal, Δa, or lateral, the
    // a_lat,max · Δκ/κ_max that a change of curvature makes where the lateral limit binds — the
    // spread of the placements at T_h away from low speeds, and independent of the speed, so that
    // the tree's shape is too (`restart` keeps it at a new speed).
    const double along_a = std::abs(grid.shape_accelerations[r1 - 1] - grid.shape_accelerations[r0]);
    const double columns_spanned = grid.curvatures.size() > 1 ? static_cast<double>(grid.curvatures.size() - 1) : 1.0;
    const double along_k = ego_.limits.max_lateral_acceleration * 2.0 * static_cast<double>(c1 - 1 - c0) / columns_spanned;
    const bool split_rows = c1 - c0 == 1 || (r1 - r0 > 1 && along_a >= along_k);
    if (split_rows) {
      const std::size_t mid = (r0 + r1) / 2;
      add_block(grid, grid_index, r0, mid, c0, c1);
      b.second = add_block(grid, grid_index, mid, r1, c0, c1);
    } else {
      const std::size_t mid = (c0 + c1) / 2;
      add_block(grid, grid_index, r0, r1, c0, mid);
      b.second = add_block(grid, grid_index, r0, r1, mid, c1);
    }
  }
  b.end = static_cast<std::uint32_t>(order_.size());
  blocks_[index] = b;
  return index;
}

double ego_sweep::arc_length_bound(double a, double t) const {
  const double v0 = ego_.speed;
  if (a < 0.0 && t * -a > v0) return v0 * v0 / (2.0 * -a);
  return std::max(0.0, v0 * t + 0.5 * a * t * t);
}

double ego_sweep::speed_bound(double a) const { return std::clamp(ego_.speed + a * window_.horizon, 0.0, ego_.limits.speed_cap); }

double ego_sweep::block_spread(const block& b, std::size_t k) const {
  // Along a at the centre's κ, then along κ at the sample's a. With s(t) the arc length travelled
  // (|∂s/∂a| ≤ t²/2, stopping and the speed cap included), on the arc p moves along the tangent
  // (|∂p/∂a| ≤ t²/2), θ = κs, and |∂p/∂κ| ≤ s²/2 at fixed s; after T_h the straight part adds
  // (t − T_h)(∂v/∂a + v κ ∂s/∂a) and (t − T_h) v s. Every point moves by at most |Δp| + R |Δθ|.
  const double t = times_[k];
  const double horizon = window_.horizon;
  const double r = ego_radius_;
  const double kappa = b.largest_curvature;
  double along_a = 0.0;
  double along_k = 0.0;
  if (t <= horizon) {
    const double s = arc_length_bound(b.top_acceleration, t);
    along_a = 0.5 * t * t * (1.0 + r * kappa);
    along_k = s * (0.5 * s + r);
  } else {
    const double straight = t - horizon;
    const double s = arc_length_bound(b.top_acceleration, horizon);
    const double v = speed_bound(b.top_acceleration);
    const double half_square = 0.5 * horizon * horizon;
    along_a = half_square * (1.0 + r * kappa) + straight * (horizon + v * kappa * half_square);
    along_k = s * (0.5 * s + r) + v * straight * s;
  }
  return (b.acceleration_spread * along_a + b.curvature_spread * along_k) * (1.0 + 1e-9) + 1e-9;
}

widening ego_sweep::straight_spread_of(const block& b) const {
  // block_spread's terms for t > T_h: constant ones, and those proportional to t − T_h.
  const double horizon = window_.horizon;
  const double r = ego_radius_;
  const double kappa = b.largest_curvature;
  const double s = arc_length_bound(b.top_acceleration, horizon);
  const double v = speed_bound(b.top_acceleration);
  const double half_square = 0.5 * horizon * horizon;
  const double base = b.acceleration_spread * (half_square * (1.0 + r * kappa)) + b.curvature_spread * (s * (0.5 * s + r));
  const double rate = b.acceleration_spread * (horizon + v * kappa * half_square) + b.curvature_spread * (v * s);
  return {base * (1.0 + 1e-9) + 1e-9, rate * (1.0 + 1e-9)};
}

double ego_sweep::velocity_spread(const block& b, std::size_t k) const {
  // The velocity v(t)(cos θ, sin θ): |∂/∂a| ≤ t + v κ t²/2 and |∂/∂κ| ≤ v s (t ≤ T_h; T_h after).
  const double t = std::min(times_[k], window_.horizon);
  const double v = speed_bound(b.top_acceleration);
  const double s = arc_length_bound(b.top_acceleration, t);
  const double along_a = t + 0.5 * v * b.largest_curvature * t * t;
  const double along_k = v * s;
  return (b.acceleration_spread * along_a + b.curvature_spread * along_k) * (1.0 + 1e-9) + 1e-9;
}

vec2 ego_sweep::velocity(std::size_t k, std::size_t m) const {
  const double t = std::min(times_[k], window_.horizon);
  return speed_after(ego_.speed, samples_.maneuvers[m].acceleration, t, ego_.limits.speed_cap) * at(k, m).direction;
}

double ego_sweep::largest_acceleration(const block& b, std::size_t k) const {
  if (times_[k] >= window_.horizon) return 0.0;
  const double v = std::max(std::min(ego_.speed, ego_.limits.speed_cap), speed_bound(b.top_acceleration));
  return (b.largest_deceleration + b.largest_curvature * v * v) * (1.0 + 1e-9);
}

double ego_sweep::largest_acceleration(std::size_t k, std::size_t m) const {
  if (times_[k] >= window_.horizon) return 0.0;
  const maneuver& u = samples_.maneuvers[m];
  const double v = sample_speed_[m];
  return (std::abs(u.acceleration) + std::abs(u.curvature) * v * v) * (1.0 + 1e-9);
}


ego_sweep::placement_columns ego_sweep::ordered_placements(std::size_t k, std::size_t begin, std::size_t end,
                                                           const sample_mask* skip) const {
  if (!ordered_[k]) ordered_[k] = std::make_unique_for_overwrite<double[]>(4 * sample_count_);
  double* const x = ordered_[k].get();
  double* const y = x + sample_count_;
  double* const c = y + sample_count_;
  double* const s = c + sample_count_;
  std::uint8_t* const stamps = ordered_known_.data() + k * sample_count_;
  for (std::size_t p = begin; p < end; ++p) {
    if (stamps[p] == ordered_generation_) continue;
    if (skip != nullptr && skip->test(p)) {
      x[p] = 0.0;
      y[p] = 0.0;
      c[p] = 1.0;
      s[p] = 0.0;
      continue;
    }
    const placement at_k = at(k, order_[p]);
    x[p] = at_k.position.x;
    y[p] = at_k.position.y;
    c[p] = at_k.direction.x;
    s[p] = at_k.direction.y;
    stamps[p] = ordered_generation_;
  }
  return {x + begin, y + begin, c + begin, s + begin};
}

ego_sweep::placement ego_sweep::placement_at(std::size_t m, double t) const {
  return in_world(local_placement_at(m, t));
}

ego_sweep::placement ego_sweep::local_placement_at(std::size_t m, double t) const {
  if (t > window_.horizon) {
    // The arc's end moved along its direction.
    const straight_part& part = straight(m);
    return {part.local + (part.speed * (t - window_.horizon)) * part.along, part.along};
  }
  return maneuver_local_placement(ego_.speed, samples_.maneuvers[m], t, window_.horizon, ego_.limits.speed_cap);
}

void ego_sweep::complete_straight(std::size_t m) const {
  straight_part& part = straight_[m];
  if (straight_known_[m] == unknown) {
    // maneuver_local_placement's values for t > T_h, in its order of operations: in the ego's
    // frame, they depend only on the speed and the maneuver.
    const double horizon = window_.horizon;
    const double cap = ego_.limits.speed_cap;
    const maneuver& u = samples_.maneuvers[m];
    const placement end = maneuver_local_placement(ego_.speed, u, horizon, horizon, cap);
    part.local = end.position;
    part.along = end.direction;
    part.speed = speed_after(ego_.speed, u.acceleration, horizon, cap);
    straight_known_[m] = local_only;
  }
  if (straight_known_[m] == local_only) {
    const placement world = in_world({part.local, part.along});
    part.direction = world.direction;
    part.start = world.position;
    part.velocity = part.speed * world.direction;
    straight_known_[m] = known;
  }
}

void ego_sweep::assign_travel_rows(std::size_t first) {
  travel_row_.resize(sample_count_);
  row_acceleration_.resize(first == 0 ? 0 : grid_travel_rows_);
  for (std::size_t m = first; m < sample_count_; ++m) {
    const double a = samples_.maneuvers[m].acceleration;
    std::size_t row = row_acceleration_.size();
    if (m > first && row_acceleration_[travel_row_[m - 1]] == a) {
      row = travel_row_[m - 1];
    } else {
      for (std::size_t r = 0; r < row_acceleration_.size(); ++r) {
        if (row_acceleration_[r] == a) {
          row = r;
          break;
        }
      }
    }
    if (row == row_acceleration_.size()) row_acceleration_.push_back(a);
    travel_row_[m] = static_cast<std::uint32_t>(row);
  }
}

double ego_sweep::travel(std::size_t k, std::size_t m) const {
  const std::size_t index = travel_row_[m] * time_count_ + k;
  if (travel_known_[index] != local_generation_) {
    travel_[index] = travelled_distance(ego_.speed, row_acceleration_[travel_row_[m]], times_[k], ego_.limits.speed_cap);
    travel_known_[index] = local_generation_;
  }
  return travel_[index];
}

void ego_sweep::fill(std::size_t k, std::size_t m) const {
  // At t ≤ T_h: maneuver_local_placement's arc, from its row's arc length.
  const double t = times_[k];
  const placement l =
      t > window_.horizon ? local_placement_at(m, t) : arc_placement(travel(k, m), samples_.maneuvers[m].curvature);
  const std::size_t index = placement_index(k, m);
  local_[index] = {l.position.x, l.position.y, l.direction.x, l.direction.y};
  local_known_[index] = local_generation_;
}

double refinement_threshold(double rate, double time_step) { return 0.5 * rate * time_step * (1.0 + 1e-9) + 1e-12; }

namespace {

/// A lower bound computed in floating point can exceed what it bounds by a few units in the last
/// place where the two are equal in exact arithmetic (the face separation of parallel faces is
/// their distance). Every bound that lets a walk skip a time is lowered by this [m], so that a time
/// is skipped only when it provably cannot matter, to the last bit.
constexpr double rounding_slack = 1e-12;

/// True when |v| − `offset` is surely below `level` [m]: the length of v surely below
/// `level` + `offset`, shown without the square root, with a slack of 10⁻⁹ of the magnitudes far
/// above the rounding of `norm(v) - offset - ...` (so that where it is true, that difference, as the
/// callers round it, is below `level` too). Most bound checks near an obstacle end here; the root's
/// latency was a tenth of the rasters' time.
bool surely_closer(vec2 v, double offset, double level) {
  const double within = offset + level - 1e-9 * (offset + std::abs(level)) - 1e-12;
  return within > 0.0 && squared_norm(v) < within * within;
}


/// How fast a gap can close, in sample steps per metre: 1 / (rate · time_step), +∞ for a rate
/// of 0 (found once per walk, so that its steps multiply instead of divide).
struct closing_speed {
  double steps_per_metre;
};

closing_speed closing_at(double rate, double time_step) {
  return {rate > 0.0 ? 1.0 / (rate * time_step) : std::numeric_limits<double>::infinity()};
}

/// First time index after k at which a quantity `gap` above the target, closing at most at
/// `speed`, could reach the target (k + 1 when it is not above). The factor 1 − 10⁻⁹ exceeds the
/// rounding of the reciprocal by far, so no time is skipped at which the gap could have closed.
std::size_t first_possible(std::size_t k, double gap, closing_speed speed) {
  if (!(gap > 0.0)) return k + 1;
  const double steps = gap * (1.0 - 1e-9) * speed.steps_per_metre;
  if (steps >= 1e9) return std::numeric_limits<std::size_t>::max();
  return k + static_cast<std::size_t>(steps) + 1;
}

std::size_t first_possible(std::size_t k, double gap, double rate, double time_step) {
  return first_possible(k, gap, closing_at(rate, time_step));
}

/// Below this many sample steps of wait from the largest rates, the raster also bounds the centres'
/// distance from how fast it changes now.
constexpr std::size_t second_order_steps = 2;

/// `smallest_signed_distance` of the ego's footprint placed at `e` and the obstacle's placed at `o`,
/// the ego translating by `motion` relative to it: the rectangle closed forms where they apply.
translation_minimum straight_part_minimum(const footprint& ego_shape, const placement& e, const footprint& obstacle_shape,
                                          const placement& o, const translation& motion) {
  if (const auto* r = std::get_if<rectangle>(&ego_shape)) {
    const placed_rectangle ego{e.position, e.direction, r->length / 2.0, r->width / 2.0};
    if (const auto* b = std::get_if<rectangle>(&obstacle_shape)) {
      return smallest_signed_distance(ego, placed_rectangle{o.position, o.direction, b->length / 2.0, b->width / 2.0},
                                      motion);
    }
    if (const auto* d = std::get_if<disc>(&obstacle_shape)) return smallest_signed_distance(ego, o.position, d->radius, motion);
  }
  return smallest_signed_distance(place(ego_shape, e.position, e.direction), place(obstacle_shape, o.position, o.direction),
                                  motion);
}

/// True when the smallest signed distance of the same is ≤ `margin` [m]: `signed_distance_reaches`
/// where the rectangle forms apply.
bool straight_part_collides(const footprint& ego_shape, const placement& e, const footprint& obstacle_shape,
                            const placement& o, const translation& motion, double margin) {
  if (const auto* r = std::get_if<rectangle>(&ego_shape)) {
    const placed_rectangle ego{e.position, e.direction, r->length / 2.0, r->width / 2.0};
    if (const auto* b = std::get_if<rectangle>(&obstacle_shape)) {
      return signed_distance_reaches(ego, placed_rectangle{o.position, o.direction, b->length / 2.0, b->width / 2.0},
                                     motion, margin);
    }
    if (const auto* d = std::get_if<disc>(&obstacle_shape)) {
      return signed_distance_reaches(ego, o.position, d->radius, motion, margin);
    }
  }
  return straight_part_minimum(ego_shape, e, obstacle_shape, o, motion).distance - margin <= 0.0;
}

/// `first_contact` of the same, at `level` [m].
double straight_part_contact(const footprint& ego_shape, const placement& e, const footprint& obstacle_shape,
                             const placement& o, const translation& motion, double level) {
  if (const auto* r = std::get_if<rectangle>(&ego_shape)) {
    const placed_rectangle ego{e.position, e.direction, r->length / 2.0, r->width / 2.0};
    if (const auto* b = std::get_if<rectangle>(&obstacle_shape)) {
      return first_contact(ego, placed_rectangle{o.position, o.direction, b->length / 2.0, b->width / 2.0}, motion, level);
    }
    if (const auto* d = std::get_if<disc>(&obstacle_shape)) return first_contact(ego, o.position, d->radius, motion, level);
  }
  return first_contact(place(ego_shape, e.position, e.direction), place(obstacle_shape, o.position, o.direction), motion,
                       level);
}

/// The ego executing `u` and the obstacle forecast with `tau`, both placed at `start` (the start of
/// the straight part), and the ego's translation relative to the obstacle from there to T_c: what
/// `clearance_field::straight_motion_of` computes, in the same order of operations.
struct straight_setup {
  placement ego;
  placement obstacle;
  translation motion;
};

straight_setup straight_setup_of(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau,
                                 double start, const collision_window& window) {
  const placement end = maneuver_placement(ego.pose, unit_vector(ego.pose.heading), ego.speed, u, window.horizon,
                                           window.horizon, ego.limits.speed_cap);
  const vec2 ego_velocity = speed_after(ego.speed, u.acceleration, window.horizon, ego.limits.speed_cap) * end.direction;
  const placement e{start > window.horizon ? end.position + (start - window.horizon) * ego_velocity : end.position,
                    end.direction};
  const pose p = forecast_pose(obstacle.motion, tau, start);
  const placement o{p.position, unit_vector(p.heading)};
  return {e, o, {ego_velocity - obstacle.motion.speed * o.direction, window.duration - start}};
}

/// First index of `times` (ascending) at or after `t`.
std::size_t first_at_or_after(const std::vector<double>& times, double t) {
  return static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t) - times.begin());
}

}  // namespace

double straight_part_start(const forecast_obstacle& obstacle, double forecast_time, const collision_window& window) {
  const double start = obstacle.motion.yaw_rate == 0.0 ? window.horizon : std::max(window.horizon, forecast_time);
  return std::min(start, window.duration);
}

clearance_field::clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                 std::span<const double> forecast_times, double cap,
                                 std::span<const std::uint8_t> wanted)
    : clearance_field(sweep, obstacle, forecast_times, cap, wanted, nullptr, recording::collisions) {}

clearance_field::clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                 std::span<const double> forecast_times, double cap,
                                 std::span<const std::uint8_t> wanted, raster_scratch& scratch, recording what)
    : clearance_field(sweep, obstacle, forecast_times, cap, wanted, &scratch, what) {}

clearance_field::clearance_field(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                 std::span<const double> forecast_times, double cap,
                                 std::span<const std::uint8_t> wanted, raster_scratch* reused, recording what)
    : sweep_(sweep),
      obstacle_(obstacle),
      taus_(forecast_times.begin(), forecast_times.end()),
      wanted_(wanted.begin(), wanted.end()),
      cap_(cap) {
  if (!wanted_.empty() && wanted_.size() != taus_.size()) {
    throw std::invalid_argument("clearance_field: wanted has " + std::to_string(wanted_.size()) +
                                " entries for " + std::to_string(taus_.size()) + " forecast times");
  }
  const std::vector<double>& times = sweep.times();
  const motion_estimate& motion = obstacle.motion;
  const collision_window& window = sweep.window();
  const double step = window.time_step;
  const double obstacle_radius = bounding_radius(obstacle.shape);
  obstacle_turn_speed_ = largest_point_speed(obstacle);
  obstacle_acceleration_ = motion.speed * std::abs(motion.yaw_rate);
  distance_rate_ = sweep.largest_point_speed() + obstacle_turn_speed_;
  // Minima up to half a step's change above the cap can still refine to below it: walk exactly to there.
  walk_cap_ = cap + distance_rate_ * step / 2.0;
  band_ = refinement_threshold(distance_rate_, step);
  reach_ = bounding_radius(sweep.ego().shape) + obstacle_radius + rounding_slack;
  centre_rate_ = sweep.largest_speed() + motion.speed;
  centre_steps_ = closing_at(centre_rate_, step).steps_per_metre;
  distance_steps_ = closing_at(distance_rate_, step).steps_per_metre;
  horizon_index_ = first_at_or_after(times, window.horizon);
  if (const auto* ego_shape = std::get_if<rectangle>(&sweep.ego().shape)) {
    ego_half_ = {ego_shape->length / 2.0, ego_shape->width / 2.0};
    if (const auto* r = std::get_if<rectangle>(&obstacle.shape)) {
      shapes_ = shape_pair::rectangles;
      obstacle_half_ = {r->length / 2.0, r->width / 2.0};
    } else if (const auto* d = std::get_if<disc>(&obstacle.shape)) {
      shapes_ = shape_pair::rectangle_disc;
      obstacle_radius_ = d->radius;
    }
  }
  const std::size_t samples = sweep.sample_count();
  const std::size_t count = taus_.size();

  // The obstacle's placements: the CTRV part shared by every τ ≥ t, then per τ the straight part.
  // Without a turn every forecast time gives the same forecast: all times are shared.
  independent_ = motion.yaw_rate == 0.0;
  const double last_tau = count == 0 ? 0.0 : taus_.back();
  heading_direction_ = unit_vector(motion.pose.heading);
  turn_end_.reserve(count);
  first_straight_.reserve(count);
  for (const double tau : taus_) {
    turn_end_.push_back(independent_ ? straight_forecast(tau) : as_placement(forecast_pose(motion, tau, tau)));
    std::size_t k = independent_ ? times.size() : 0;
    while (k < times.size() && times[k] <= tau) ++k;
    first_straight_.push_back(k);
  }
  work_.placements = turn_end_.size();
  const std::size_t slots = independent_ ? std::min<std::size_t>(count, 1) : count;
  part_start_.reserve(slots);
  part_first_.reserve(slots);
  for (std::size_t i = 0; i < slots; ++i) {
    const double start = straight_part_start(obstacle, taus_[i], window);
    part_start_.push_back(start);
    part_first_.push_back(first_at_or_after(times, start));
  }
  const vec2 start = sweep.reach_centre(0);
  // A neighbour that no maneuver comes near costs its placements at the forecast times alone, and
  // one empty set serves every forecast time.
  if (slots > 0 && what == recording::collisions && far_at_every_time(start)) {
    inert_ = true;
    sets_.assign(1, {});
    sampled_.assign(1, sample_mask(samples));
    exact_.assign(1, {});
    return;
  }
  sets_.assign(slots, {});
  sampled_.assign(slots, sample_mask(samples));
  exact_.assign(slots, {});
  turning_.reserve(times.size());
  for (std::size_t k = 0; k < times.size() && (independent_ || times[k] <= last_tau); ++k) {
    turning_.push_back(independent_ ? straight_forecast(times[k]) : as_placement(forecast_pose(motion, times[k], times[k])));
  }
  // The straight part of each slot's window: both road users where it starts.
  part_obstacle_.reserve(slots);
  part_velocity_.reserve(slots);
  for (std::size_t i = 0; i < slots; ++i) {
    const pose p = forecast_pose(motion, taus_[i], part_start_[i]);
    part_obstacle_.push_back({p.position, unit_vector(p.heading)});
    part_velocity_.push_back(motion.speed * part_obstacle_.back().direction);
  }
  work_.placements += turning_.size() + slots;

  // The collisions. The sample times shared by every forecast time that includes them (t_k ≤ τ: the
  // CTRV placement, and before the straight part of the window) are rastered once, in order; each
  // forecast time continues from their state at τ with its own sample times before its straight
  // part (the obstacle straight, the ego still on its arc), then the straight part in closed form. A
  // block waits for the first time index at which one of its samples can overlap: the signed
  // distance changes no faster than L under any forecast, so a wait computed on the shared times
  // holds for every forecast time's own times too.
  bool near = false;
  // No sample can overlap the obstacle at time index k (and none comes within the walking cap).
  const auto out_of_reach = [&](std::size_t k, const obstacle_at& o) {
    const double gap = reach_gap(k, norm(o.position - start));
    if (gap < walk_cap_) near = true;
    return gap > band_;
  };
  const std::vector<std::uint32_t>& order = sweep.order();
  std::optional<raster_scratch> own_scratch;
  raster_scratch& scratch = reused != nullptr ? *reused : own_scratch.emplace();
  raster_state& shared = scratch.shared_;
  const bool record = what == recording::first_overlaps;
  if (record) first_overlap_.assign(slots, {});
  shared.reset(samples, times.size(), sweep.block_count(), record);
  for (const std::uint32_t root : sweep.roots()) shared.wait(0, root);
  std::size_t shared_done = 0;
  raster_state& own = scratch.own_;
  // A slot is computed when a forecast time it serves is wanted (every one shares slot 0 without a turn).
  const auto slot_wanted = [&](std::size_t i) {
    if (!independent_) return evaluated(i);
    for (std::size_t f = 0; f < count; ++f) {
      if (evaluated(f)) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < slots; ++i) {
    if (!slot_wanted(i)) continue;
    const std::size_t shared_until = shared_end(i);
    for (; shared_done < shared_until; ++shared_done) {
      if (out_of_reach(shared_done, turning_[shared_done])) {
        shared.postpone(shared_done);
        continue;
      }
      shared.end = shared_until;
      raster(shared_done, turning_[shared_done], shared);
    }
    if (shared_until < part_first_[i]) {
      own = shared;
      own.shared = false;
      own.slot = i;
      own.end = part_first_[i];
      for (std::size_t k = shared_until; k < part_first_[i]; ++k) {
        const obstacle_at o = obstacle_pose(i, k);
        if (out_of_reach(k, o)) {
          own.postpone(k);
          continue;
        }
        raster(k, o, own);
      }
    } else {
      // No sample time of its own before the straight part, which reads and marks only the hits:
      // the waiting lists (a link per block) need not be copied.
      own.hit = shared.hit;
      own.near = shared.near;
      own.near_at = shared.near_at;
      own.hit_at = shared.hit_at;
    }
    // The straight part: how close the obstacle comes to the disc that holds every sample's
    // reference point (its radius grows linearly there, the obstacle moves on a line), in closed
    // form, bounds every sample (for inertness, and whether to look at the part at all); then every
    // block is tested once in closed form.
    {
      const double gap = straight_reach_gap(i, part_obstacle_[i].position - start, part_velocity_[i]);
      if (gap < walk_cap_) near = true;
      if (gap <= 0.0) raster_straight_part(i, own);
    }
    if (record) first_overlap_[i].assign(samples, no_collision);
    own.hit.for_each([&](std::size_t p) {
      sampled_[i].set(order[p]);
      if (record) first_overlap_[i][order[p]] = own.hit_at[p];
    });
    // The samples that came within θ of the obstacle at a sample time before the straight part
    // without overlapping it there can touch it between sample times: they collide where their
    // exact clearance (the sampled minimum refined around its time) is ≤ 0. Recording, the contact is
    // put at the sampled minimum's time.
    own.near.for_each([&](std::size_t p) {
      if (own.hit.test(p)) return;  // it overlaps at a sample time, or on the straight part
      const std::size_t m = order[p];
      if (!may_touch_between(i, m, own.near_at[p]) || !(exact(i, m) <= 0.0)) return;
      sampled_[i].set(m);
      if (record) {
        const bool walked = !argmin_.empty() && !argmin_[i].empty() && argmin_[i][m] != none;
        first_overlap_[i][m] = walked ? times[argmin_[i][m]] : part_start_[i];
      }
    });
  }
  if (!near) {
    // Never within the walking cap of any sample: every clearance is exactly +cap.
    inert_ = true;
  }
}

double clearance_field::reach_gap(std::size_t k, double distance) const {
  return distance - sweep_.reach_radius(k) - reach_ - sweep_.window().margin;
}

double clearance_field::straight_reach_gap(std::size_t i, vec2 offset, vec2 velocity) const {
  const collision_window& window = sweep_.window();
  const widening reach = sweep_.straight_reach();
  const double from = part_start_[i];
  const double radius = reach.base + reach.rate * (from - window.horizon);
  const double closest = closest_approach_to_growing_disc(offset, velocity, reach.rate, window.duration - from);
  return closest - 1e-12 * std::abs(closest) - 1e-9 - radius - reach_ - window.margin;
}

bool clearance_field::far_at_every_time(vec2 start) const {
  const std::vector<double>& times = sweep_.times();
  const collision_window& window = sweep_.window();
  const double speed = obstacle_.motion.speed;
  // Rounding of the placements (forecast_pose, the construction's own order of operations) and of
  // the distances, far below this at any coordinates a scene has [m].
  const double slack = 1e-6 + 1e-12 * (norm(start) + norm(obstacle_.motion.pose.position) + speed * window.duration);
  const double need = walk_cap_ + slack;
  const auto far = [&](double distance, std::size_t k) { return reach_gap(k, distance) >= need; };
  const std::size_t slots = part_start_.size();
  const auto along = [&](std::size_t i, double t) {
    return turn_end_[i].position + speed * (t - taus_[i]) * turn_end_[i].direction;
  };
  const auto straight_part_far = [&](std::size_t i) {
    return straight_reach_gap(i, along(i, part_start_[i]) - start, speed * turn_end_[i].direction) >= need;
  };
  if (independent_) {
    if (slots == 0) return true;
    for (std::size_t k = 0; k < part_first_[0]; ++k) {
      if (!far(norm(straight_forecast(times[k]).position - start), k)) return false;
    }
    return straight_part_far(0);
  }
  if (!std::is_sorted(taus_.begin(), taus_.end()) || (!taus_.empty() && taus_.front() < 0.0)) return false;
  // The times every τ ≥ t shares (the CTRV curve): between two placements it knows, at τ_l ≤ t ≤
  // τ_{l+1} (and the present pose at t = 0), the obstacle is within v·(t − τ_l) of the one and
  // v·(τ_{l+1} − t) of the other, the arc being no shorter than the chord.
  std::size_t shared = 0;
  for (std::size_t i = 0; i < slots; ++i) shared = std::max(shared, std::min(first_straight_[i], part_first_[i]));
  double before_time = 0.0;
  double before = norm(obstacle_.motion.pose.position - start);
  std::size_t next = 0;
  for (std::size_t k = 0; k < shared; ++k) {
    const double t = times[k];
    while (next < slots && taus_[next] < t) {
      before_time = taus_[next];
      before = norm(turn_end_[next].position - start);
      ++next;
    }
    double distance = before - speed * (t - before_time);
    if (next < slots) distance = std::max(distance, norm(turn_end_[next].position - start) - speed * (taus_[next] - t));
    if (!far(distance, k)) return false;
  }
  // Each forecast time's own times before its straight part, and that part: the obstacle straight from τ_i.
  for (std::size_t i = 0; i < slots; ++i) {
    for (std::size_t k = std::min(first_straight_[i], part_first_[i]); k < part_first_[i]; ++k) {
      if (!far(norm(along(i, times[k]) - start), k)) return false;
    }
    if (!straight_part_far(i)) return false;
  }
  return true;
}

std::uint32_t clearance_field::until_second_order(std::size_t k, double gap, double change, double curvature) const {
  // gap + change·Δ − curvature·Δ²/2 > 0 before the positive root.
  constexpr std::uint32_t never = std::numeric_limits<std::uint32_t>::max();
  if (!(gap > 0.0) || !(curvature > 0.0)) return static_cast<std::uint32_t>(k + 1);
  // The positive root, in the form without cancellation for either sign of the change.
  const double discriminant = std::sqrt(change * change + 2.0 * curvature * gap);
  const double root = change >= 0.0 ? (change + discriminant) / curvature : 2.0 * gap / (discriminant - change);
  const double steps = root * (1.0 - 1e-9) / sweep_.window().time_step;
  if (!(steps < 1e9)) return never;
  return static_cast<std::uint32_t>(std::min<std::size_t>(k + static_cast<std::size_t>(steps) + 1, never));
}

void clearance_field::raster(std::size_t k, const obstacle_at& o, raster_state& state) {
  const placed_rectangle rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
  const placed_footprint placed =
      shapes_ == shape_pair::general ? place(obstacle_.shape, o.position, o.direction) : placed_footprint{};
  const placed_obstacle at{o, rectangle, placed};
  for (std::uint32_t j = state.take(k); j != raster_state::none;) {
    const std::uint32_t after = state.link[j];
    raster_block(j, k, at, state);
    j = after;
  }
}

void clearance_field::raster_state::reset(std::size_t samples, std::size_t times, std::size_t blocks, bool record) {
  hit.clear(samples);
  near.clear(samples);
  near_at.resize(samples);
  head.assign(times, none);
  if (link.size() < blocks) link.resize(blocks);
  if (record) {
    hit_at.resize(samples);
  } else {
    hit_at.clear();
  }
}

double clearance_field::first_overlap(std::size_t i, std::size_t m) const {
  const std::size_t s = slot(i);
  if (s >= first_overlap_.size() || first_overlap_[s].empty()) {
    throw std::logic_error("clearance_field::first_overlap: forecast time " + std::to_string(i) +
                           " was not evaluated with recording::first_overlaps");
  }
  return first_overlap_[s][m];
}

void clearance_field::raster_state::wait(std::size_t k, std::uint32_t block) {
  if (k >= head.size()) return;
  link[block] = head[k];
  head[k] = block;
}

std::uint32_t clearance_field::raster_state::take(std::size_t k) {
  const std::uint32_t first = head[k];
  head[k] = none;
  return first;
}

void clearance_field::raster_state::postpone(std::size_t k) {
  for (std::uint32_t j = take(k); j != none;) {
    const std::uint32_t after = link[j];
    wait(k + 1, j);
    j = after;
  }
}

template <class Corners>
clearance_field::clearance_bounds clearance_field::rectangle_bounds(double face, double margin, bool corners,
                                                                    Corners&& corner_distance) {
  if (face <= 0.0) return {face - margin - rounding_slack, face - margin};
  if (!corners) return {face - margin - rounding_slack, std::numeric_limits<double>::infinity()};
  ++work_.distance_evaluations;
  const double high = corner_distance() - margin;
  return {high, high};
}

void clearance_field::raster_block(std::uint32_t index, std::size_t k, const placed_obstacle& o, raster_state& state) {
  const ego_sweep::block& b = sweep_.block_of(index);
  if (state.hit.all_in(b.begin, b.end)) return;
  const double margin = sweep_.window().margin;
  const double step = sweep_.window().time_step;
  const ego_sweep::placement p = sweep_.at(k, b.centre);
  const bool single = b.second == 0;
  const bool record = !state.hit_at.empty();
  const double spread = single ? 0.0 : sweep_.block_spread(b, k);
  // What a test looks for besides an overlap: a sample within its θ (a block: within the largest θ).
  // A sample already near is looked at again only where it can overlap.
  const double band = !single ? band_ : state.near.test(b.begin) ? 0.0 : sample_threshold(b.centre);
  ++work_.bound_checks;
  // The first time at which a gap [m] above zero can close, from the largest rates over the window.
  const auto until = [&](double gap, bool centres) {
    if (!single) return first_possible(k, gap, closing_speed{centres ? centre_steps_ : distance_steps_});
    return first_possible(k, gap, centres ? centre_rate(b.centre) : distance_rate(b.centre), step);
  };
  // Every sample of the block is within `spread` of the centre's placement: its signed distance −
  // margin lies in [low − spread, high + spread], with low and high bounds of the centre's.
  const vec2 apart = p.position - o.at.position;
  if (!surely_closer(apart, reach_ + margin + spread + band, 0.0)) {
    const double centres = norm(apart);
    const double disc = centres - reach_ - margin - spread - band;
    if (disc > 0.0) {
      std::size_t next = until(disc, true);
      if (next < k + second_order_steps) {
        // The samples' reference-point distances D to the obstacle's, from how fast the centre's
        // changes now: D(t_k + Δ) ≥ D − spread + (Ḋ − correction) Δ − M Δ²/2, where while D ≥ the
        // reach, D̈ ≤ |ṙ|²/D + |r̈| ≤ M. Long waits for an obstacle that moves away.
        const double level = reach_ + margin;
        const vec2 closing = sweep_.velocity(k, b.centre) - obstacle_.motion.speed * o.at.direction;
        const double rate = single ? centre_rate(b.centre) : centre_rate_;
        const double velocity_spread = single ? 0.0 : sweep_.velocity_spread(b, k);
        const double change = dot(apart, closing) / centres - velocity_spread - 2.0 * spread * norm(closing) / centres;
        const double curvature = rate * rate / level +
                                 (single ? sweep_.largest_acceleration(k, b.centre) : sweep_.largest_acceleration(b, k)) +
                                 obstacle_acceleration_;
        next = std::max<std::size_t>(next, until_second_order(k, disc, change, curvature));
      }
      state.wait(next, index);
      return;
    }
  }
  double low = 0.0;
  double high = std::numeric_limits<double>::infinity();
  if (shapes_ == shape_pair::rectangles) {
    const placed_rectangle ego_rectangle{p.position, p.direction, ego_half_.x, ego_half_.y};
    const double face = face_separation(ego_rectangle, o.rectangle);
    // Apart, the exact distance where the margin can still make it (or the whole block) overlap.
    const clearance_bounds c =
        rectangle_bounds(face, margin, single ? face - margin - rounding_slack <= 0.0 : face + spread < margin,
                         [&] { return corner_distance(ego_rectangle, o.rectangle); });
    low = c.low;
    high = c.high;
  } else {
    ++work_.distance_evaluations;
    const double d = shapes_ == shape_pair::general
                         ? signed_distance(place(sweep_.ego().shape, p.position, p.direction), o.footprint)
                         : distance(p.position, p.direction, o.at);
    low = d - margin;
    high = low;
  }
  // A sample is in one waiting block at a time and is hit once, at the first sample time at which it
  // overlaps (no wait passes a time at which one of its samples can). A block whose samples were
  // tested one by one (`raster_samples`) waits with some of them hit already: those keep their time.
  const auto mark_all = [&] {
    for (std::size_t q = b.begin; q < b.end; ++q) {
      if (record && !state.hit.test(q)) state.hit_at[q] = sweep_.times()[k];
      state.hit.set(q);
    }
  };
  if (single) {
    // A single sample: `clearance_at` ≤ 0 bit for bit; near where a lower bound of it (the face
    // separation less the margin) is ≤ θ.
    if (high <= 0.0) {
      mark_all();
    } else if (low <= band) {
      state.near.set(b.begin);
      state.near_at[b.begin] = static_cast<std::uint32_t>(k);
      state.wait(until(low, false), index);
    } else {
      state.wait(until(low - band, false), index);
    }
    return;
  }
  if (low - spread > band) {
    state.wait(until(low - spread - band, false), index);
  } else if (high + spread + rounding_slack <= 0.0) {
    mark_all();
  } else if (state.hit_at.empty() && overlaps_whole_ahead(b, k, state)) {
    // Overlapping everywhere a little later: hit (when the first overlap is not recorded).
    mark_all();
  } else if (b.end - b.begin <= together && shapes_ == shape_pair::rectangles) {
    raster_samples(index, k, o, state);
  } else {
    // Undecided as a whole: its halves wait on their own from now on.
    raster_block(index + 1, k, o, state);
    raster_block(b.second, k, o, state);
  }
}

void clearance_field::raster_samples(std::uint32_t index, std::size_t k, const placed_obstacle& o,
                                     raster_state& state) {
  const ego_sweep::block& b = sweep_.block_of(index);
  const std::size_t n = b.end - b.begin;
  const ego_sweep::placement_columns p = sweep_.ordered_placements(k, b.begin, b.end, &state.hit);
  std::array<double, together> face;
  face_separation_of_each(n, p.x, p.y, p.c, p.s, ego_half_, o.rectangle, face.data());
  const double margin = sweep_.window().margin;
  const bool record = !state.hit_at.empty();
  const std::vector<std::uint32_t>& order = sweep_.order();
  // The block waits until the smallest gap of its clear samples (to their θ, or to an overlap) can
  // close at the largest rate L.
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t q = b.begin + i;
    if (state.hit.test(q)) continue;
    ++work_.bound_checks;
    // A single sample's test in `raster_block`: `clearance_at` ≤ 0 bit for bit; near where the face
    // separation less the margin is ≤ θ (the corners are needed only where the margin can overlap).
    const double band = state.near.test(q) ? 0.0 : sample_threshold(order[q]);
    const clearance_bounds c = rectangle_bounds(face[i], margin, face[i] - margin - rounding_slack <= 0.0, [&] {
      const placed_rectangle ego{{p.x[i], p.y[i]}, {p.c[i], p.s[i]}, ego_half_.x, ego_half_.y};
      return corner_distance(ego, o.rectangle);
    });
    if (c.high <= 0.0) {
      state.hit.set(q);
      if (record) state.hit_at[q] = sweep_.times()[k];
    } else if (c.low <= band) {
      state.near.set(q);
      state.near_at[q] = static_cast<std::uint32_t>(k);
      gap = std::min(gap, c.low);
    } else {
      gap = std::min(gap, c.low - band);
    }
  }
  if (gap != std::numeric_limits<double>::infinity()) {
    state.wait(first_possible(k, gap, closing_speed{distance_steps_}), index);
  }
}

bool clearance_field::overlaps_whole_ahead(const ego_sweep::block& b, std::size_t k, const raster_state& state) {
  const double margin = sweep_.window().margin;
  const std::size_t last = std::min(k + 1 + lookahead_steps, state.end);
  for (std::size_t later = k + 1; later < last; ++later) {
    const obstacle_at o = state.shared ? turning_[later] : obstacle_pose(state.slot, later);
    const ego_sweep::placement p = sweep_.at(later, b.centre);
    ++work_.bound_checks;
    double high = 0.0;
    const double spread = sweep_.block_spread(b, later);
    if (shapes_ == shape_pair::rectangles) {
      // The corners' distance only where the margin can still make the whole block overlap.
      const placed_rectangle ego{p.position, p.direction, ego_half_.x, ego_half_.y};
      const placed_rectangle obstacle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
      const double face = face_separation(ego, obstacle);
      const auto corners = [&] { return corner_distance(ego, obstacle); };
      high = rectangle_bounds(face, margin, face + spread < margin, corners).high;
    } else {
      ++work_.distance_evaluations;
      high = distance(p.position, p.direction, o) - margin;
    }
    if (high + spread + rounding_slack <= 0.0) return true;
  }
  return false;
}

void clearance_field::raster_straight_part(std::size_t i, raster_state& state) {
  for (const std::uint32_t root : sweep_.roots()) straight_part_block(root, i, state);
}

void clearance_field::straight_part_block(std::uint32_t index, std::size_t i, raster_state& state) {
  const ego_sweep::block& b = sweep_.block_of(index);
  if (state.hit.all_in(b.begin, b.end)) return;
  ++work_.bound_checks;
  const straight_motion part = straight_motion_of(i, b.centre);
  const bool record = !state.hit_at.empty();
  const auto mark = [&](std::size_t q, double when) {
    state.hit.set(q);
    if (record) state.hit_at[q] = when;
  };
  if (b.second == 0) {
    // A single sample: `collisions_reference`'s test, bit for bit.
    if (straight_apart(part, 0.0)) return;
    if (straight_collides(part)) mark(b.begin, record ? part_start_[slot(i)] + straight_first_contact(part) : 0.0);
    return;
  }
  // Every sample's footprint lies within the block's spread of the centre's, a spread that grows
  // linearly along the straight part: the centre's distances less it bound every sample's.
  const widening& grown = sweep_.straight_spread(index);
  const widening spread{grown.base + grown.rate * (part_start_[slot(i)] - sweep_.window().horizon), grown.rate};
  if (straight_apart(part, spread.base + spread.rate * part.motion.duration)) return;
  const double margin = sweep_.window().margin;
  if (shapes_ == shape_pair::general) {
    const translation_minimum low = straight_minimum(part);
    if (low.distance - (spread.base + spread.rate * part.motion.duration) > 0.0) return;
    if (!record && low.distance + (spread.base + spread.rate * low.time) + rounding_slack <= 0.0) {
      for (std::size_t q = b.begin; q < b.end; ++q) mark(q, 0.0);
      return;
    }
  } else {
    // Clear when the centre's face separation stays above the margin and the spread; every sample
    // overlaps when it falls below minus the spread where it is the centre's signed distance (two
    // rectangles overlapping; a disc whose centre is inside the rectangle, less its radius).
    const face_separations separations = straight_separations(part);
    if (!separations.reach({margin + spread.base, spread.rate})) return;
    const double inside = shapes_ == shape_pair::rectangle_disc ? obstacle_radius_ : 0.0;
    if (!record && separations.reach({-spread.base - inside - rounding_slack, -spread.rate})) {
      for (std::size_t q = b.begin; q < b.end; ++q) mark(q, 0.0);
      return;
    }
  }
  if (b.end - b.begin <= straight_together) {
    // Undecided and small: its samples one by one, each `collisions_reference`'s test, without the
    // tests of the blocks between (most of which decide nothing this close to the boundary).
    for (std::size_t q = b.begin; q < b.end; ++q) {
      if (state.hit.test(q)) continue;
      ++work_.bound_checks;
      const straight_motion single = straight_motion_of(i, sweep_.order()[q]);
      if (straight_apart(single, 0.0)) continue;
      if (straight_collides(single)) mark(q, record ? part_start_[slot(i)] + straight_first_contact(single) : 0.0);
    }
    return;
  }
  straight_part_block(index + 1, i, state);
  straight_part_block(b.second, i, state);
}

bool clearance_field::straight_collides(const straight_motion& part) { return straight_within(part, 0.0); }

bool clearance_field::straight_within(const straight_motion& part, double level) {
  ++work_.translation_minima;
  const double margin = sweep_.window().margin;
  const placement& e = part.ego;
  const obstacle_at& o = part.obstacle;
  const placed_rectangle ego{e.position, e.direction, ego_half_.x, ego_half_.y};
  if (shapes_ == shape_pair::rectangles) {
    return signed_distance_reaches(ego, placed_rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y},
                                   part.motion, level + margin);
  }
  if (shapes_ == shape_pair::rectangle_disc) {
    return signed_distance_reaches(ego, o.position, obstacle_radius_, part.motion, level + margin);
  }
  return straight_part_minimum(sweep_.ego().shape, e, obstacle_.shape, o, part.motion).distance - margin <= level;
}

face_separations clearance_field::straight_separations(const straight_motion& part) {
  ++work_.translation_minima;
  const placement& e = part.ego;
  const obstacle_at& o = part.obstacle;
  const placed_rectangle ego{e.position, e.direction, ego_half_.x, ego_half_.y};
  if (shapes_ == shape_pair::rectangles) {
    return {ego, placed_rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y}, part.motion};
  }
  return {ego, o.position, obstacle_radius_, part.motion};
}

clearance_field::straight_motion clearance_field::straight_motion_of(std::size_t i, std::size_t m) const {
  const std::size_t s = slot(i);
  const double start = part_start_[s];
  const double horizon = sweep_.window().horizon;
  const ego_sweep::line line = sweep_.straight_line(m);
  const vec2 position = start > horizon ? line.start + (start - horizon) * line.velocity : line.start;
  return {{position, sweep_.straight_direction(m)},
          part_obstacle_[s],
          {line.velocity - part_velocity_[s], sweep_.window().duration - start}};
}

translation_minimum clearance_field::straight_minimum(const straight_motion& part) {
  ++work_.translation_minima;
  const placement& e = part.ego;
  const obstacle_at& o = part.obstacle;
  translation_minimum low;
  if (shapes_ == shape_pair::rectangles) {
    const placed_rectangle ego{e.position, e.direction, ego_half_.x, ego_half_.y};
    const placed_rectangle obstacle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
    low = smallest_signed_distance(ego, obstacle, part.motion, face_separations(ego, obstacle, part.motion));
  } else if (shapes_ == shape_pair::rectangle_disc) {
    low = smallest_signed_distance(placed_rectangle{e.position, e.direction, ego_half_.x, ego_half_.y}, o.position,
                                   obstacle_radius_, part.motion);
  } else {
    low = straight_part_minimum(sweep_.ego().shape, e, obstacle_.shape, o, part.motion);
  }
  low.distance -= sweep_.window().margin;
  return low;
}

bool clearance_field::straight_apart(const straight_motion& part, double gap) const {
  // The reference points' offset r₀ + w s stays farther than R from the origin on [0, S] when its
  // squared length does: at s = 0, at s = S, or at the vertex, where it is |r₀ × w|²/|w|² —
  // compared without division or square root.
  const double radius = (gap + reach_ + sweep_.window().margin) * (1.0 + 1e-12) + 1e-9;
  if (radius <= 0.0) return true;
  const double limit = radius * radius;
  const vec2 offset = part.ego.position - part.obstacle.position;
  const vec2 w = part.motion.velocity;
  const double along = dot(offset, w);
  if (along >= 0.0) return squared_norm(offset) > limit;
  const double speed_squared = squared_norm(w);
  if (-along >= part.motion.duration * speed_squared) return squared_norm(offset + part.motion.duration * w) > limit;
  const double across = cross(offset, w);
  return across * across > limit * speed_squared;
}

double clearance_field::straight_first_contact(const straight_motion& part) const {
  return straight_part_contact(sweep_.ego().shape, part.ego, obstacle_.shape, part.obstacle, part.motion,
                               sweep_.window().margin);
}

clearance_field::obstacle_at clearance_field::obstacle_pose(std::size_t i, std::size_t k) const {
  if (k < first_straight_[i]) return turning_[k];
  if (independent_) return turning_[k];
  return straight_after_turn(i, sweep_.times()[k]);
}

clearance_field::obstacle_at clearance_field::straight_forecast(double t) const {
  const motion_estimate& motion = obstacle_.motion;
  return {motion.pose.position + motion.speed * t * heading_direction_, heading_direction_};
}

clearance_field::obstacle_at clearance_field::as_placement(const pose& p) { return {p.position, unit_vector(p.heading)}; }

clearance_field::obstacle_at clearance_field::straight_after_turn(std::size_t i, double t) const {
  const obstacle_at& end = turn_end_[i];
  return {end.position + obstacle_.motion.speed * (t - taus_[i]) * end.direction, end.direction};
}

double clearance_field::clearance_at_time(std::size_t i, std::size_t m, double t) const {
  const ego_sweep::placement e = sweep_.placement_at(m, t);
  obstacle_at o;
  if (independent_) {
    o = straight_forecast(t);
  } else if (t > taus_[i]) {
    o = straight_after_turn(i, t);
  } else {
    o = as_placement(forecast_pose(obstacle_.motion, taus_[i], t));
  }
  return distance(e.position, e.direction, o) - sweep_.window().margin;
}

double clearance_field::distance(vec2 position, vec2 direction, const obstacle_at& o) const {
  if (shapes_ == shape_pair::rectangles) {
    return signed_distance(placed_rectangle{position, direction, ego_half_.x, ego_half_.y},
                           placed_rectangle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y});
  }
  if (shapes_ == shape_pair::rectangle_disc) {
    return signed_distance(placed_rectangle{position, direction, ego_half_.x, ego_half_.y}, o.position,
                           obstacle_radius_);
  }
  return signed_distance(place(sweep_.ego().shape, position, direction), place(obstacle_.shape, o.position, o.direction));
}

clearance_field::lower_bound clearance_field::distance_or_bound(const ego_sweep::placement& p, const obstacle_at& o,
                                                                 double enough) const {
  const double margin = sweep_.window().margin;
  if (shapes_ != shape_pair::rectangles) return {distance(p.position, p.direction, o) - margin, true};
  // `distance`'s arithmetic, with the face separation looked at before the corners.
  const placed_rectangle ego{p.position, p.direction, ego_half_.x, ego_half_.y};
  const placed_rectangle obstacle{o.position, o.direction, obstacle_half_.x, obstacle_half_.y};
  const double separation = face_separation(ego, obstacle);
  if (separation <= 0.0) return {separation - margin, true};
  if (const double bound = separation - margin - rounding_slack; bound >= enough) return {bound, false};
  return {corner_distance(ego, obstacle) - margin, true};
}

bool clearance_field::may_touch_between(std::size_t i, std::size_t m, std::size_t first_near) {
  if (shapes_ == shape_pair::general) return true;
  const std::vector<double>& times = sweep_.times();
  const std::size_t sampled = part_first_[i];
  // Without a sample time at or after t_s the last pair is cut short: left to `exact`.
  if (sampled >= times.size()) return true;
  const double theta = sample_threshold(m);
  const closing_speed closing = closing_at(distance_rate(m), sweep_.window().time_step);
  const support_shape ego{ego_half_, 0.0};
  const support_shape obstacle =
      shapes_ == shape_pair::rectangles ? support_shape{obstacle_half_, 0.0} : support_shape{{0.0, 0.0}, obstacle_radius_};
  const maneuver& u = sweep_.samples().maneuvers[m];
  const double curvature = std::abs(u.curvature);
  const double turn_rate = std::abs(obstacle_.motion.yaw_rate);
  const double horizon = sweep_.window().horizon;
  const double forecast = taus_[i];
  // Every pair before the one ending at the first time within θ is farther than θ at both ends.
  std::size_t k = first_near > 0 ? first_near - 1 : 0;
  std::size_t stride = 1;
  std::uint8_t direction = 4;
  // A pair that ends at a time t ≤ τ_i is the same for every larger τ (the CTRV placements, no
  // bend): each sample walks those once, from the same first time within θ (`shared_proof`), and
  // every forecast time continues from where that walk got to. The slots come in increasing τ, so a
  // walk made for an earlier one reaches past what a later one shares only where it skipped ahead
  // (valid under every forecast: L bounds them all).
  std::size_t limit = sampled;
  shared_proof* proof = nullptr;
  // (Without a turn there is one slot: nothing to share.)
  if (const std::size_t shared_until = std::min(first_straight_[i] - 1, sampled);
      !independent_ && k < shared_until && first_near < none) {
    if (shared_proofs_.empty()) shared_proofs_.assign(sweep_.sample_count(), shared_proof{});
    shared_proof& p = shared_proofs_[m];
    if (p.first_near == none) p.first_near = static_cast<std::uint32_t>(first_near);
    if (p.first_near == first_near && p.limit <= shared_until) {
      if (p.failed) return true;
      k = std::max<std::size_t>(k, p.next);
      stride = p.stride;
      direction = p.direction;
      p.limit = static_cast<std::uint32_t>(shared_until);
      limit = shared_until;
      proof = &p;
    }
  }
  // Every pair from k to the limit proven apart, several steps at once where the gap allows it (the
  // dip grows with the square of the interval); first the shared ones (then `proof` records how far
  // they got), then the forecast time's own.
  for (;;) {
    while (k < limit) {
      const std::size_t end = k + std::min(stride, limit - k);
      const double duration = times[end] - times[k];
      // The ego's heading is κ·s(t) on its arc (s'' = a, or 0 where the speed is clamped) and
      // constant after T_h; the obstacle's turns at ω until τ, then not at all.
      const double ego_turn = curvature * sweep_.sample_speed(m) * duration;
      const double ego_bend = times[end] <= horizon || times[k] >= horizon
                                  ? curvature * std::abs(u.acceleration) * duration * duration / 8.0 * (1.0 + 1e-9)
                                  : ego_turn;
      const double obstacle_turn = turn_rate * duration;
      const double obstacle_bend = independent_ || times[end] <= forecast || times[k] >= forecast ? 0.0 : obstacle_turn;
      const interval_motion ego_motion{sweep_.at(k, m), sweep_.at(end, m), sweep_.largest_acceleration(k, m), ego_turn,
                                       ego_bend};
      const interval_motion obstacle_motion{obstacle_pose(i, k), obstacle_pose(i, end), obstacle_acceleration_,
                                            obstacle_turn, obstacle_bend};
      const interval_separation gap =
          separated_throughout(ego, ego_motion, obstacle, obstacle_motion, duration, sweep_.window().margin, direction);
      if (!gap.separated) {
        if (end == k + 1) {
          if (proof != nullptr) proof->failed = true;
          return true;
        }
        stride = (end - k) / 2;
        continue;
      }
      direction = gap.direction;
      stride = std::min<std::size_t>(2 * (end - k), 8);
      k = end;
      // The times after it before the first at which the clearance can be ≤ θ again are farther
      // than θ, and so is every pair between them.
      if (gap.gap_at_end > theta) k = std::max(k, first_possible(k, gap.gap_at_end - theta, closing) - 1);
    }
    if (proof == nullptr) return false;
    proof->next = static_cast<std::uint32_t>(k);
    proof->stride = static_cast<std::uint8_t>(stride);
    proof->direction = direction;
    proof = nullptr;
    limit = sampled;
  }
}

double clearance_field::refined_at(std::size_t i, std::size_t m, std::size_t k, double at_sample) {
  const auto at = [&](double t) { return clearance_at_time(i, m, t); };
  // On the shared times (t ≤ τ) the search sees the same function for every τ: search once.
  const bool shared = k + 1 < first_straight_[i];
  if (shared) {
    if (refined_head_.empty()) refined_head_.assign(sweep_.sample_count(), none);
    for (std::uint32_t e = refined_head_[m]; e != none; e = refined_[e].next) {
      if (refined_[e].argmin == k) return refined_[e].value;
    }
  }
  ++work_.refinements;
  const double value = refined_minimum(sweep_.times(), k, at, at_sample);
  if (shared) {
    refined_.push_back({k, value, refined_head_[m]});
    refined_head_[m] = static_cast<std::uint32_t>(refined_.size() - 1);
  }
  return value;
}

clearance_set& clearance_field::materialized(std::size_t i) const {
  clearance_set& set = sets_[i];
  if (set.empty()) {
    set.assign(sweep_.sample_count(), cap_);
    sampled_[i].for_each([&](std::size_t m) { set[m] = -cap_; });
  }
  return set;
}

double clearance_field::exact(std::size_t forecast, std::size_t m) {
  const std::size_t i = slot(forecast);
  if (inert_) return cap_;
  if (!exact_[i].empty() && exact_[i][m]) return sets_[i][m];
  const std::size_t sampled = part_first_[i];
  const double step = sweep_.window().time_step;
  const double margin = sweep_.window().margin;
  const double centre = centre_rate(m);
  const double rate = distance_rate(m);
  const double theta = sample_threshold(m);
  // The straight part first, in closed form (at or above the walking cap every value clamps alike,
  // so a bound there is enough).
  const straight_motion part = straight_motion_of(forecast, m);
  double straight = walk_cap_;
  if (!straight_apart(part, walk_cap_)) straight = std::min(straight, straight_minimum(part).distance);
  // A seed: the value at the time the sampled minimum of the same sample under a neighbouring
  // forecast time, or of a neighbouring sample, was found (any sample time before this straight
  // part gives a valid seed). The walks then skip every time that provably lies above it by more
  // than the argmin tolerance (such a time cannot become the argmin of the running minimum, so the
  // result is that of a walk over every time); the seed's own time is looked at as any other.
  std::uint32_t seed_time = none;
  const auto known_argmin = [&](std::size_t other, std::size_t sample) {
    if (seed_time == none && other < argmin_.size() && sample < sweep_.sample_count() && !argmin_[other].empty() &&
        argmin_[other][sample] < sampled) {
      seed_time = argmin_[other][sample];
    }
  };
  known_argmin(i - 1, m);  // the same sample under the neighbouring forecast times
  known_argmin(i + 1, m);
  known_argmin(i, m - 1);  // its neighbours in the sample order
  known_argmin(i, m + 1);
  double seed = std::numeric_limits<double>::infinity();
  if (seed_time != none && straight > -walk_cap_) {
    const ego_sweep::placement p = sweep_.at(seed_time, m);
    ++work_.distance_evaluations;
    seed = distance(p.position, p.direction, obstacle_pose(i, seed_time)) - margin + 3.0 * argmin_tolerance;
  }
  // Looks at time index k and returns the next one that can be below the running minimum (or the
  // walking cap: above it every value clamps to the cap; or the ceiling).
  const closing_speed centre_closing = closing_at(centre, step);
  const closing_speed closing = closing_at(rate, step);
  const auto look = [&](std::size_t k, const obstacle_at& o, running_minimum& r, double ceiling) {
    // Every value below −walk_cap clamps to −cap: once the minimum is there, nothing can change it.
    if (std::min(r.value, walk_cap_) <= -walk_cap_) return std::numeric_limits<std::size_t>::max();
    const double known = std::min({r.value, walk_cap_, ceiling});
    const ego_sweep::placement p = sweep_.at(k, m);
    ++work_.bound_checks;
    if (!surely_closer(p.position - o.position, reach_ + margin, known)) {
      const double bound = norm(p.position - o.position) - reach_ - margin;
      if (bound >= known) return first_possible(k, bound - known, centre_closing);
    }
    const lower_bound at = distance_or_bound(p, o, known);
    if (!at.exact) return first_possible(k, at.value - known, closing);
    ++work_.distance_evaluations;
    r.update(at.value, k);
    return first_possible(k, at.value - std::min({r.value, walk_cap_, ceiling}), closing);
  };
  running_minimum r;
  if (straight > -walk_cap_) {
    // The shared times first (kept for larger τ), then this τ's own sample times. A seed from a
    // shared time is a value every larger τ shares, so it may prune the shared walk too. A sample
    // time at least 2θ above the straight part's minimum cannot matter, nor can its refinement
    // (every time of its bracket lies within half a step of a sample time at least as high, or of
    // the straight part): it bounds this τ's own walk.
    if (prefix_of_.empty()) prefix_of_.assign(sweep_.sample_count(), none);
    if (prefix_of_[m] == none) {
      prefix_of_[m] = static_cast<std::uint32_t>(prefix_.size());
      prefix_.emplace_back();
    }
    prefix_walk& prefix = prefix_[prefix_of_[m]];
    const std::size_t shared = shared_end(i);
    if (prefix.until > shared) prefix = prefix_walk{};
    const double shared_seed = seed_time < shared ? seed : std::numeric_limits<double>::infinity();
    for (; prefix.next < shared;) prefix.next = look(prefix.next, turning_[prefix.next], prefix.minimum, shared_seed);
    prefix.until = shared;
    r = prefix.minimum;
    const double ceiling = std::min(seed, straight + 2.0 * theta + 3.0 * argmin_tolerance);
    for (std::size_t k = prefix.next; k < sampled;) k = look(k, obstacle_pose(i, k), r, ceiling);
  }
  double c = std::min(r.value, straight);
  if (r.value > -walk_cap_ && r.value < walk_cap_ && r.value < straight + 2.0 * theta) {
    c = std::min(c, refined_at(i, m, r.argmin, r.at_argmin));
  }
  c = std::clamp(c, -cap_, cap_);
  ++work_.exact_values;
  if (exact_[i].empty()) exact_[i].assign(sweep_.sample_count(), 0);
  materialized(i)[m] = c;
  exact_[i][m] = 1;
  if (r.value < walk_cap_) {
    if (argmin_.empty()) argmin_.resize(sets_.size());
    if (argmin_[i].empty()) argmin_[i].assign(sweep_.sample_count(), none);
    argmin_[i][m] = static_cast<std::uint32_t>(r.argmin);
  }
  return c;
}

void clearance_field::make_all_exact() {
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    for (std::size_t m = 0; m < sweep_.sample_count(); ++m) exact(i, m);
  }
}

std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap) {
  clearance_field field(sweep, obstacle, forecast_times, cap);
  field.make_all_exact();
  std::vector<clearance_set> result;
  for (std::size_t i = 0; i < field.forecast_count(); ++i) result.push_back(field.set(i));
  return result;
}

std::vector<clearance_set> clearances_reference(const ego_state& ego, const maneuver_samples& samples,
                                                const forecast_obstacle& obstacle,
                                                std::span<const double> forecast_times,
                                                const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  std::vector<clearance_set> result;
  for (const double tau : forecast_times) {
    const double start = straight_part_start(obstacle, tau, window);
    const std::size_t sampled = first_at_or_after(times, start);
    clearance_set clearance(samples.size());
    for (std::size_t m = 0; m < samples.size(); ++m) {
      const maneuver& u = samples.maneuvers[m];
      const auto at = [&](double t) { return clearance_at(ego, u, obstacle, tau, t, window); };
      running_minimum r;
      for (std::size_t k = 0; k < sampled; ++k) r.update(at(times[k]), k);
      double c = r.value;
      if (sampled > 0) c = std::min(c, refined_minimum(times, r.argmin, at, r.at_argmin));
      const straight_setup part = straight_setup_of(ego, u, obstacle, tau, start, window);
      const double straight =
          straight_part_minimum(ego.shape, part.ego, obstacle.shape, part.obstacle, part.motion).distance - window.margin;
      clearance[m] = std::min(c, straight);
    }
    result.push_back(std::move(clearance));
  }
  return result;
}

std::vector<sample_mask> collisions_reference(const ego_state& ego, const maneuver_samples& samples,
                                              const forecast_obstacle& obstacle, std::span<const double> forecast_times,
                                              const collision_window& window) {
  std::vector<sample_mask> sets;
  for (const double tau : forecast_times) {
    sample_mask set(samples.size());
    const std::vector<double> first = first_overlaps_reference(ego, samples, obstacle, tau, window);
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (first[m] != no_collision) set.set(m);
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

std::vector<double> first_overlaps_reference(const ego_state& ego, const maneuver_samples& samples,
                                             const forecast_obstacle& obstacle, double forecast_time,
                                             const collision_window& window) {
  const std::vector<double> times = sample_times(window.duration, window.time_step);
  const double start = straight_part_start(obstacle, forecast_time, window);
  const std::size_t sampled = first_at_or_after(times, start);
  std::vector<double> first(samples.size(), no_collision);
  for (std::size_t m = 0; m < samples.size(); ++m) {
    const maneuver& u = samples.maneuvers[m];
    const auto at = [&](double t) { return clearance_at(ego, u, obstacle, forecast_time, t, window); };
    running_minimum r;
    for (std::size_t k = 0; k < sampled; ++k) {
      const double c = at(times[k]);
      r.update(c, k);
      if (c <= 0.0) {
        first[m] = times[k];
        break;
      }
    }
    if (first[m] != no_collision) continue;
    const straight_setup part = straight_setup_of(ego, u, obstacle, forecast_time, start, window);
    if (straight_part_collides(ego.shape, part.ego, obstacle.shape, part.obstacle, part.motion, window.margin)) {
      first[m] = start + straight_part_contact(ego.shape, part.ego, obstacle.shape, part.obstacle, part.motion,
                                               window.margin);
      continue;
    }
    // Within θ at a sample time: a contact between sample times where the refined minimum is ≤ 0
    // (refined where `clearance_field::exact` refines: below the straight part's minimum + 2θ).
    const double theta = refinement_threshold(
        largest_point_speed(ego, u, window.horizon) + largest_point_speed(obstacle), window.time_step);
    if (sampled == 0 || !(r.value <= theta)) continue;
    const double straight =
        straight_part_minimum(ego.shape, part.ego, obstacle.shape, part.obstacle, part.motion).distance - window.margin;
    if (r.value < straight + 2.0 * theta && refined_minimum(times, r.argmin, at, r.at_argmin) <= 0.0) {
      first[m] = times[r.argmin];
    }
  }
  return first;
}

std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window, double proof_resolution) {
  std::vector<sample_mask> sets;
  for (const double tau : forecast_times) {
    sample_mask set(samples.size());
    const std::array<double, 1> taus{tau};
    for (std::size_t m = 0; m < samples.size(); ++m) {
      if (!verified_collision_free_reference(ego, samples.maneuvers[m], std::span(&obstacle, 1), taus, window,
                                             proof_resolution)) {
        set.set(m);
      }
    }
    sets.push_back(std::move(set));
  }
  return sets;
}

}  // namespace mm
