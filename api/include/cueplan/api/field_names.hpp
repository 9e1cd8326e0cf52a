// Library fields in the command line's words.
//
// Every library reports bad input as a physics::ValidationError whose path names a
// field of its own structs ({"mu_table"}, {"noise", "scale"}, {"shot", "speed"}). A
// command keeps a table of the fields it sets from its flags (or CSV columns) and
// shows the error under those names; a path it has no name for is shown as it is.
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include "cueplan/physics/validation.hpp"

namespace cueplan::api {

struct FieldName {
  physics::FieldPath field;
  std::string_view name;  // e.g. "--mu-table"
};

// The name of `path` in `names` (an entry whose field is `path` or a prefix of it, the
// longest such); the path's own text when none matches.
std::string name_of(const physics::FieldPath& path, std::span<const FieldName> names);

// "NAME RULE, got VALUE" with the field and any other field of the rule named by `names`.
std::string message_in(const physics::ValidationError& error, std::span<const FieldName> names);

// The ball and cushion (physics::CushionParams) and the impact's options
// (physics::ImpactOptions) as `cueplan rebound` and `cueplan collide` set them.
extern const std::initializer_list<FieldName> kCushionFlags;

}  // namespace cueplan::api

// The faces (command line, server, batch) name these as their own.
namespace cueplan::cli {
using api::FieldName;
using api::name_of;
using api::message_in;
using api::kCushionFlags;
}  // namespace cueplan::cli
