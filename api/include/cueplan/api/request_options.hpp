// Options as a JSON request gives them (`cueplan serve`'s `options`, {"seed": 7, ...}):
// typed reads of one field each, and the planner's and impact method's options read and
// checked by the one validator (options.hpp, impact.hpp) that the command line's flags go
// through. Every error is an InputError naming the field as the request does
// ("options.max_time").
#pragma once

#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "cueplan/api/errors.hpp"
#include "cueplan/api/field_names.hpp"
#include "cueplan/api/impact.hpp"
#include "cueplan/api/options.hpp"

namespace cueplan::api {

// Typed reads of one field; each throws InputError naming `field` when the value has
// the wrong type. `unit` (may be null) is said in the message.
double json_number(const nlohmann::ordered_json& v, const std::string& field, const char* unit);
// A whole number within an int, either way.
int json_whole(const nlohmann::ordered_json& v, const std::string& field);
// A whole number from 0 to 2^64 - 1.
uint64_t json_seed(const nlohmann::ordered_json& v, const std::string& field);
bool json_bool(const nlohmann::ordered_json& v, const std::string& field);
std::string json_text(const nlohmann::ordered_json& v, const std::string& field);

// Throws InputError naming `field` when value > most ("... at most N on this server").
void json_at_most(int value, int most, const std::string& field);

// Every key of `options` is one of `keys`; otherwise throws naming the first that is not
// ("options.KEY").
void check_request_option_keys(const nlohmann::ordered_json& options,
                               std::initializer_list<const char*> keys);

// The options a request's planner (solve, spinmap) takes: global, local,
// max_evaluations, max_time, starts, seed, noise, robust, samples, enforce_rigid_limit,
// alternatives, method, accuracy.
std::initializer_list<const char*> search_option_keys();

// The library's fields as a request names them (PlannerOptions' {"max_time_s"} ->
// "options.max_time", {"simulation", "impact_method"} -> "options.method", ...).
std::span<const FieldName> request_option_names();

// What a server lets one request ask of the planner. Beyond a bound the field is
// refused; max_time is clamped instead.
struct SearchLimits {
  double max_time_s = 20.0;
  int max_evaluations = 200000;
  int max_starts = 32;
  int max_samples = 2000;
  int max_alternatives = 10;
};

// The planner's and the impact method's options of a request, in the flags' units.
struct SearchInputs {
  PlannerArgs planner;
  ImpactArgs impact;
  bool accuracy_given = false;
  bool time_clamped = false;  // max_time asked beyond limits.max_time_s
};

// Reads a request's `options` (an object) for the planner; `default_method` is the
// impact method when none is named. Throws InputError naming the field.
SearchInputs read_search_options(const nlohmann::ordered_json& options,
                                 const std::string& default_method, const SearchLimits& limits);

// The impact method's options of `in`, checked by impact_options (errors named as the
// request names them).
physics::SimulationOptions search_simulation(const SearchInputs& in);

// The planner's options of `in` with `threads` and `simulation`, checked by the one
// validator, planner_options (errors named as the request names them).
planner::PlannerOptions search_planner_options(const SearchInputs& in, int threads,
                                               const physics::SimulationOptions& simulation);

}  // namespace cueplan::api
