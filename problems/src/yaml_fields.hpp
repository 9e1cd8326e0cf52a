// Strict reading of YAML values into the typed fields of a problem file.
//
// yaml-cpp accepts more than the format allows: it keeps duplicated keys, turns a
// quoted "0.5" into 0.5 and reads .nan and .inf as numbers. These helpers refuse all of
// that and say which field of the file is wrong and on which line. Private to the loader.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cueplan/physics/shot.hpp"

namespace cueplan::problems::detail {

// What is wrong with one field. Thrown inside the loader only and caught at its public
// boundary, which turns it into LoadResult::error.
struct FieldError {
  int line = 0;       // from 1; 0 when unknown
  std::string field;  // path in the file, e.g. "table.length", "limits.speed[1]"
  std::string message;
};

// Line (from 1) at which yaml-cpp saw `node`; 0 when it has no position.
int line_of(const YAML::Node& node);

// A value in the file and where it is: the field's path and its line.
struct Field {
  YAML::Node value;
  std::string path;
  int line = 0;  // of its key; of the element itself in a sequence
};

// One mapping of the file whose keys are checked on construction: every key a plain
// string from `allowed` (any plain word when `allowed` is empty: a mapping from names,
// such as `balls`), none repeated. Every field found is entered in `lines`
// (path -> line), so that later checks can point back into the file.
class Mapping {
 public:
  Mapping(const Field& mapping, std::initializer_list<std::string_view> allowed,
          std::map<std::string, int>& lines);

  // Its fields in the order the file gives them.
  const std::vector<std::pair<std::string, Field>>& entries() const { return entries_; }

  // The field under `key`, or nothing when the file leaves it out.
  std::optional<Field> find(std::string_view key) const;
  // The field under `key`; FieldError when it is missing.
  Field require(std::string_view key, std::string_view what_it_is) const;

  int line() const { return line_; }

 private:
  std::string child_path(std::string_view key) const;

  std::string path_;  // empty for the document itself
  int line_ = 0;
  std::vector<std::pair<std::string, Field>> entries_;
};

// " (did you mean CANDIDATE?)" for the candidate spelled closest to `name` (within two
// edits), or "".
std::string did_you_mean(std::string_view name, const std::vector<std::string_view>& candidates);
// One of `names` (a word from a fixed list, or a name the file defines); otherwise a
// FieldError: "must be one of A, B, got "X" (did you mean B?)" with `what` for "one of".
std::string one_of(const Field& field, const std::vector<std::string_view>& names,
                   std::string_view what = "one of");

// A plain finite number; quoted strings, .nan, .inf, booleans and the like are refused.
double number(const Field& field);
double positive_number(const Field& field);      // > 0
double non_negative_number(const Field& field);  // >= 0
// A whole number in [lo, hi].
int whole_number(const Field& field, int lo, int hi);
// Any scalar, as written.
std::string text(const Field& field);
// True when the field is the word `word` (e.g. `free`, `none`), quoted or not.
bool is_word(const Field& field, std::string_view word);
// The elements of a sequence; with `size` > 0, exactly that many.
std::vector<Field> sequence(const Field& field, std::size_t size, std::string_view what_it_is);
// A point [x, y] in m.
physics::Vec2 point(const Field& field);
// What a node holds, for messages: "a mapping", "the quoted string \"0.5\"", ...
std::string describe_value(const YAML::Node& node);
// Text with its control characters escaped (\n, \t, \xNN), fit for a one-line message.
std::string printable(std::string_view text);
// Text from the file, quoted for a one-line message: control characters escaped, long
// text cut short.
std::string shown_text(std::string_view text);

[[noreturn]] void fail(const Field& field, std::string message);

}  // namespace cueplan::problems::detail
