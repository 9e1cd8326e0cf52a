#include "label_placer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cueplan::draw::detail {
namespace {

double overlap_area(const Box& a, const Box& b) {
  const double w = std::min(a.right, b.right) - std::max(a.left, b.left);
  const double h = std::min(a.bottom, b.bottom) - std::max(a.top, b.top);
  return w > 0.0 && h > 0.0 ? w * h : 0.0;
}

}  // namespace

Box LabelPlacer::place(double x, double y, double width, double height, double gap) {
  // Directions in order of preference: right, upper right, above, upper left, left,
  // lower left, below, lower right; each tried at 1, 2, 3, ... times the gap.
  constexpr int kDirections = 8;
  constexpr int kRings = 12;
  Box best{};
  double best_labels = INFINITY;
  double best_avoided = INFINITY;
  for (int ring = 1; ring <= kRings; ++ring) {
    const double d = gap * ring;
    for (int k = 0; k < kDirections; ++k) {
      const double angle = k * std::numbers::pi / 4.0;
      const double ux = std::cos(angle);
      const double uy = -std::sin(angle);  // page y points down
      // The label's box touches the circle of radius d on the side facing (x, y).
      const double cx = x + ux * (d + 0.5 * width * std::abs(ux));
      const double cy = y + uy * (d + 0.5 * height * std::abs(uy));
      Box b{cx - 0.5 * width, cy - 0.5 * height, cx + 0.5 * width, cy + 0.5 * height};
      // Keep within the area by sliding back inside it.
      if (b.left < area_.left) b = {area_.left, b.top, area_.left + width, b.bottom};
      if (b.right > area_.right) b = {area_.right - width, b.top, area_.right, b.bottom};
      if (b.top < area_.top) b = {b.left, area_.top, b.right, area_.top + height};
      if (b.bottom > area_.bottom) b = {b.left, area_.bottom - height, b.right, area_.bottom};
      double on_labels = 0.0;
      for (const Box& l : labels_) on_labels += overlap_area(b, l.grown(1.0));
      double on_avoided = 0.0;
      for (const Box& a : avoided_) on_avoided += overlap_area(b, a);
      if (on_labels == 0.0 && on_avoided == 0.0) {
        labels_.push_back(b);
        return b;
      }
      if (on_labels < best_labels || (on_labels == best_labels && on_avoided < best_avoided)) {
        best = b;
        best_labels = on_labels;
        best_avoided = on_avoided;
      }
    }
  }
  labels_.push_back(best);
  return best;
}

}  // namespace cueplan::draw::detail
