// The drawing layer's private core: a display list of shapes and Pango-set text that is
// laid out once and painted on any Cairo surface (SVG, PNG, PDF), and the typesetter
// that measures text with the same font options the painting uses.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "cueplan/draw/picture.hpp"

typedef struct _cairo cairo_t;
typedef struct _PangoLayout PangoLayout;
typedef struct _PangoContext PangoContext;

namespace cueplan::draw::detail {

struct Point {
  double x = 0.0, y = 0.0;
};

// Text made safe as the content of an XML element (SVG metadata) or Pango markup: & < >.
std::string escape_xml(std::string_view text);

// A path in picture units: lines, cubic Bezier pieces, circular arcs.
class Path {
 public:
  enum class Op { move, line, curve, arc, close };
  struct Element {
    Op op;
    // move/line: x y; curve: c1 c2 end; arc: cx cy r a0 a1 (radians, clockwise on the page)
    double v[6];
  };

  Path& move_to(double x, double y);
  Path& line_to(double x, double y);
  Path& curve_to(double x1, double y1, double x2, double y2, double x, double y);
  // A quadratic Bezier piece from the current point, drawn exactly as a cubic one.
  Path& quad_to(double cx, double cy, double x, double y);
  Path& arc(double cx, double cy, double r, double a0, double a1);
  Path& close();
  Path& rect(double x, double y, double w, double h);
  Path& circle(double cx, double cy, double r);
  Path& polygon(const std::vector<Point>& points);

  bool empty() const { return elements_.empty(); }
  // The extent of every point, control point and arc (a box that holds the path).
  Box bounds() const;
  const std::vector<Element>& elements() const { return elements_; }
  Path translated(double dx, double dy) const;

 private:
  std::vector<Element> elements_;
  Point current_;
  Point start_;
};

enum class LineCap { butt, round, square };

struct Pen {
  Pen() = default;
  Pen(Colour c, double w, std::vector<double> d = {}) : colour(c), width(w), dash(std::move(d)) {}
  Colour colour;
  double width = 1.0;
  std::vector<double> dash;  // on, off, ... lengths; empty: solid
  LineCap cap = LineCap::butt;
  bool round_join = false;
};

struct Font {
  double size = 13.0;  // px
  bool bold = false;
};

enum class Align { left, centre, right };

// Text laid out by Pango: its size and the plain words behind its markup.
class Text {
 public:
  double width() const { return width_; }
  double height() const { return height_; }
  double baseline() const { return baseline_; }  // of the first line, from the top
  const std::string& plain() const { return plain_; }
  PangoLayout* layout() const { return layout_.get(); }

 private:
  friend class Typesetter;
  std::shared_ptr<PangoLayout> layout_;
  double width_ = 0.0, height_ = 0.0, baseline_ = 0.0;
  std::string plain_;
};

// Sets text in DejaVu Sans. Labels may write subscripts as k_{T} and superscripts as
// 10^{8}; everything else is plain text (no markup is read from the label).
class Typesetter {
 public:
  Typesetter();
  Typesetter(const Typesetter&) = delete;
  Typesetter& operator=(const Typesetter&) = delete;
  ~Typesetter();

  // `wrap_width` > 0 breaks lines at word boundaries to fit within it (px).
  Text set(std::string_view label, Font font, double wrap_width = 0.0,
           Align align = Align::left) const;

 private:
  PangoContext* context_ = nullptr;
};

// Where a text's box sits relative to the point it is drawn at: x 0 left .. 1 right,
// and vertically its top, its middle or its first line's baseline.
enum class VAnchor { top, middle, baseline, bottom };
struct Anchor {
  double x = 0.0;
  VAnchor v = VAnchor::top;
};
inline constexpr Anchor kTopLeft{0.0, VAnchor::top};

// The box `text` occupies when drawn at (x, y) with `anchor`, unrotated.
Box text_box(const Text& text, double x, double y, Anchor anchor);

class Canvas {
 public:
  Canvas(double width, double height);  // rounded up to whole units
  double width() const { return width_; }
  double height() const { return height_; }

  void fill(const Path& path, Colour colour, std::string role);
  void stroke(const Path& path, const Pen& pen, std::string role);
  void fill_and_stroke(const Path& path, Colour fill, const Pen& pen, std::string role);
  // Fills with a linear gradient from (x0, y0) to (x1, y1) through `stops` (offset in
  // [0, 1], colour), one smooth fill in every format.
  struct Stop {
    double offset;
    Colour colour;
  };
  void fill_gradient(const Path& path, Point from, Point to, std::vector<Stop> stops,
                     std::string role);
  // Draws `text` in `colour`; returns its box (for a rotated text, the box around it).
  // angle_deg turns it counter-clockwise on the page about (x, y).
  Box text(const Text& text, double x, double y, Anchor anchor, Colour colour, std::string role,
           double angle_deg = 0.0);
  // Everything drawn until the matching unclip() is clipped to `path`.
  void clip(const Path& path);
  void unclip();
  // Another canvas drawn with its origin at (dx, dy); its marks join this one's.
  void embed(std::shared_ptr<const Canvas> panel, double dx, double dy);

  void paint(cairo_t* cr) const;
  std::vector<Mark> marks() const;

 private:
  struct Shape {
    Path path;
    bool filled = false;
    Colour fill;
    bool stroked = false;
    Pen pen;
    std::string role;
    std::vector<Stop> gradient;  // non-empty: the fill is this gradient
    Point from, to;
  };
  struct TextOp {
    Text text;
    double x = 0.0, y = 0.0;  // top left of the layout before rotation
    double angle_deg = 0.0;
    double pivot_x = 0.0, pivot_y = 0.0;
    Colour colour;
    std::string role;
    Box box;
  };
  struct ClipOp {
    Path path;
  };
  struct UnclipOp {};
  struct EmbedOp {
    std::shared_ptr<const Canvas> panel;
    double dx = 0.0, dy = 0.0;
  };
  using Op = std::variant<Shape, TextOp, ClipOp, UnclipOp, EmbedOp>;

  void collect(std::vector<Mark>* marks, double dx, double dy) const;

  double width_, height_;
  std::vector<Op> ops_;
  int open_clips_ = 0;
};

}  // namespace cueplan::draw::detail
