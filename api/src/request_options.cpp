#include "cueplan/api/request_options.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cueplan::api {
namespace {

using nlohmann::ordered_json;

constexpr std::initializer_list<const char*> kSearchOptions = {
    "global", "local", "max_evaluations", "max_time", "starts", "seed", "noise",
    "robust", "samples", "enforce_rigid_limit", "alternatives", "method", "accuracy"};

// The library's fields as a request names them: what the validator names its errors by.
const std::initializer_list<FieldName> kOptionNames = {
    {{"global"}, "options.global"},
    {{"local"}, "options.local"},
    {{"max_evaluations"}, "options.max_evaluations"},
    {{"max_time_s"}, "options.max_time"},
    {{"local_starts"}, "options.starts"},
    {{"seed"}, "options.seed"},
    {{"noise", "scale"}, "options.noise"},
    {{"robust"}, "options.robust"},
    {{"robustness_samples"}, "options.samples"},
    {{"enforce_rigid_limit"}, "options.enforce_rigid_limit"},
    {{"max_alternatives"}, "options.alternatives"},
    {{"simulation", "impact_method"}, "options.method"},
    {{"simulation", "impact_accuracy"}, "options.accuracy"},
};

std::string listed(std::initializer_list<const char*> keys) {
  std::string text;
  for (const char* k : keys) text += (text.empty() ? "" : ", ") + std::string(k);
  return text;
}

}  // namespace

double json_number(const ordered_json& v, const std::string& field, const char* unit) {
  if (!v.is_number())
    throw InputError(field, field + " must be a number" +
                                (unit ? std::string(" (") + unit + ")" : "") + ", got " + v.dump());
  return v.get<double>();
}

int json_whole(const ordered_json& v, const std::string& field) {
  const double x = v.is_number() ? v.get<double>() : NAN;
  if (!v.is_number() || x != std::floor(x) || std::abs(x) > std::numeric_limits<int>::max())
    throw InputError(field, field + " must be a whole number (at most 2147483647 either way), got " +
                                v.dump());
  return static_cast<int>(x);
}

uint64_t json_seed(const ordered_json& v, const std::string& field) {
  if (v.is_number_unsigned()) return v.get<uint64_t>();
  if (v.is_number_integer() && v.get<int64_t>() >= 0) return static_cast<uint64_t>(v.get<int64_t>());
  throw InputError(field, field + " must be a whole number from 0 to 18446744073709551615, got " +
                              v.dump());
}

bool json_bool(const ordered_json& v, const std::string& field) {
  if (!v.is_boolean()) throw InputError(field, field + " must be true or false, got " + v.dump());
  return v.get<bool>();
}

std::string json_text(const ordered_json& v, const std::string& field) {
  if (!v.is_string()) throw InputError(field, field + " must be a string, got " + v.dump());
  return v.get<std::string>();
}

void json_at_most(int value, int most, const std::string& field) {
  if (value > most)
    throw InputError(field, field + " must be at most " + std::to_string(most) +
                                " on this server, got " + std::to_string(value));
}

void check_request_option_keys(const ordered_json& options, std::initializer_list<const char*> keys) {
  for (const auto& [key, value] : options.items())
    if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; }))
      throw InputError("options." + key,
                       "unknown field 'options." + key + "'; the options are " + listed(keys));
}

std::initializer_list<const char*> search_option_keys() { return kSearchOptions; }

std::span<const FieldName> request_option_names() { return kOptionNames; }

SearchInputs read_search_options(const ordered_json& options, const std::string& default_method,
                                 const SearchLimits& limits) {
  check_request_option_keys(options, kSearchOptions);
  SearchInputs in;
  in.impact.method = default_method;
  for (const auto& [key, v] : options.items()) {
    const std::string field = "options." + key;
    if (key == "global") in.planner.global = json_text(v, field);
    if (key == "local") in.planner.local = json_text(v, field);
    if (key == "max_evaluations") {
      in.planner.max_evaluations = json_whole(v, field);
      json_at_most(in.planner.max_evaluations, limits.max_evaluations, field);
    }
    if (key == "max_time") {
      const double t = json_number(v, field, "s");
      in.time_clamped = t > limits.max_time_s;
      in.planner.max_time_s = std::min(t, limits.max_time_s);
    }
    if (key == "starts") {
      in.planner.starts = json_whole(v, field);
      json_at_most(in.planner.starts, limits.max_starts, field);
    }
    if (key == "seed") in.planner.seed = json_seed(v, field);
    if (key == "noise") in.planner.noise = json_number(v, field, nullptr);
    if (key == "robust") in.planner.robust = json_bool(v, field);
    if (key == "samples") {
      in.planner.samples = json_whole(v, field);
      json_at_most(in.planner.samples, limits.max_samples, field);
    }
    if (key == "enforce_rigid_limit") in.planner.enforce_rigid_limit = json_bool(v, field);
    if (key == "alternatives") {
      in.planner.alternatives = json_whole(v, field);
      json_at_most(in.planner.alternatives, limits.max_alternatives, field);
    }
    if (key == "method") in.impact.method = json_text(v, field);
    if (key == "accuracy") {
      in.impact.accuracy = json_number(v, field, nullptr);
      in.accuracy_given = true;
    }
  }
  // The planner's time budget never exceeds the server's.
  in.planner.max_time_s = std::min(in.planner.max_time_s, limits.max_time_s);
  return in;
}

physics::SimulationOptions search_simulation(const SearchInputs& in) {
  physics::SimulationOptions simulation;
  impact_options(in.impact, kOptionNames, &simulation);
  return simulation;
}

planner::PlannerOptions search_planner_options(const SearchInputs& in, int threads,
                                               const physics::SimulationOptions& simulation) {
  return planner_options(in.planner, threads, simulation, kOptionNames);
}

}  // namespace cueplan::api
