// A picture laid out once and written as SVG, PNG or PDF: the same drawing, the same
// layout and the same text metrics in every format (Cairo draws it, Pango sets its text).
//
// The pictures themselves are made by table.hpp (a table seen from above with balls and
// their paths), spin_map.hpp ("what spin lands here?") and plot.hpp (line plots). Each
// keeps a list of the marks it drew - their role and extent - so that a caller or a test
// can ask what a picture shows without reading the file back.
//
// Units: picture units are pixels at 100 % (a PNG pixel, an SVG px, a PDF point).
// Thread safety: building and encoding pictures in several threads at once is safe; one
// Picture is encoded by one thread at a time.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cueplan::draw {

namespace detail {
class Canvas;
}

// An sRGB colour with opacity, each channel in [0, 1].
struct Colour {
  double r = 0.0, g = 0.0, b = 0.0;
  double a = 1.0;

  // "#rrggbb" (a bad string gives black); `alpha` sets the opacity.
  static constexpr Colour hex(std::string_view rrggbb, double alpha = 1.0) {
    const auto digit = [](char c) {
      return c >= '0' && c <= '9'   ? c - '0'
             : c >= 'a' && c <= 'f' ? c - 'a' + 10
             : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                    : -1;
    };
    if (rrggbb.size() != 7 || rrggbb[0] != '#') return {0.0, 0.0, 0.0, alpha};
    double channel[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < 3; ++i) {
      const int hi = digit(rrggbb[1 + 2 * i]), lo = digit(rrggbb[2 + 2 * i]);
      if (hi < 0 || lo < 0) return {0.0, 0.0, 0.0, alpha};
      channel[i] = (16 * hi + lo) / 255.0;
    }
    return {channel[0], channel[1], channel[2], alpha};
  }
  Colour with_alpha(double alpha) const { return {r, g, b, alpha}; }
  std::string to_hex() const;  // "#rrggbb", opacity left out
};

enum class Format { svg, png, pdf };
const char* to_string(Format format);  // "svg", "png", "pdf"

// The format a file name asks for by its extension (.svg, .png, .pdf, any letter case);
// empty for any other extension.
std::optional<Format> format_of(const std::filesystem::path& file);

// An axis-aligned rectangle in picture units, y down.
struct Box {
  double left = 0.0, top = 0.0, right = 0.0, bottom = 0.0;

  double width() const { return right - left; }
  double height() const { return bottom - top; }
  bool overlaps(const Box& other) const;  // interiors meet (touching edges do not count)
  bool inside(const Box& outer) const;    // within `outer`, edges included
  Box grown(double margin) const {
    return {left - margin, top - margin, right + margin, bottom + margin};
  }
};

// One thing drawn: what it is and where.
struct Mark {
  std::string role;  // e.g. "pocket", "ball", "path-rolling", "label", "cell", "tick-label"
  Box box;           // its extent (for text: the laid-out lines, as Pango measures them)
  std::string text;  // the words of a text mark, markup removed; empty for shapes
  bool is_text = false;
};

class Picture {
 public:
  Picture();
  double width() const { return width_; }
  double height() const { return height_; }
  // Every mark in drawing order, panels included.
  const std::vector<Mark>& marks() const { return marks_; }
  // Marks of one role.
  std::vector<Mark> marks_of(std::string_view role) const;
  // Written into the files' metadata (SVG <title> and <desc>, PDF title).
  const std::string& title() const { return title_; }
  const std::string& description() const { return description_; }

  // Made by the picture builders of this library.
  Picture(std::shared_ptr<const detail::Canvas> canvas, std::string title, std::string description);
  const detail::Canvas* canvas() const { return canvas_.get(); }

 private:
  std::shared_ptr<const detail::Canvas> canvas_;
  double width_ = 0.0, height_ = 0.0;
  std::vector<Mark> marks_;
  std::string title_, description_;
};

// The file's bytes, or why there are none.
struct Encoded {
  std::string bytes;
  std::string error;  // empty on success
  bool ok() const { return error.empty(); }
};

struct EncodeOptions {
  double png_scale = 1.0;  // PNG pixels per picture unit, in (0, 8]
};

Encoded encode(const Picture& picture, Format format, const EncodeOptions& options = {});

// The largest canvas a table or a spin map gets, in picture units per side, whatever the
// scene: extreme tables (1e9 m, 6 cm) are scaled to fit, never drawn larger. (A plot is
// as wide as its panels.)
inline constexpr double kMaxCanvasSide = 2400.0;

}  // namespace cueplan::draw
