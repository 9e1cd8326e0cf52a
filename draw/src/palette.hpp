// The colours the pictures share.
#pragma once

#include "cueplan/draw/picture.hpp"

namespace cueplan::draw::detail {

inline Colour ink() {
  return Colour::hex("#1a1a1a");
}
inline Colour muted() {
  return Colour::hex("#444444");
}
inline Colour axis_grey() {
  return Colour::hex("#333333");
}
inline Colour white() {
  return {1.0, 1.0, 1.0, 1.0};
}
inline Colour target_green() {
  return Colour::hex("#009E73");
}  // Okabe-Ito bluish green
inline Colour faint_grey() {
  return Colour::hex("#8c8c8c");
}
inline Colour note_amber() {
  return Colour::hex("#8a5a00");
}

// A colour mixed toward black (t = 0: itself, 1: black).
inline Colour darker(Colour c, double t) {
  return {c.r * (1.0 - t), c.g * (1.0 - t), c.b * (1.0 - t), c.a};
}

}  // namespace cueplan::draw::detail
