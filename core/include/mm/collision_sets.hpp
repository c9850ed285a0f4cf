#pragma once

#include <span>
#include <vector>

#include "mm/collision.hpp"
#include "mm/maneuver_samples.hpp"
#include "mm/sample_mask.hpp"

namespace mm {

/// Signed distance − margin [m] between the ego executing `u` and the obstacle forecast with
/// forecast time `tau`, at time t.
double clearance_at(const ego_state& ego, const maneuver& u, const forecast_obstacle& obstacle, double tau, double t,
                    const collision_window& window);

/// Signed clearance of every sample: the smallest signed distance − margin [m] between the ego
/// executing the sample and an obstacle over the collision window. Negative ⇔ the sample collides
/// [CSS]; the magnitude lets estimators place the boundary between samples. Clamped to ±cap.
using clearance_set = std::vector<double>;

/// The ego's trajectories for every sample of a `maneuver_samples`, at every sample time of the
/// collision window, computed once per planning step and shared by all obstacles and forecast times.
class ego_sweep {
 public:
  ego_sweep(const ego_state& ego, const maneuver_samples& samples, const collision_window& window);

  const ego_state& ego() const { return ego_; }
  const maneuver_samples& samples() const { return samples_; }
  const collision_window& window() const { return window_; }
  std::size_t sample_count() const { return sample_count_; }
  const std::vector<double>& times() const { return times_; }
  /// Pose of sample m at time index k.
  const pose& at(std::size_t k, std::size_t m) const { return poses_[k * sample_count_ + m]; }
  /// (cos θ, sin θ) of that pose's heading.
  vec2 direction(std::size_t k, std::size_t m) const { return directions_[k * sample_count_ + m]; }
  /// Largest speed of any point of the ego footprint over the window [m/s]: v_max (1 + κ_max R).
  double largest_point_speed() const { return largest_point_speed_; }
  /// Largest speed of the ego's reference point over the window [m/s].
  double largest_speed() const { return largest_speed_; }

  /// A disc containing the reference points of all samples at time index k.
  vec2 reach_centre(std::size_t k) const { return reach_centre_[k]; }
  double reach_radius(std::size_t k) const { return reach_radius_[k]; }

 private:
  ego_state ego_;
  const maneuver_samples& samples_;
  collision_window window_;
  std::size_t sample_count_;
  std::vector<double> times_;
  std::vector<pose> poses_;
  std::vector<vec2> directions_;
  double largest_speed_ = 0.0;
  double largest_point_speed_ = 0.0;
  std::vector<vec2> reach_centre_;
  std::vector<double> reach_radius_;
};

/// Clearances of one obstacle for every forecast time (spec §5): entry [i][m] is the signed
/// clearance of sample m with the obstacle forecast with `forecast_times[i]` (ascending): the
/// `refined_minimum` of the signed distance − margin over the sample times of the sweep, clamped
/// to [−cap, cap].
///
/// Fast path, each step exact for the sampled times:
/// - forecasts agree up to τ, so the minimum over t ≤ τ_i is accumulated once and shared by all
///   larger τ;
/// - a time is skipped for every sample when the obstacle is beyond the cap from a disc holding
///   all of the sweep's reference points;
/// - a (sample, time) pair is skipped when a lower bound — the distance of bounding discs, or the
///   last clearance computed minus the largest relative speed of any two footprint points times
///   the elapsed time (the signed distance is Lipschitz in time) — shows it cannot lower the
///   sample's clearance below what is known, or below −cap.
/// Equal, bit for bit, to `clearances_reference` clamped to ±cap.
std::vector<clearance_set> clearances(const ego_sweep& sweep, const forecast_obstacle& obstacle,
                                      std::span<const double> forecast_times, double cap);

/// The reference for `clearances`: every sample, forecast time and sample time, no pruning, no cap;
/// the same `refined_minimum`.
std::vector<clearance_set> clearances_reference(const ego_state& ego, const maneuver_samples& samples,
                                                const forecast_obstacle& obstacle,
                                                std::span<const double> forecast_times,
                                                const collision_window& window);

/// Collision sets [CSS](τ_i) of the reference planner (spec §11), in continuous time: mask i holds
/// the samples that `verified_collision_free` cannot prove free of the obstacle forecast with
/// `forecast_times[i]` at any time in [0, T_c] — they overlap, or pass within (largest relative
/// point speed × `proof_resolution`) of it.
std::vector<sample_mask> collision_sets_reference(const ego_state& ego, const maneuver_samples& samples,
                                                  const forecast_obstacle& obstacle,
                                                  std::span<const double> forecast_times,
                                                  const collision_window& window, double proof_resolution);

}  // namespace mm
