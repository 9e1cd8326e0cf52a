// Problem files into a Problem: each section read in the order the format lists them,
// then the physics' own checks on the finished scene and positions (problems/README.md).
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>

#include "cueplan/problems/problem.hpp"
#include "yaml_fields.hpp"

namespace cueplan::problems {
namespace {

using detail::Field;
using detail::FieldError;
using detail::Mapping;
using FieldLines = std::map<std::string, int>;  // path in the file -> line

constexpr const char* kDocument = "(document)";

// The file's fields behind the names Scene::validate and check_position use.
constexpr std::array<std::pair<std::string_view, std::string_view>, 6> kPhysicsNames{{
    {"mass", "ball.mass"},
    {"radius", "ball.radius"},
    {"cushion_height", "physics.cushion_height"},
    {"mu_cushion", "physics.mu_cushion"},
    {"mu_table", "physics.mu_slide"},  // one ball-cloth friction in the file
    {"restitution", "physics.restitution"},
}};

std::string file_field(const std::string& physics_name) {
  for (const auto& [name, field] : kPhysicsNames) {
    if (physics_name == name) return std::string(field);
  }
  if (physics_name.starts_with("pockets[")) return "table.pocket_radius";
  return physics_name;  // table.length, physics.mu_roll, obstacles[2], cue_ball, ...
}

// Line of `field`, or of the nearest enclosing field the file gives; else `fallback`.
int line_in_file(std::string field, const FieldLines& lines, int fallback) {
  while (!field.empty()) {
    if (const auto it = lines.find(field); it != lines.end()) return it->second;
    const std::size_t cut = field.find_last_of(".[");
    if (cut == std::string::npos) break;
    field.resize(cut);
  }
  return fallback;
}

// A message from the physics checks ("mass must be positive ...") as a FieldError on
// the file's field, with the physics' leading name dropped where it only repeats it.
[[noreturn]] void fail_from_physics(const std::string& message, const FieldLines& lines,
                                    int fallback_line) {
  const std::size_t space = message.find(' ');
  const std::string name = message.substr(0, space);
  std::string field = file_field(name);
  // A table too small for the ball: blame whichever of the two the file sets.
  if (message.starts_with("table.length and table.width") && !lines.contains("table.length"))
    field = lines.contains("table.width") || !lines.contains("ball.radius") ? "table.width"
                                                                              : "ball.radius";
  std::string rest = space == std::string::npos ? message : message.substr(space + 1);
  if (rest.starts_with("and ")) rest = message;  // "table.length and table.width must ..."
  throw FieldError{line_in_file(field, lines, fallback_line), field, rest};
}

std::string read_name(const Mapping& root, const std::string& source) {
  if (const std::optional<Field> field = root.find("name")) {
    std::string name = detail::text(*field);
    if (name.empty()) detail::fail(*field, "must not be empty");
    return name;
  }
  std::string stem = std::filesystem::path(source).stem().string();
  return stem.empty() ? std::string("problem") : stem;
}

// table: length, width (m), pockets (standard | none), pocket_radius (m).
void read_table(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  double pocket_radius = kDefaultPocketRadius;
  bool standard_pockets = true;
  if (const std::optional<Field> table = root.find("table")) {
    const Mapping m(*table, {"length", "width", "pockets", "pocket_radius"}, lines);
    if (auto f = m.find("length")) scene.length = detail::positive_number(*f);
    if (auto f = m.find("width")) scene.width = detail::positive_number(*f);
    if (auto f = m.find("pockets")) {
      if (detail::is_word(*f, "none"))
        standard_pockets = false;
      else if (!detail::is_word(*f, "standard"))
        detail::fail(*f, "must be standard or none, got " + detail::describe_value(f->value));
    }
    if (auto f = m.find("pocket_radius")) pocket_radius = detail::positive_number(*f);
  }
  scene.pockets.clear();
  if (!standard_pockets) return;
  // Four corners and the middles of the long cushions y = 0 and y = width.
  const double l = scene.length, w = scene.width;
  for (const physics::Vec2 centre : {physics::Vec2{0.0, 0.0}, physics::Vec2{l / 2, 0.0},
                                     physics::Vec2{l, 0.0}, physics::Vec2{0.0, w},
                                     physics::Vec2{l / 2, w}, physics::Vec2{l, w}})
    scene.pockets.push_back({centre, pocket_radius});
}

// ball: radius (m), mass (kg). Keeps the rest of the cushion parameters at their defaults.
void read_ball(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  physics::CushionParams& ball = scene.ball_and_cushion;
  if (const std::optional<Field> field = root.find("ball")) {
    const Mapping m(*field, {"radius", "mass"}, lines);
    if (auto f = m.find("radius")) ball.radius = detail::positive_number(*f);
    if (auto f = m.find("mass")) ball.mass = detail::positive_number(*f);
  }
  // The cushion nose sits at 7R/5 unless physics.cushion_height says otherwise.
  ball.cushion_height = physics::params_for_radius(ball.radius).cushion_height;
}

// physics: cloth and cushion coefficients; mu_slide is both the cloth's sliding
// friction and the impact model's ball-table friction.
void read_physics(const Mapping& root, FieldLines& lines, physics::Scene& scene) {
  const std::optional<Field> field = root.find("physics");
  if (!field) return;
  const Mapping m(*field,
                  {"mu_slide", "mu_roll", "mu_spin", "mu_cushion", "restitution",
                   "cushion_height", "gravity"},
                  lines);
  physics::CushionParams& cushion = scene.ball_and_cushion;
  physics::ClothParams& cloth = scene.cloth;
  if (auto f = m.find("mu_slide")) cloth.mu_slide = cushion.mu_table = detail::positive_number(*f);
  if (auto f = m.find("mu_roll")) cloth.mu_roll = detail::positive_number(*f);
  if (auto f = m.find("mu_spin")) cloth.mu_spin = detail::non_negative_number(*f);
  if (auto f = m.find("mu_cushion")) cushion.mu_cushion = detail::non_negative_number(*f);
  if (auto f = m.find("restitution")) cushion.restitution = detail::positive_number(*f);
  if (auto f = m.find("cushion_height")) cushion.cushion_height = detail::positive_number(*f);
  if (auto f = m.find("gravity")) cloth.gravity = detail::positive_number(*f);
}

void read_obstacles(const Mapping& root, physics::Scene& scene, FieldLines& lines) {
  const std::optional<Field> field = root.find("obstacles");
  if (!field) return;
  for (const Field& obstacle : detail::sequence(*field, 0, "a list of points [x, y] in m")) {
    lines[obstacle.path] = obstacle.line;
    scene.obstacles.push_back(detail::point(obstacle));
  }
}

// A ball position the scene accepts: on the cloth, clear of pockets and obstacles.
physics::Vec2 read_position(const Mapping& root, std::string_view key, std::string_view meaning,
                            const physics::Scene& scene) {
  const Field field = root.require(key, meaning);
  const physics::Vec2 position = detail::point(field);
  if (const std::string why = scene.check_position(position, field.path); !why.empty())
    fail_from_physics(why, {{field.path, field.line}}, field.line);
  return position;
}

// limits.speed [min, max] m/s, spin, aim_deg (free | phi | [lo, hi]), cushions (n | [lo, hi]).
Limits read_limits(const Mapping& root, FieldLines& lines) {
  Limits limits;
  const std::optional<Field> field = root.find("limits");
  if (!field) return limits;
  const Mapping m(*field, {"speed", "spin", "aim_deg", "cushions"}, lines);

  if (const std::optional<Field> speed = m.find("speed")) {
    const auto bounds = detail::sequence(*speed, 2, "[min, max] in m/s");
    limits.speed_min = detail::positive_number(bounds[0]);
    limits.speed_max = detail::positive_number(bounds[1]);
    if (!(limits.speed_min < limits.speed_max))
      detail::fail(*speed, "min must be below max, got [" + bounds[0].value.Scalar() + ", " +
                               bounds[1].value.Scalar() + "]");
  }
  if (const std::optional<Field> spin = m.find("spin"))
    limits.spin_max = detail::positive_number(*spin);

  if (const std::optional<Field> aim = m.find("aim_deg")) {
    if (detail::is_word(*aim, "free")) {
      limits.aim = {AimMode::free, 0.0, 0.0};
    } else if (aim->value.IsSequence()) {
      const auto bounds = detail::sequence(*aim, 2, "free, an angle, or [lo, hi] in deg");
      const double lo = detail::number(bounds[0]), hi = detail::number(bounds[1]);
      if (!(lo < hi) || hi - lo > 360.0)
        detail::fail(*aim, "needs lo < hi <= lo + 360 (deg), got [" + bounds[0].value.Scalar() +
                               ", " + bounds[1].value.Scalar() + "]");
      limits.aim = {AimMode::range, lo, hi};
    } else if (aim->value.IsScalar() && aim->value.Tag() == "?" &&
               !aim->value.Scalar().empty() &&
               std::isalpha(static_cast<unsigned char>(aim->value.Scalar().front()))) {
      detail::fail(*aim, "must be free, an angle, or [lo, hi] in deg, got " +
                             detail::describe_value(aim->value));
    } else {
      const double phi = detail::number(*aim);
      limits.aim = {AimMode::fixed, phi, phi};
    }
  }

  if (const std::optional<Field> cushions = m.find("cushions")) {
    constexpr int kMost = 1000;
    if (cushions->value.IsSequence()) {
      const auto bounds = detail::sequence(*cushions, 2, "a count n or a range [lo, hi]");
      limits.cushions_min = detail::whole_number(bounds[0], 0, kMost);
      limits.cushions_max = detail::whole_number(bounds[1], 0, kMost);
      if (limits.cushions_min > limits.cushions_max)
        detail::fail(*cushions, "lo must not exceed hi, got [" + bounds[0].value.Scalar() + ", " +
                                    bounds[1].value.Scalar() + "]");
    } else {
      limits.cushions_min = limits.cushions_max = detail::whole_number(*cushions, 0, kMost);
    }
  }
  return limits;
}

// The most strokes a route may take (max_strokes).
constexpr int kMostStrokes = 100;

// The stages of reading one problem, in order.
Problem read_problem(const Field& document, const std::string& source) {
  FieldLines lines;
  const Mapping root(document,
                     {"name", "table", "ball", "physics", "cue_ball", "target", "tolerance",
                      "obstacles", "limits", "max_strokes", "time_budget_s"},
                     lines);
  Problem problem;
  problem.source = source;
  problem.name = read_name(root, source);

  physics::Scene& scene = problem.scene;
  read_table(root, lines, scene);
  read_ball(root, lines, scene);
  read_physics(root, lines, scene);
  read_obstacles(root, scene, lines);
  if (const std::string why = scene.validate(); !why.empty())
    fail_from_physics(why, lines, root.line());

  problem.cue_ball = read_position(root, "cue_ball", "the cue ball's centre [x, y] in m", scene);
  problem.target =
      read_position(root, "target", "where the cue ball should stop, [x, y] in m", scene);
  if (const std::optional<Field> f = root.find("tolerance"))
    problem.tolerance = detail::positive_number(*f);
  problem.limits = read_limits(root, lines);
  if (const std::optional<Field> f = root.find("max_strokes"))
    problem.max_strokes = detail::whole_number(*f, 1, kMostStrokes);
  if (const std::optional<Field> f = root.find("time_budget_s"))
    problem.time_budget_s = detail::positive_number(*f);
  return problem;
}

std::string located(const std::string& source, int line, const std::string& field,
                    const std::string& message) {
  std::string where = source + ":";
  if (line > 0) where += std::to_string(line) + ":";
  return where + " " + field + ": " + message;
}

LoadResult failure(std::string error) { return {std::nullopt, std::move(error)}; }

// Where the first node of a YAML document starts; the rest of the events are ignored.
class FirstNodeLine : public YAML::EventHandler {
 public:
  int line() const { return line_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { see(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { see(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    see(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    see(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    see(mark);
  }
  void OnMapEnd() override {}

 private:
  void see(const YAML::Mark& mark) {
    if (line_ == 0) line_ = mark.is_null() ? 1 : mark.line + 1;
  }
  int line_ = 0;
};

// The line at which a second YAML document starts in `text`, or 0 when there is none.
// Throws YAML exceptions for syntax errors in the first two documents. (YAML::LoadAll
// is not used: yaml-cpp 0.7 can loop forever in it on malformed text, jbeder/yaml-cpp
// pull request 1319; here the parser is asked for two documents at most.)
int second_document_line(const std::string& text) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  FirstNodeLine first;
  if (!parser.HandleNextDocument(first)) return 0;
  FirstNodeLine second;
  if (!parser.HandleNextDocument(second)) return 0;
  return second.line() > 0 ? second.line() : 1;
}

}  // namespace

LoadResult parse_problem(const std::string& yaml_text, const std::string& source_name) {
  try {
    const int second_line = second_document_line(yaml_text);
    const YAML::Node root = YAML::Load(yaml_text);
    if (root.IsNull())
      return failure(located(source_name, 1, kDocument,
                             "is empty; a problem needs at least cue_ball and target"));
    if (second_line > 0)
      return failure(located(source_name, second_line, kDocument,
                             "holds a second YAML document; one problem per file"));
    const int line = detail::line_of(root) > 0 ? detail::line_of(root) : 1;
    if (!root.IsMap())
      return failure(located(source_name, line, kDocument,
                             "must be a mapping of fields (name, table, ..., limits), got " +
                                 detail::describe_value(root)));
    return {read_problem({root, "", line}, source_name), {}};
  } catch (const FieldError& e) {
    return failure(located(source_name, e.line, e.field.empty() ? kDocument : e.field, e.message));
  } catch (const YAML::Exception& e) {
    // Syntax errors: yaml-cpp counts lines and columns from 0.
    const int line = e.mark.is_null() ? 0 : e.mark.line + 1;
    std::string message = detail::printable(e.msg);
    if (!e.mark.is_null()) message += " (column " + std::to_string(e.mark.column + 1) + ")";
    return failure(located(source_name, line, "yaml", message));
  } catch (const std::exception& e) {
    return failure(source_name + ": cannot be read: " + detail::printable(e.what()));
  } catch (...) {
    return failure(source_name + ": cannot be read: unknown error");
  }
}

LoadResult load_problem(const std::string& path) {
  try {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      return failure(path + ": is a directory, not a problem file");
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      const int error = errno;
      return failure(path + ": cannot open: " +
                     (error != 0 ? std::generic_category().message(error) : "unknown error"));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return failure(path + ": cannot read");
    return parse_problem(text.str(), path);
  } catch (const std::exception& e) {
    return failure(path + ": cannot be read: " + e.what());
  }
}

}  // namespace cueplan::problems
