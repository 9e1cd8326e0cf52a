#include "cueplan/api/problem_codec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <utility>


namespace cueplan::api {
namespace {

namespace phys = cueplan::physics;
namespace prob = cueplan::problems;
using nlohmann::ordered_json;

// A problem is a few levels deep (limits.speed[0]); anything much deeper is not a
// problem, and is refused before it reaches a recursive writer or parser.
constexpr int kDeepestProblem = 8;

// How deep `value` nests (a number: 0; [1]: 1; {"a": [1]}: 2), counting no further
// than `limit` + 1, without recursion.
int depth_of(const ordered_json& value, int limit) {
  std::vector<std::pair<const ordered_json*, int>> stack = {{&value, 0}};
  int deepest = 0;
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    if (!node->is_structured()) continue;
    deepest = std::max(deepest, depth + 1);
    if (deepest > limit) return deepest;
    for (const ordered_json& child : *node) stack.push_back({&child, depth + 1});
  }
  return deepest;
}

// The loader's "SOURCE:LINE: FIELD: message" without its SOURCE:LINE: FIELD: part.
std::string loader_message(const prob::LoadResult& r, const std::string& source) {
  const std::string located = source + ":" + std::to_string(r.line) + ": ";
  std::string text = r.error;
  if (text.rfind(located, 0) == 0) text.erase(0, located.size());
  if (!r.field.empty() && text.rfind(r.field + ": ", 0) == 0) text.erase(0, r.field.size() + 2);
  return text;
}

// A YAML 1.2 core-schema number as the loader reads one (a digit or a point first,
// after an optional sign; no hex, no "inf", no "1_000"); nothing otherwise.
std::optional<ordered_json> yaml_number(const std::string& text) {
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const std::string_view digits = !s.empty() && s.front() == '-' ? s.substr(1) : s;
  if (digits.empty() || !(std::isdigit(static_cast<unsigned char>(digits.front())) ||
                          digits.front() == '.'))
    return std::nullopt;
  if (digits.find_first_of(".eE") == std::string_view::npos) {
    int64_t whole = 0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), whole);
    if (error == std::errc() && end == s.data() + s.size()) return ordered_json(whole);
  }
  double value = 0.0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (error != std::errc() || end != s.data() + s.size() || !std::isfinite(value))
    return std::nullopt;
  return ordered_json(value);
}

ordered_json json_of(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      ordered_json object = ordered_json::object();
      for (auto it = node.begin(); it != node.end(); ++it)
        object[it->first.Scalar()] = json_of(it->second);
      return object;
    }
    case YAML::NodeType::Sequence: {
      ordered_json array = ordered_json::array();
      for (const YAML::Node& item : node) array.push_back(json_of(item));
      return array;
    }
    case YAML::NodeType::Scalar:
      if (node.Tag() == "?")
        if (std::optional<ordered_json> number = yaml_number(node.Scalar())) return *number;
      return node.Scalar();
    default:
      return nullptr;
  }
}

ordered_json point(phys::Vec2 p) { return {p.x, p.y}; }

// "snooker", "pool" or "carom": which markings a drawing of the table shows.
const char* table_kind(const phys::Scene& scene) {
  if (scene.pockets.empty()) return "carom";
  return scene.length >= 3.0 ? "snooker" : "pool";
}

// The pockets' names: the standard six by kPocketNames, any others by number.
// The pockets' names in problem files (the problems library's, jawed or not).
std::vector<std::string> pocket_names(const phys::Scene& scene) {
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.pockets.size(); ++i)
    names.push_back(prob::pocket_name(scene, static_cast<int>(i)));
  return names;
}

ordered_json aim_json(const prob::AimLimit& aim) {
  switch (aim.mode) {
    case prob::AimMode::free: return "free";
    case prob::AimMode::fixed: return aim.lo_deg;
    case prob::AimMode::range: return {aim.lo_deg, aim.hi_deg};
  }
  return "free";
}

}  // namespace

ProblemFromJson problem_from_json(const ordered_json& value, const std::string& prefix) {
  ProblemFromJson out;
  if (!value.is_object()) {
    out.error = {prefix, prefix + " must be an object of the problem file's fields (problems/README.md), "
                         "such as {\"cue_ball\": [0.8, 0.5], \"target\": [2.6, 1.2]}"};
    return out;
  }
  if (depth_of(value, kDeepestProblem) > kDeepestProblem) {
    out.error = {prefix, prefix + " nests deeper than any problem file (" +
                             std::to_string(kDeepestProblem) + " levels)"};
    return out;
  }
  // One field a line, so that the loader's lines stay short; the text is JSON, which
  // the YAML loader reads as flow mappings and sequences.
  const std::string source = "request";
  const std::string text = value.dump(1, ' ', false, ordered_json::error_handler_t::replace);
  prob::LoadResult loaded = prob::parse_problem(text, source);
  if (loaded.ok()) {
    out.problem = std::move(*loaded.problem);
    return out;
  }
  const bool whole = loaded.field.empty() || loaded.field == "(document)" || loaded.field == "yaml";
  out.error.field = whole ? prefix : prefix + "." + loaded.field;
  out.error.message = out.error.field + ": " + loader_message(loaded, source);
  return out;
}

std::optional<ordered_json> problem_yaml_to_json(std::string_view yaml, std::string* error) {
  try {
    const YAML::Node root = YAML::Load(std::string(yaml));
    if (!root.IsMap()) {
      *error = "not a mapping of fields";
      return std::nullopt;
    }
    return json_of(root);
  } catch (const YAML::Exception& e) {
    *error = e.what();
    return std::nullopt;
  }
}

ordered_json scene_json(const prob::Problem& problem) {
  const phys::Scene& scene = problem.scene;
  ordered_json pockets = ordered_json::array();
  const std::vector<std::string> names = pocket_names(scene);
  for (size_t i = 0; i < scene.pockets.size(); ++i) {
    ordered_json pocket = {{"name", names[i]},
                           {"centre", point(scene.pockets[i].centre)},
                           {"radius", scene.pockets[i].radius}};
    // A jawed pocket's geometry (PHYSICS.md, "Jawed pockets"), index 0 the left side
    // as seen from the table: the shape, the unrounded nose corners, the points'
    // rounding centres, the facings from their tangent points to the hole's depth, where
    // each straight cushion nose ends, and the hole.
    if (const auto& j = scene.pockets[i].jaws) {
      ordered_json facings = ordered_json::array();
      for (int k = 0; k < 2; ++k) {
        const phys::Vec2 end{j->facing_start[k].x + j->facing_length[k] * j->facing_dir[k].x,
                             j->facing_start[k].y + j->facing_length[k] * j->facing_dir[k].y};
        facings.push_back({{"start", point(j->facing_start[k])}, {"end", point(end)}});
      }
      pocket["jaws"] = {{"mouth", j->shape.mouth},
                        {"wall_angle_deg", j->shape.wall_angle_deg},
                        {"shelf", j->shape.shelf},
                        {"hole_radius", j->shape.hole_radius},
                        {"point_radius", j->shape.point_radius},
                        {"inward", point(j->inward)},
                        {"corners", {point(j->corner[0]), point(j->corner[1])}},
                        {"point_centres", {point(j->point_centre[0]), point(j->point_centre[1])}},
                        {"nose_ends", {point(j->nose_tangent[0]), point(j->nose_tangent[1])}},
                        {"facings", facings},
                        {"hole_centre", point(j->hole_centre)}};
    }
    pockets.push_back(pocket);
  }
  ordered_json obstacles = ordered_json::array();
  for (const phys::Vec2& o : scene.obstacles) obstacles.push_back(point(o));
  const prob::Limits& l = problem.limits;
  ordered_json j;
  j["kind"] = table_kind(scene);
  j["length"] = scene.length;
  j["width"] = scene.width;
  j["ball_radius"] = scene.radius();
  j["contact_offset"] = scene.contact_offset();
  j["cushion_height"] = scene.ball_and_cushion.cushion_height;
  j["pockets"] = pockets;
  j["obstacles"] = obstacles;
  j["cue_ball"] = point(problem.cue_ball);
  j["target"] = point(problem.target);
  j["tolerance"] = problem.tolerance;
  j["limits"] = {{"speed", {l.speed_min, l.speed_max}},
                 {"spin", l.spin_max},
                 {"aim_deg", aim_json(l.aim)},
                 {"cushions", {l.cushions_min, l.cushions_max}}};
  return j;
}

}  // namespace cueplan::api
