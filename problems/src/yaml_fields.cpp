#include "yaml_fields.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

namespace cueplan::problems::detail {
namespace {

// Tags yaml-cpp gives a scalar written as a number: "?" for a plain scalar, or an
// explicit !!float / !!int. A quoted scalar has "!" and is a string.
bool number_tag(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:float" || tag == "tag:yaml.org,2002:int";
}

// YAML 1.2 core-schema floats: [-+]?(.[0-9]+|[0-9]+(.[0-9]*)?)([eE][-+]?[0-9]+)?, and
// [-+]?.inf, .nan. Returns nothing for anything else (hex, "1_000", "nan", "inf", ...).
std::optional<double> parse_float(std::string_view s) {
  if (s == ".nan" || s == ".NaN" || s == ".NAN") return std::nan("");
  bool negative = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s == ".inf" || s == ".Inf" || s == ".INF")
    return negative ? -HUGE_VAL : HUGE_VAL;
  // from_chars would also take "inf" and "nan": insist on a digit or a point first.
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s.front())) || s.front() == '.'))
    return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (error == std::errc::result_out_of_range) return negative ? -HUGE_VAL : HUGE_VAL;
  if (error != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return negative ? -value : value;
}

// Levenshtein distance, for "did you mean" on unknown keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A key the format could name: letters, digits and underscores, as every field is.
bool plain_word(std::string_view key) {
  if (key.empty()) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

std::string format_number(double value) { return fmt::format("{:.10g}", value); }

}  // namespace

std::string did_you_mean(std::string_view name, const std::vector<std::string_view>& candidates) {
  std::string_view closest;
  std::size_t best = 3;  // suggest only close spellings
  for (std::string_view candidate : candidates) {
    const std::size_t d = edit_distance(name, candidate);
    if (d < best) best = d, closest = candidate;
  }
  return closest.empty() ? std::string() : " (did you mean " + std::string(closest) + "?)";
}

std::string one_of(const Field& field, const std::vector<std::string_view>& names,
                   std::string_view what) {
  const std::string given = text(field);
  for (std::string_view n : names)
    if (given == n) return given;
  std::string list;
  for (std::string_view n : names) list += (list.empty() ? "" : ", ") + std::string(n);
  fail(field, "must be " + std::string(what) + " " + list + ", got " + describe_value(field.value) +
                  did_you_mean(given, names));
}

int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

void fail(const Field& field, std::string message) {
  throw FieldError{field.line, field.path, std::move(message)};
}

std::string describe_value(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Scalar: break;
  }
  return (node.Tag() == "!" ? "the quoted string " : "") + shown_text(node.Scalar());
}

std::string printable(std::string_view text) {
  std::string shown;
  shown.reserve(text.size());
  for (const char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '\n') {
      shown += "\\n";
    } else if (c == '\t') {
      shown += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      shown += fmt::format("\\x{:02x}", static_cast<unsigned>(c));
    } else {
      shown += ch;
    }
  }
  return shown;
}

std::string shown_text(std::string_view text) {
  constexpr std::size_t kLongest = 40;
  std::string shown = "\"";
  for (const char c : text.substr(0, kLongest)) {
    if (c == '"' || c == '\\') shown += '\\';
    shown += c;
  }
  shown = printable(shown);
  if (text.size() > kLongest) shown += "...";
  return shown + "\"";
}

Mapping::Mapping(const Field& mapping, std::initializer_list<std::string_view> allowed,
                 std::map<std::string, int>& lines)
    : path_(mapping.path), line_(mapping.line) {
  if (!mapping.value.IsMap())
    fail(mapping, "must be a mapping of fields, got " + describe_value(mapping.value));
  for (auto it = mapping.value.begin(); it != mapping.value.end(); ++it) {
    const YAML::Node key = it->first;  // copies: the iterator hands out a temporary
    const YAML::Node value = it->second;
    const int key_line = line_of(key) > 0 ? line_of(key) : line_;
    if (!key.IsScalar())
      fail({key, path_.empty() ? "(document)" : path_, key_line},
           "has a key that is " + describe_value(key) + "; keys are plain words");
    const std::string name = key.Scalar();
    // Only a plain word can be a field's name; anything else is named by its mapping.
    if (!plain_word(name))
      fail({key, path_.empty() ? "(document)" : path_, key_line},
           "has the key " + shown_text(name) + "; keys are plain words" +
               (allowed.size() > 0 ? " such as " + std::string(*allowed.begin()) : ""));
    // A block value starts on a later line (and an empty one wherever the next token
    // is): the key's line is where the field is.
    Field field{value, child_path(name), key_line};
    if (allowed.size() > 0 && std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      std::string message = "unknown key; expected one of ";
      for (std::string_view candidate : allowed) {
        if (candidate != *allowed.begin()) message += ", ";
        message += candidate;
      }
      fail({value, field.path, key_line},
           message + did_you_mean(name, std::vector<std::string_view>(allowed)));
    }
    for (const auto& [seen, earlier] : entries_) {
      if (seen == name)
        fail({value, field.path, key_line},
             "duplicated key (first given at line " + std::to_string(earlier.line) + ")");
    }
    lines[field.path] = field.line;
    entries_.emplace_back(name, std::move(field));
  }
}

std::string Mapping::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::optional<Field> Mapping::find(std::string_view key) const {
  for (const auto& [name, field] : entries_) {
    if (name == key) return field;
  }
  return std::nullopt;
}

Field Mapping::require(std::string_view key, std::string_view what_it_is) const {
  if (std::optional<Field> field = find(key)) return *field;
  throw FieldError{line_, child_path(key), "missing; required: " + std::string(what_it_is)};
}

double number(const Field& field) {
  const YAML::Node& node = field.value;
  if (!node.IsScalar() || !number_tag(node))
    fail(field, "must be a number, got " + describe_value(node));
  const std::optional<double> value = parse_float(node.Scalar());
  if (!value) fail(field, "must be a number, got " + describe_value(node));
  if (!std::isfinite(*value)) fail(field, "must be a finite number, got " + node.Scalar());
  return *value;
}

double positive_number(const Field& field) {
  const double value = number(field);
  if (!(value > 0.0)) fail(field, "must be positive, got " + format_number(value));
  return value;
}

double non_negative_number(const Field& field) {
  const double value = number(field);
  if (value < 0.0) fail(field, "must not be negative, got " + format_number(value));
  return value;
}

int whole_number(const Field& field, int lo, int hi) {
  const double value = number(field);
  if (value != std::floor(value))
    fail(field, "must be a whole number, got " + format_number(value));
  if (value < lo || value > hi)
    fail(field, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                    format_number(value));
  return static_cast<int>(value);
}

std::string text(const Field& field) {
  if (!field.value.IsScalar()) fail(field, "must be text, got " + describe_value(field.value));
  return field.value.Scalar();
}

bool is_word(const Field& field, std::string_view word) {
  return field.value.IsScalar() && field.value.Scalar() == word;
}

std::vector<Field> sequence(const Field& field, std::size_t size, std::string_view what_it_is) {
  if (!field.value.IsSequence())
    fail(field, "must be " + std::string(what_it_is) + ", got " + describe_value(field.value));
  if (size > 0 && field.value.size() != size)
    fail(field, "must be " + std::string(what_it_is) + ", got " +
                    std::to_string(field.value.size()) + " element" +
                    (field.value.size() == 1 ? "" : "s"));
  std::vector<Field> elements;
  elements.reserve(field.value.size());
  for (std::size_t i = 0; i < field.value.size(); ++i) {
    const YAML::Node element = field.value[i];
    const int line = line_of(element) > 0 ? line_of(element) : field.line;
    elements.push_back({element, field.path + "[" + std::to_string(i) + "]", line});
  }
  return elements;
}

physics::Vec2 point(const Field& field) {
  const std::vector<Field> xy = sequence(field, 2, "a point [x, y] in m");
  return {number(xy[0]), number(xy[1])};
}

}  // namespace cueplan::problems::detail
