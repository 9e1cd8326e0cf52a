// A small RGB raster for pictures the command line writes as PNG: filled rectangles and
// circles, rings, thick lines, text in a built-in 5 x 8 pixel font (scaled by whole
// numbers; `k_{T}` lowers the T as in the SVG writers), and a PNG encoder on zlib.
//
// Shapes are drawn with 4 x 4 supersampling at their edges, so circles and slanted
// lines come out smooth; text is pixel-exact.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::cli {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};

// "#rrggbb" to a colour; anything else gives black.
Rgb parse_colour(std::string_view hex);

class Raster {
 public:
  Raster(int width, int height, Rgb background = {255, 255, 255});

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const;

  // Every shape blends with `opacity` in [0, 1] over what is there.
  void fill_rect(double x, double y, double w, double h, Rgb colour, double opacity = 1.0);
  void fill_circle(double cx, double cy, double r, Rgb colour, double opacity = 1.0);
  // The band between radii r - width / 2 and r + width / 2; with dash > 0, drawn in dashes
  // of about `dash` px with gaps as long.
  void stroke_circle(double cx, double cy, double r, double width, Rgb colour, double opacity = 1.0,
                     double dash = 0.0);
  // A segment of the given width with round ends.
  void line(double x1, double y1, double x2, double y2, double width, Rgb colour,
            double opacity = 1.0);
  // Diagonal hatching over a rectangle: lines `spacing` px apart.
  void hatch_rect(double x, double y, double w, double h, double spacing, Rgb colour);

  // Text with its baseline at y; anchor 0 left, 0.5 centre, 1 right. Characters the font
  // lacks show as '?'. Returns the width drawn (px).
  double text(double x, double y, std::string_view label, int scale, Rgb colour,
              double anchor = 0.0);
  // Width (px) text() would draw.
  static double text_width(std::string_view label, int scale);
  // Height (px) of a capital letter at this scale.
  static double cap_height(int scale) { return 7.0 * scale; }

 private:
  // Blends `colour` into pixel (x, y) with coverage `alpha`.
  void blend(int x, int y, Rgb colour, double alpha);
  // Fills the pixels in the box where `inside(px, py)` holds, sampled 4 x 4 per pixel.
  template <typename Inside>
  void fill_shape(double x0, double y0, double x1, double y1, Rgb colour, double opacity,
                  const Inside& inside);

  int width_;
  int height_;
  std::vector<Rgb> pixels_;
};

// The image as a PNG file (8-bit RGB, zlib-compressed, no interlace).
std::string encode_png(const Raster& image);

}  // namespace cueplan::cli
