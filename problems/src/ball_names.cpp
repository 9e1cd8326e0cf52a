#include "cueplan/problems/ball_names.hpp"

#include <algorithm>
#include <array>
#include <cctype>

namespace cueplan::problems {
namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 2 &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

struct SnookerColour {
  const char* name;
  int value;
  const char* hex;
};
constexpr std::array<SnookerColour, 6> kSnookerColours{{{"yellow", 2, "#f2c500"},
                                                        {"green", 3, "#0a7a3a"},
                                                        {"brown", 4, "#6b3a1e"},
                                                        {"blue", 5, "#1d4fb5"},
                                                        {"pink", 6, "#f29ab8"},
                                                        {"black", 7, "#111111"}}};
// Pool's colours for 1-8; 9-15 repeat 1-7 as stripes.
constexpr std::array<const char*, 8> kPoolColours{"#f2c500", "#1d4fb5", "#c8102e", "#5b2c83",
                                                  "#f07f13", "#0a7a3a", "#7a1f1f", "#111111"};
constexpr const char* kRedHex = "#b0151a";

}  // namespace

BallIdentity identify_ball(const std::string& name) {
  BallIdentity id;
  if (name.rfind("red", 0) == 0 && (name.size() == 3 || all_digits(name.substr(3)))) {
    id.kind = BallKind::red;
    id.number = 1;
    id.colour = kRedHex;
    return id;
  }
  for (const SnookerColour& c : kSnookerColours) {
    if (name == c.name) {
      id.kind = BallKind::colour;
      id.number = c.value;
      id.colour = c.hex;
      return id;
    }
  }
  std::string digits = name;
  if (digits.rfind("ball", 0) == 0) digits = digits.substr(4);
  if (all_digits(digits) && digits[0] != '0') {
    const int n = std::stoi(digits);
    if (n >= 1 && n <= 15) {
      id.number = n;
      id.kind = n < 8 ? BallKind::pool_solid : n == 8 ? BallKind::pool_eight : BallKind::pool_stripe;
      id.colour = kPoolColours[static_cast<size_t>((n - 1) % 8)];
      id.striped = n > 8;
      if (n > 8) id.colour = kPoolColours[static_cast<size_t>(n - 9)];
    }
  }
  return id;
}

bool is_contact_class(const std::string& word) {
  return std::any_of(std::begin(kContactClasses), std::end(kContactClasses),
                     [&](const char* c) { return word == c; });
}

std::optional<std::string> lowest_pool_ball(const std::vector<physics::ObjectBall>& balls) {
  std::optional<std::string> best;
  int best_number = 16;
  for (const physics::ObjectBall& b : balls) {
    const BallIdentity id = identify_ball(b.name);
    const bool pool = id.kind == BallKind::pool_solid || id.kind == BallKind::pool_eight ||
                      id.kind == BallKind::pool_stripe;
    if (pool && id.number < best_number) {
      best_number = id.number;
      best = b.name;
    }
  }
  return best;
}

bool contact_allowed(const std::string& rule, const std::string& ball,
                     const std::vector<physics::ObjectBall>& balls) {
  const BallKind kind = identify_ball(ball).kind;
  if (rule == "any_red") return kind == BallKind::red;
  if (rule == "any_colour") return kind == BallKind::colour;
  if (rule == "solids") return kind == BallKind::pool_solid;
  if (rule == "stripes") return kind == BallKind::pool_stripe;
  if (rule == "lowest") return lowest_pool_ball(balls) == ball;
  return rule == ball;
}

}  // namespace cueplan::problems
