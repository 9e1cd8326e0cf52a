#include "cueplan/physics/validation.hpp"

#include <fmt/format.h>

namespace cueplan::physics {

FieldPath FieldPath::operator/(FieldStep step) const {
  FieldPath path = *this;
  path.steps_.push_back(std::move(step));
  return path;
}

FieldPath FieldPath::operator/(const FieldPath& tail) const {
  FieldPath path = *this;
  path.steps_.insert(path.steps_.end(), tail.steps_.begin(), tail.steps_.end());
  return path;
}

bool FieldPath::starts_with(const FieldPath& prefix) const {
  if (prefix.steps_.size() > steps_.size()) return false;
  for (size_t i = 0; i < prefix.steps_.size(); ++i)
    if (!(steps_[i] == prefix.steps_[i])) return false;
  return true;
}

FieldPath FieldPath::drop_front(size_t n) const {
  if (n >= steps_.size()) return {};
  return FieldPath(std::vector<FieldStep>(steps_.begin() + static_cast<std::ptrdiff_t>(n),
                                          steps_.end()));
}

std::string FieldPath::text() const {
  std::string out;
  for (const FieldStep& step : steps_) {
    if (const int* index = std::get_if<int>(&step)) {
      out += fmt::format("[{}]", *index);
    } else {
      if (!out.empty()) out += '.';
      out += std::get<std::string>(step);
    }
  }
  return out;
}

std::string ValidationError::rule_text(std::string_view other_name) const {
  std::string text = rule;
  if (other) {
    const std::string name = other_name.empty() ? other->text() : std::string(other_name);
    for (size_t at = text.find("{other}"); at != std::string::npos;
         at = text.find("{other}", at + name.size()))
      text.replace(at, 7, name);
  }
  if (value) text += fmt::format(", got {:.10g}", *value);
  return text;
}

std::string ValidationError::message(std::string_view name, std::string_view other_name) const {
  return fmt::format("{} {}", name, rule_text(other_name));
}

std::string ValidationError::message() const { return message(field.text()); }

ValidationError ValidationError::under(const FieldPath& parent) const {
  ValidationError moved = *this;
  moved.field = field.under(parent);
  if (other) moved.other = other->under(parent);
  return moved;
}

ValidationError invalid(FieldPath field, std::string rule) {
  return {std::move(field), std::move(rule), std::nullopt, std::nullopt};
}

ValidationError invalid(FieldPath field, std::string rule, double value) {
  return {std::move(field), std::move(rule), value, std::nullopt};
}

}  // namespace cueplan::physics
