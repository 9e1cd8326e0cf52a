// The problems `cueplan serve` ships; a problem to and from JSON is the api's problems
// codec (cueplan/api/problem_codec.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/api/problem_codec.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::server {
using namespace cueplan::api;  // the api's types and checks, as the server's own

using api::ProblemFromJson;
using api::RequestError;
using api::problem_from_json;
using api::problem_yaml_to_json;
using api::scene_json;

// A shipped problem (problems/*.yaml, carried in the binary).
struct Example {
  std::string name;                // the problem's name
  std::string file;                // e.g. "one_rail_position.yaml" (a label, never opened)
  nlohmann::ordered_json problem;  // the file's fields as JSON, `name` included
  problems::Problem loaded;
};

// Every shipped problem; empty with *error set if one does not load (a build defect).
std::vector<Example> shipped_examples(std::string* error);

}  // namespace cueplan::server
