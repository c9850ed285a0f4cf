#include "mm/plan_input_json.hpp"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace mm::capture {
namespace {

nlohmann::json pose_json(const pose& p) { return {{"x", p.position.x}, {"y", p.position.y}, {"heading", p.heading}}; }

pose pose_from(const nlohmann::json& j) {
  return {{j.at("x").get<double>(), j.at("y").get<double>()}, j.at("heading").get<double>()};
}

nlohmann::json shape_json(const footprint& shape) {
  if (const auto* r = std::get_if<rectangle>(&shape)) return {{"rectangle", {r->length, r->width}}};
  if (const auto* d = std::get_if<disc>(&shape)) return {{"disc", d->radius}};
  nlohmann::json vertices = nlohmann::json::array();
  for (const vec2& v : std::get<convex_polygon>(shape).vertices) vertices.push_back({v.x, v.y});
  return {{"polygon", vertices}};
}

footprint shape_from(const nlohmann::json& j) {
  if (j.contains("rectangle")) return rectangle{j.at("rectangle").at(0).get<double>(), j.at("rectangle").at(1).get<double>()};
  if (j.contains("disc")) return disc{j.at("disc").get<double>()};
  if (j.contains("polygon")) {
    convex_polygon polygon;
    for (const auto& v : j.at("polygon")) polygon.vertices.push_back({v.at(0).get<double>(), v.at(1).get<double>()});
    return polygon;
  }
  throw std::invalid_argument("footprint: expected one of rectangle, disc, polygon, got " + j.dump());
}

obstacle_kind kind_from(const std::string& name) {
  for (const obstacle_kind k : {obstacle_kind::vehicle, obstacle_kind::pedestrian, obstacle_kind::static_obstacle}) {
    if (to_string(k) == name) return k;
  }
  throw std::invalid_argument("obstacle kind: expected vehicle, pedestrian or static, got " + name);
}

}  // namespace

nlohmann::json to_json(const plan_input& in) {
  const ego_limits& l = in.ego.limits;
  const planner_config& c = in.config;
  nlohmann::json obstacles = nlohmann::json::array();
  for (const obstacle_track& track : in.obstacles) {
    nlohmann::json history = nlohmann::json::array();
    for (const observation& o : track.history) {
      history.push_back({{"time", o.time}, {"pose", pose_json(o.pose)}, {"speed", o.speed}});
    }
    obstacles.push_back({{"id", track.id}, {"kind", std::string(to_string(track.kind))},
                         {"shape", shape_json(track.shape)}, {"history", history}});
  }
  nlohmann::json result = {
      {"time", in.time},
      {"ego",
       {{"pose", pose_json(in.ego.pose)},
        {"speed", in.ego.speed},
        {"shape", shape_json(in.ego.shape)},
        {"limits",
         {{"max_acceleration", l.max_acceleration},
          {"max_deceleration", l.max_deceleration},
          {"max_lateral_acceleration", l.max_lateral_acceleration},
          {"min_turning_radius", l.min_turning_radius},
          {"speed_cap", l.speed_cap},
          {"steering", l.steering}}}}},
      {"nominal", {{"acceleration", in.nominal.acceleration}, {"curvature", in.nominal.curvature}}},
      {"obstacles", obstacles},
      {"config",
       {{"displacement_horizon", c.displacement_horizon},
        {"collision_window", c.collision_window},
        {"forecast_step", c.forecast_step},
        {"forecast_count", c.forecast_count},
        {"history_window", c.history_window},
        {"safety_margin", c.safety_margin},
        {"policy", std::string(to_string(c.policy.kind))},
        {"constant_forecast_time", c.policy.constant_forecast_time},
        {"effort", {c.effort.longitudinal, c.effort.lateral}},
        {"urgent_steering", c.urgent_steering},
        {"resolution", {c.resolution.accelerations, c.resolution.curvatures}},
        {"max_time_step", c.max_time_step},
        {"assignment_search", std::string(to_string(c.assignment_search))},
        {"max_exhaustive_assignments", c.max_exhaustive_assignments},
        {"record_samples", c.record_samples},
        {"map_column", c.map_column}}}};
  if (in.drivable_area) {
    nlohmann::json polygons = nlohmann::json::array();
    for (const std::vector<vec2>& polygon : in.drivable_area->polygons()) {
      nlohmann::json points = nlohmann::json::array();
      for (const vec2 v : polygon) points.push_back({v.x, v.y});
      polygons.push_back(points);
    }
    nlohmann::json open = nlohmann::json::array();
    for (const polygon_edge& e : in.drivable_area->open_edges()) open.push_back({e.polygon, e.edge});
    result["drivable_area"] = {{"polygons", polygons}, {"open_edges", open}};
  }
  return result;
}

plan_input plan_input_from_json(const nlohmann::json& j) {
  plan_input in;
  in.time = j.at("time").get<double>();
  const nlohmann::json& ego = j.at("ego");
  in.ego.pose = pose_from(ego.at("pose"));
  in.ego.speed = ego.at("speed").get<double>();
  in.ego.shape = shape_from(ego.at("shape"));
  const nlohmann::json& l = ego.at("limits");
  in.ego.limits = {l.at("max_acceleration").get<double>(), l.at("max_deceleration").get<double>(),
                   l.at("max_lateral_acceleration").get<double>(), l.at("min_turning_radius").get<double>(),
                   l.at("speed_cap").get<double>(), l.at("steering").get<bool>()};
  in.nominal = {j.at("nominal").at("acceleration").get<double>(), j.at("nominal").at("curvature").get<double>()};
  for (const nlohmann::json& o : j.at("obstacles")) {
    obstacle_track track;
    track.id = o.at("id").get<std::uint32_t>();
    track.kind = kind_from(o.at("kind").get<std::string>());
    track.shape = shape_from(o.at("shape"));
    for (const nlohmann::json& h : o.at("history")) {
      track.history.push_back({h.at("time").get<double>(), pose_from(h.at("pose")), h.at("speed").get<double>()});
    }
    in.obstacles.push_back(std::move(track));
  }
  const nlohmann::json& c = j.at("config");
  planner_config& config = in.config;
  config.displacement_horizon = c.at("displacement_horizon").get<double>();
  config.collision_window = c.at("collision_window").get<double>();
  config.forecast_step = c.at("forecast_step").get<double>();
  config.forecast_count = c.at("forecast_count").get<std::size_t>();
  config.history_window = c.at("history_window").get<double>();
  config.safety_margin = c.at("safety_margin").get<double>();
  const std::string policy = c.at("policy").get<std::string>();
  if (policy == to_string(forecast_policy_kind::adjustable)) {
    config.policy.kind = forecast_policy_kind::adjustable;
  } else if (policy == to_string(forecast_policy_kind::constant)) {
    config.policy.kind = forecast_policy_kind::constant;
  } else if (policy == to_string(forecast_policy_kind::robust)) {
    config.policy.kind = forecast_policy_kind::robust;
  } else {
    throw std::invalid_argument("config.policy: expected adj, const or robust, got " + policy);
  }
  config.policy.constant_forecast_time = c.at("constant_forecast_time").get<double>();
  config.effort = {c.at("effort").at(0).get<double>(), c.at("effort").at(1).get<double>()};
  config.urgent_steering = c.at("urgent_steering").get<bool>();
  config.resolution = {c.at("resolution").at(0).get<std::size_t>(), c.at("resolution").at(1).get<std::size_t>()};
  config.max_time_step = c.at("max_time_step").get<double>();
  const std::string search = c.at("assignment_search").get<std::string>();
  if (search == to_string(assignment_search_kind::coordinate_ascent)) {
    config.assignment_search = assignment_search_kind::coordinate_ascent;
  } else if (search == to_string(assignment_search_kind::exhaustive)) {
    config.assignment_search = assignment_search_kind::exhaustive;
  } else {
    throw std::invalid_argument("config.assignment_search: expected coordinate_ascent or exhaustive, got " + search);
  }
  config.max_exhaustive_assignments = c.at("max_exhaustive_assignments").get<std::size_t>();
  config.record_samples = c.at("record_samples").get<bool>();
  // Inputs saved before the key existed planned the whole column.
  config.map_column = c.contains("map_column") ? c.at("map_column").get<bool>() : true;
  if (j.contains("drivable_area")) {
    const nlohmann::json& area = j.at("drivable_area");
    std::vector<std::vector<vec2>> polygons;
    for (const nlohmann::json& polygon : area.at("polygons")) {
      std::vector<vec2>& points = polygons.emplace_back();
      for (const nlohmann::json& v : polygon) points.push_back({v.at(0).get<double>(), v.at(1).get<double>()});
    }
    std::vector<polygon_edge> open;
    for (const nlohmann::json& e : area.at("open_edges")) open.push_back({e.at(0).get<std::size_t>(), e.at(1).get<std::size_t>()});
    in.drivable_area = std::make_shared<const drivable_area>(std::move(polygons), open);
  }
  return in;
}

}  // namespace mm::capture
