// The problems codec: a problem to and from JSON, as every face takes and gives one. A
// problem is the problem file's fields as a JSON object (problems/README.md), read by the
// same loader as the files - JSON is YAML's flow syntax, so the object is written out and
// parsed as a file would be, and every check and message of the loader applies, unknown
// keys included.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "cueplan/problems/problem.hpp"

namespace cueplan::api {

// A bad part of a request: the field as the request names it ("problem.table.length",
// "options.max_time", "stroke.speed"; empty for the request as a whole) and the message,
// which names the field the same way.
struct RequestError {
  std::string field;
  std::string message;
};

// The request's `problem` (the value itself; `prefix` names it in errors, "problem"),
// loaded: the problem, or the loader's error with its field under the prefix.
struct ProblemFromJson {
  std::optional<problems::Problem> problem;
  RequestError error;  // when there is no problem
};
ProblemFromJson problem_from_json(const nlohmann::ordered_json& value, const std::string& prefix);

// A problem file's YAML as a JSON object of the same fields: mappings become objects,
// sequences arrays, plain scalars that YAML reads as numbers become numbers and every
// other scalar a string. Empty (and *error set) when the text is not YAML.
std::optional<nlohmann::ordered_json> problem_yaml_to_json(std::string_view yaml,
                                                           std::string* error);

// What a page needs to draw a problem's table, resolved from the loaded problem (every
// default applied): kind (snooker, pool or carom, for the markings: carom without
// pockets, snooker from 3 m long, pool below), length, width, ball_radius,
// contact_offset (where a ball's centre meets a cushion nose), cushion_height, pockets
// [{name, centre, radius}], obstacles [[x, y]], cue_ball, target, tolerance and limits
// {speed [min, max], spin, aim_deg ("free", a number or [lo, hi]), cushions [min, max]}.
// Metres, m/s and degrees, in the table frame.
nlohmann::ordered_json scene_json(const problems::Problem& problem);

}  // namespace cueplan::api
