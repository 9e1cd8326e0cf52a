// A broken rule of an input, as data: which field, what must hold, the value given.
//
// Every layer checks its own structs and names their fields in its own terms (physics
// says {"cloth", "mu_roll"}, the problem files say physics.mu_roll, the command line
// --mu-roll). An error travels between layers as this struct, never as text to parse:
// the layer that shows it maps the path to its own words (the loader adds FILE:LINE,
// the command line names its flag) and calls message() with that name.
#pragma once

#include <compare>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace cueplan::physics {

// One step of a path: a member or key name ("table", "red"), or an index in a list.
using FieldStep = std::variant<std::string, int>;

// Where a value lives: {"table", "length"}, {"balls", "red", 0}, {"pockets", 2, "radius"}.
class FieldPath {
 public:
  FieldPath() = default;
  FieldPath(std::initializer_list<FieldStep> steps) : steps_(steps) {}
  explicit FieldPath(std::vector<FieldStep> steps) : steps_(std::move(steps)) {}

  const std::vector<FieldStep>& steps() const { return steps_; }
  bool empty() const { return steps_.empty(); }
  size_t size() const { return steps_.size(); }

  // This path with `step` (or every step of `tail`) appended.
  FieldPath operator/(FieldStep step) const;
  FieldPath operator/(const FieldPath& tail) const;
  // `parent` followed by this path: how a layer that holds this struct as a member
  // names its fields.
  FieldPath under(const FieldPath& parent) const { return parent / *this; }

  bool starts_with(const FieldPath& prefix) const;
  // The path without its first `n` steps.
  FieldPath drop_front(size_t n) const;

  // Names joined by '.', indices as [i]: "table.length", "balls.red[0]", "pockets[2].radius".
  std::string text() const;

  friend bool operator==(const FieldPath&, const FieldPath&) = default;
  friend auto operator<=>(const FieldPath&, const FieldPath&) = default;

 private:
  std::vector<FieldStep> steps_;
};

struct ValidationError {
  FieldPath field;            // the value that breaks the rule
  std::string rule;           // what must hold: "must be positive and finite (m)"
  std::optional<double> value;  // the offending number, when there is one
  std::optional<FieldPath> other;  // a second field the rule involves ("overlaps ..."),
                                   // named by the rule's {other} placeholder

  // "NAME RULE, got VALUE" with `name` standing for the field (and `other_name` for
  // {other} in the rule): each layer passes its own name for the path.
  std::string message(std::string_view name, std::string_view other_name = {}) const;
  // The same with the paths' own text as the names.
  std::string message() const;
  // RULE, got VALUE: the message without the field's name, for layers that print the
  // name apart (the loader's "FILE:LINE: FIELD: RULE").
  std::string rule_text(std::string_view other_name = {}) const;

  // This error with its paths moved under `parent` (see FieldPath::under).
  ValidationError under(const FieldPath& parent) const;
};

// Empty when the input is valid.
using Validation = std::optional<ValidationError>;

// Shorthands for the common rules.
ValidationError invalid(FieldPath field, std::string rule);
ValidationError invalid(FieldPath field, std::string rule, double value);

}  // namespace cueplan::physics
