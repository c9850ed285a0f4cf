#pragma once

#include <span>
#include <vector>

#include "mm/collision.hpp"
#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// The ego's trajectories for every sample of a `maneuver_samples`, at every sample time of the
/// collision window, computed once per planning step and shared by all obstacles and forecast times.
class ego_sweep {
 public:
  ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window);

  const ego_state& ego() const { return ego_; }
  const collision_window& window() const { return window_; }
  std::size_t sample_count() const { return sample_count_; }
  const std::vector<double>& times() const { return times_; }
  /// Pose of sample m at time index k.
  const pose& at(std::size_t k, std::size_t m) const { return poses_[k * sample_count_ + m]; }

  /// A disc containing the reference points of all samples at time index k.
  vec2 reach_centre(std::size_t k) const { return reach_centre_[k]; }
  double reach_radius(std::size_t k) const { return reach_radius_[k]; }

 private:
  ego_state ego_;
  collision_window window_;
  std::size_t sample_count_;
  std::vector<double> times_;
  std::vector<pose> poses_;
  std::vector<vec2> reach_centre_;
  std::vector<double> reach_radius_;
};

/// Collision sets [CSS](τ_i) of one obstacle for every forecast time (spec §5): mask i holds the
/// samples whose trajectory overlaps the obstacle, forecast with `forecast_times[i]`, at a sample
/// time of the sweep. `forecast_times` must be ascending.
///
/// Fast path: forecasts agree up to τ, so the hits of t ≤ τ_i are accumulated once and shared by
/// all larger τ; a disc around the whole sweep and a disc per sample reject far pairs before the
/// exact footprint test; a sample already known to collide is not tested again. Same result, bit
/// for bit, as `collision_sets_reference` on the same samples and time step.
std::vector<sample_mask> collision_sets(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                        std::span<const double> forecast_times);

/// The reference for `collision_sets` (spec §11): each sample and forecast time on its own, the
/// exact test at every sample time of `window`.
std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window);

}  // namespace mm
