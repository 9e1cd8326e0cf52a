// libFuzzer target: problems::parse_problem on arbitrary text.
//
// Beyond "no crash, hang or leak" (the sanitizers and libFuzzer watch those), every
// input must keep the loader's contract (problems/include/cueplan/problems/problem.hpp):
//   - exactly one of a problem or an error;
//   - an error is one line of the form "<fuzz>:LINE: FIELD: message" with LINE >= 1
//     and FIELD a path into the file such as table.length or limits.speed[1], or
//     "yaml" or "(document)";
//   - an accepted problem holds finite numbers the scene's own checks accept.
// A broken promise aborts, which libFuzzer reports as a crash with the input saved.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cueplan/problems/problem.hpp"

namespace {

constexpr const char* kSource = "<fuzz>";

[[noreturn]] void broken(const char* promise, const std::string& detail) {
  std::fprintf(stderr, "problem_loader_fuzzer: %s\n  %s\n", promise, detail.c_str());
  std::abort();
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// A field path: words of [a-z_] joined by '.', each optionally followed by [N] indices;
// or "yaml" or "(document)". Unknown keys are shown as written, so any printable text
// without ": " is allowed between the dots, as long as it is one line.
bool is_field(const std::string& field) {
  if (field.empty()) return false;
  for (const char c : field)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  return field.find(": ") == std::string::npos;
}

void check_error(const std::string& error) {
  if (error.find('\n') != std::string::npos || error.find('\r') != std::string::npos)
    broken("an error is one line", error);
  const std::string prefix = std::string(kSource) + ":";
  if (error.rfind(prefix, 0) != 0) broken("an error starts with the source name", error);
  std::size_t at = prefix.size();
  const std::size_t digits_begin = at;
  while (at < error.size() && is_digit(error[at])) ++at;
  if (at == digits_begin || error[digits_begin] == '0' || at >= error.size() || error[at] != ':')
    broken("an error gives a line number from 1 after the source", error);
  if (error.compare(at, 2, ": ") != 0) broken("a space follows SOURCE:LINE:", error);
  at += 2;
  // FIELD runs up to the next ": " (a field never holds one; see is_field).
  const std::size_t field_end = error.find(": ", at);
  if (field_end == std::string::npos) broken("an error names a field before ': '", error);
  const std::string field = error.substr(at, field_end - at);
  if (!is_field(field)) broken("the named field is a path, yaml or (document)", error);
  if (field_end + 2 >= error.size()) broken("an error has a message after the field", error);
}

bool finite(cueplan::physics::Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

void check_problem(const cueplan::problems::Problem& problem) {
  using cueplan::physics::Vec2;
  const auto& scene = problem.scene;
  const auto& ball = scene.ball_and_cushion;
  const auto& limits = problem.limits;
  for (const double value :
       {scene.length, scene.width, ball.mass, ball.radius, ball.cushion_height, ball.mu_cushion,
        ball.mu_table, ball.restitution, scene.cloth.mu_slide, scene.cloth.mu_roll,
        scene.cloth.mu_spin, scene.cloth.gravity, problem.tolerance, limits.speed_min,
        limits.speed_max, limits.spin_max, limits.aim.lo_deg, limits.aim.hi_deg})
    if (!std::isfinite(value)) broken("an accepted problem holds finite numbers", problem.name);
  for (const auto& pocket : scene.pockets)
    if (!finite(pocket.centre) || !std::isfinite(pocket.radius))
      broken("an accepted problem holds finite pockets", problem.name);
  for (const Vec2 obstacle : scene.obstacles)
    if (!finite(obstacle)) broken("an accepted problem holds finite obstacles", problem.name);
  if (const auto e = scene.validate()) broken("an accepted scene passes Scene::validate", e->message());
  if (const auto e = scene.check_position(problem.cue_ball, {"cue_ball"}))
    broken("an accepted cue ball passes Scene::check_position", e->message());
  if (const auto e = scene.check_position(problem.target, {"target"}))
    broken("an accepted target passes Scene::check_position", e->message());
  if (const auto e = cueplan::problems::validate(problem))
    broken("an accepted problem passes problems::validate", e->message());
  if (!(problem.tolerance > 0.0)) broken("an accepted tolerance is positive", problem.name);
  if (!(limits.speed_min > 0.0 && limits.speed_min < limits.speed_max))
    broken("accepted speed limits satisfy 0 < min < max", problem.name);
  if (!(limits.spin_max > 0.0)) broken("an accepted spin limit is positive", problem.name);
  if (!(limits.cushions_min >= 0 && limits.cushions_min <= limits.cushions_max))
    broken("accepted cushion limits satisfy 0 <= min <= max", problem.name);
  if (problem.name.empty()) broken("an accepted problem has a name", problem.source);
  if (problem.source != kSource) broken("an accepted problem keeps its source", problem.source);
  // describe() is what `cueplan solve` prints first; it must not fail on what loads.
  if (cueplan::problems::describe(problem).empty())
    broken("an accepted problem can be described", problem.name);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const cueplan::problems::LoadResult result = cueplan::problems::parse_problem(text, kSource);
  if (result.ok() == !result.error.empty())
    broken("exactly one of a problem or an error", result.error);
  if (result.ok())
    check_problem(*result.problem);
  else
    check_error(result.error);
  return 0;
}
