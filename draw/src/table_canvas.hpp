// The table drawing as a canvas, for pictures that hold it as one of their panels.
#pragma once

#include <memory>

#include "canvas.hpp"
#include "cueplan/draw/table.hpp"

namespace cueplan::draw::detail {

std::shared_ptr<Canvas> draw_table(const TableScene& scene, const TableStyle& style,
                                   const Typesetter& type);

}  // namespace cueplan::draw::detail
