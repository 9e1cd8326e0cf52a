// Places text labels beside the points they name so that no two labels overlap and none
// covers what it should not (balls, pockets): candidate positions around the point, at
// growing distances, the first free one taken.
#pragma once

#include <optional>
#include <vector>

#include "canvas.hpp"

namespace cueplan::draw::detail {

class LabelPlacer {
 public:
  // Labels stay within `area`.
  explicit LabelPlacer(Box area) : area_(area) {}

  // Something labels should not cover (a ball, a pocket, a badge).
  void avoid(const Box& box) { avoided_.push_back(box); }

  // The box for a `width` x `height` label near the point (x, y), at least `gap` from it:
  // the first candidate that overlaps no label and nothing avoided; failing that, the one
  // that overlaps no label and the least of what is avoided; failing that (a full area),
  // the candidate with the least overlap of all. The box is then taken.
  Box place(double x, double y, double width, double height, double gap);

  // Takes a box placed by other means (e.g. a number on a cushion) so labels keep off it.
  void take(const Box& box) { labels_.push_back(box); }

  const std::vector<Box>& labels() const { return labels_; }

 private:
  Box area_;
  std::vector<Box> labels_;
  std::vector<Box> avoided_;
};

}  // namespace cueplan::draw::detail
