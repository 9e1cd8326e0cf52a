// Small pieces the stress programs share: reading a count from the command line and
// writing a tally of outcomes as a JSON object.
#pragma once

#include <cstdlib>
#include <map>
#include <ostream>
#include <string>

namespace cueplan::physics::test {

// True when `text` is a whole integer >= min; the value goes to *out.
inline bool parse_count(const char* text, long long min, long long* out) {
  char* end = nullptr;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || v < min) return false;
  *out = v;
  return true;
}

// {"name": count, ...} in the map's order.
inline void write_counts_json(std::ostream& out, const std::map<std::string, long long>& counts) {
  out << '{';
  bool first = true;
  for (const auto& [name, n] : counts) {
    out << (first ? "" : ", ") << '"' << name << "\": " << n;
    first = false;
  }
  out << '}';
}

}  // namespace cueplan::physics::test
