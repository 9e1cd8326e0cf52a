// Bad input as every face reports it: the field, named as the caller's user knows it (a
// flag "--max-time", a request's "options.max_time", a CSV column), and a message that
// names it the same way. Faces read the field from the error, never from the message.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace cueplan::api {

class InputError : public std::invalid_argument {
 public:
  InputError(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}

  // Empty for the input as a whole.
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

}  // namespace cueplan::api
