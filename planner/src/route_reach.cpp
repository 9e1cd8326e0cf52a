// unreachable_reason(): a proof that the cue ball's centre cannot get from where it lies
// to the target without touching an obstacle ball or entering a pocket.
//
// The centre moves continuously inside the rectangle between the cushion contact lines
// (cushions turn it back, they never let it out). It must stay outside every obstacle's
// disc of radius 2R (touching is contact) and every pocket's capture circle. A grid over
// the rectangle closes only the cells that lie wholly inside one such disc; every other
// cell holds a point the centre might occupy. Any continuous path visits a chain of
// 8-connected open cells, so when the target's cell cannot be reached from the cue
// ball's cell over open cells, no path exists: the check errs only toward "maybe
// reachable", never toward a false proof.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cueplan/planner/route.hpp"

namespace cueplan::planner {
namespace {

constexpr double kCell = 0.004;  // m, grid spacing

struct Disc {
  physics::Vec2 centre;
  double radius;
};

bool inside(const Disc& d, double x, double y) {
  return std::hypot(x - d.centre.x, y - d.centre.y) <= d.radius;
}

}  // namespace

std::string unreachable_reason(const problems::Problem& problem) {
  const physics::Scene& s = problem.scene;
  const double off = s.contact_offset();
  const double x0 = off, y0 = off, w = s.length - 2.0 * off, h = s.width - 2.0 * off;
  if (!(w > 0.0 && h > 0.0)) return {};
  const int nx = static_cast<int>(std::ceil(w / kCell)), ny = static_cast<int>(std::ceil(h / kCell));
  const double cx = w / nx, cy = h / ny;

  std::vector<Disc> discs;
  for (const physics::Vec2& o : s.obstacles) discs.push_back({o, 2.0 * s.radius()});
  for (const physics::Pocket& p : s.pockets) discs.push_back({p.centre, p.radius});

  std::vector<char> open(static_cast<size_t>(nx) * ny, 1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double xa = x0 + i * cx, xb = xa + cx, ya = y0 + j * cy, yb = ya + cy;
      for (const Disc& d : discs)
        if (inside(d, xa, ya) && inside(d, xb, ya) && inside(d, xa, yb) && inside(d, xb, yb)) {
          open[static_cast<size_t>(j) * nx + i] = 0;
          break;
        }
    }

  const auto cell = [&](physics::Vec2 p) {
    const int i = std::clamp(static_cast<int>((p.x - x0) / cx), 0, nx - 1);
    const int j = std::clamp(static_cast<int>((p.y - y0) / cy), 0, ny - 1);
    return static_cast<size_t>(j) * nx + i;
  };
  const size_t from = cell(problem.cue_ball), to = cell(problem.target);
  if (!open[from] || !open[to]) return {};  // cannot happen for valid positions; no proof

  std::vector<char> seen(open.size(), 0);
  std::vector<size_t> stack{from};
  seen[from] = 1;
  while (!stack.empty()) {
    const size_t c = stack.back();
    stack.pop_back();
    if (c == to) return {};
    const int i = static_cast<int>(c % nx), j = static_cast<int>(c / nx);
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
        const size_t n = static_cast<size_t>(b) * nx + a;
        if (open[n] && !seen[n]) {
          seen[n] = 1;
          stack.push_back(n);
        }
      }
  }
  return "The target cannot be reached by any sequence of strokes: obstacle balls (and "
         "pockets) wall it off from the cue ball, so every path of the ball's centre between "
         "them touches a ball or enters a pocket.";
}

}  // namespace cueplan::planner
