#include "canvas.hpp"

#include <cairo.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cmath>
#include <numbers>

// Fontconfig keeps a few hundred bytes of the configuration it parses for the life of the
// process, beyond the reach of LeakSanitizer's scan; under the sanitizers that one library
// is not reported (every other allocation still is).
#if defined(__SANITIZE_ADDRESS__)
#define CUEPLAN_LEAK_CHECKED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CUEPLAN_LEAK_CHECKED 1
#endif
#endif
#ifdef CUEPLAN_LEAK_CHECKED
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace cueplan::draw::detail {
namespace {

constexpr const char* kFontFamily = "DejaVu Sans";

// The label's Pango markup and its plain words: "k_{T}" -> "k<sub>T</sub>" and "kT".
std::pair<std::string, std::string> markup_of(std::string_view label) {
  std::string markup, plain;
  size_t i = 0;
  while (i < label.size()) {
    const size_t sub = label.find("_{", i);
    const size_t sup = label.find("^{", i);
    const size_t open = std::min(sub, sup);
    const size_t close = open == std::string_view::npos ? open : label.find('}', open);
    if (close == std::string_view::npos) {
      markup += escape_xml(label.substr(i));
      plain += label.substr(i);
      break;
    }
    markup += escape_xml(label.substr(i, open - i));
    plain += label.substr(i, open - i);
    const std::string_view inner = label.substr(open + 2, close - open - 2);
    const char* tag = open == sub ? "sub" : "sup";
    markup += std::string("<") + tag + ">" + escape_xml(inner) + "</" + tag + ">";
    plain += inner;
    i = close + 1;
  }
  return {markup, plain};
}

void set_colour(cairo_t* cr, Colour c) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a);
}

void trace(cairo_t* cr, const Path& path) {
  cairo_new_path(cr);
  for (const Path::Element& e : path.elements()) {
    switch (e.op) {
      case Path::Op::move: cairo_move_to(cr, e.v[0], e.v[1]); break;
      case Path::Op::line: cairo_line_to(cr, e.v[0], e.v[1]); break;
      case Path::Op::curve:
        cairo_curve_to(cr, e.v[0], e.v[1], e.v[2], e.v[3], e.v[4], e.v[5]);
        break;
      case Path::Op::arc: cairo_arc(cr, e.v[0], e.v[1], e.v[2], e.v[3], e.v[4]); break;
      case Path::Op::close: cairo_close_path(cr); break;
    }
  }
}

void apply_pen(cairo_t* cr, const Pen& pen) {
  set_colour(cr, pen.colour);
  cairo_set_line_width(cr, pen.width);
  cairo_set_dash(cr, pen.dash.empty() ? nullptr : pen.dash.data(),
                 static_cast<int>(pen.dash.size()), 0.0);
  cairo_set_line_cap(cr, pen.cap == LineCap::round    ? CAIRO_LINE_CAP_ROUND
                         : pen.cap == LineCap::square ? CAIRO_LINE_CAP_SQUARE
                                                      : CAIRO_LINE_CAP_BUTT);
  cairo_set_line_join(cr, pen.round_join ? CAIRO_LINE_JOIN_ROUND : CAIRO_LINE_JOIN_MITER);
}

Box rotated_box(const Box& b, double px, double py, double angle_deg) {
  const double a = -angle_deg * std::numbers::pi / 180.0;  // y points down on the page
  const double c = std::cos(a), s = std::sin(a);
  Box out{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (const Point p : {Point{b.left, b.top}, Point{b.right, b.top}, Point{b.left, b.bottom},
                        Point{b.right, b.bottom}}) {
    const double x = px + c * (p.x - px) - s * (p.y - py);
    const double y = py + s * (p.x - px) + c * (p.y - py);
    out.left = std::min(out.left, x);
    out.right = std::max(out.right, x);
    out.top = std::min(out.top, y);
    out.bottom = std::max(out.bottom, y);
  }
  return out;
}

}  // namespace

std::string escape_xml(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      default: out += c;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// Path

Path& Path::move_to(double x, double y) {
  elements_.push_back({Op::move, {x, y}});
  current_ = start_ = {x, y};
  return *this;
}

Path& Path::line_to(double x, double y) {
  elements_.push_back({Op::line, {x, y}});
  current_ = {x, y};
  return *this;
}

Path& Path::curve_to(double x1, double y1, double x2, double y2, double x, double y) {
  elements_.push_back({Op::curve, {x1, y1, x2, y2, x, y}});
  current_ = {x, y};
  return *this;
}

Path& Path::quad_to(double cx, double cy, double x, double y) {
  // Degree elevation: the cubic's controls lie 2/3 of the way to the quadratic's.
  const Point p0 = current_;
  return curve_to(p0.x + 2.0 / 3.0 * (cx - p0.x), p0.y + 2.0 / 3.0 * (cy - p0.y),
                  x + 2.0 / 3.0 * (cx - x), y + 2.0 / 3.0 * (cy - y), x, y);
}

Path& Path::arc(double cx, double cy, double r, double a0, double a1) {
  elements_.push_back({Op::arc, {cx, cy, r, a0, a1}});
  current_ = {cx + r * std::cos(a1), cy + r * std::sin(a1)};
  return *this;
}

Path& Path::close() {
  elements_.push_back({Op::close, {}});
  current_ = start_;
  return *this;
}

Path& Path::rect(double x, double y, double w, double h) {
  return move_to(x, y).line_to(x + w, y).line_to(x + w, y + h).line_to(x, y + h).close();
}

Path& Path::circle(double cx, double cy, double r) {
  move_to(cx + r, cy);
  arc(cx, cy, r, 0.0, 2.0 * std::numbers::pi);
  return close();
}

Path& Path::polygon(const std::vector<Point>& points) {
  for (size_t i = 0; i < points.size(); ++i)
    i == 0 ? move_to(points[i].x, points[i].y) : line_to(points[i].x, points[i].y);
  return points.empty() ? *this : close();
}

Box Path::bounds() const {
  Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
  const auto add = [&](double x, double y) {
    b.left = std::min(b.left, x);
    b.right = std::max(b.right, x);
    b.top = std::min(b.top, y);
    b.bottom = std::max(b.bottom, y);
  };
  for (const Element& e : elements_) {
    switch (e.op) {
      case Op::move:
      case Op::line: add(e.v[0], e.v[1]); break;
      case Op::curve:
        add(e.v[0], e.v[1]);
        add(e.v[2], e.v[3]);
        add(e.v[4], e.v[5]);
        break;
      case Op::arc:
        add(e.v[0] - e.v[2], e.v[1] - e.v[2]);
        add(e.v[0] + e.v[2], e.v[1] + e.v[2]);
        break;
      case Op::close: break;
    }
  }
  return elements_.empty() ? Box{} : b;
}

Path Path::translated(double dx, double dy) const {
  Path p = *this;
  for (Element& e : p.elements_) {
    switch (e.op) {
      case Op::move:
      case Op::line:
      case Op::arc:
        e.v[0] += dx;
        e.v[1] += dy;
        break;
      case Op::curve:
        for (int i = 0; i < 6; i += 2) {
          e.v[i] += dx;
          e.v[i + 1] += dy;
        }
        break;
      case Op::close: break;
    }
  }
  return p;
}

// ---------------------------------------------------------------------------
// Text

Typesetter::Typesetter() {
  // The same font options for measuring and for every surface: no hinting, no rounding
  // of glyph positions, so a text is as wide in a PNG as in an SVG or a PDF.
  // A font map of its own, released with the last picture that uses it: no state shared
  // between threads, nothing of Pango's left behind.
  PangoFontMap* fonts = pango_cairo_font_map_new();
  context_ = pango_font_map_create_context(fonts);
  g_object_unref(fonts);  // the context holds it
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_NONE);
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  pango_cairo_context_set_font_options(context_, options);
  cairo_font_options_destroy(options);
  pango_cairo_context_set_resolution(context_, 96.0);
  pango_context_set_round_glyph_positions(context_, FALSE);
}

Typesetter::~Typesetter() {
  g_object_unref(context_);
}

Text Typesetter::set(std::string_view label, Font font, double wrap_width, Align align) const {
  PangoLayout* layout = pango_layout_new(context_);
  PangoFontDescription* description = pango_font_description_new();
  pango_font_description_set_family(description, kFontFamily);
  pango_font_description_set_absolute_size(description, font.size * PANGO_SCALE);
  pango_font_description_set_weight(description,
                                    font.bold ? PANGO_WEIGHT_BOLD : PANGO_WEIGHT_NORMAL);
  pango_layout_set_font_description(layout, description);
  pango_font_description_free(description);
  const auto [markup, plain] = markup_of(label);
  pango_layout_set_markup(layout, markup.c_str(), -1);
  if (wrap_width > 0.0) {
    pango_layout_set_width(layout, static_cast<int>(wrap_width * PANGO_SCALE));
    pango_layout_set_wrap(layout, PANGO_WRAP_WORD_CHAR);
  }
  pango_layout_set_alignment(layout, align == Align::centre  ? PANGO_ALIGN_CENTER
                                     : align == Align::right ? PANGO_ALIGN_RIGHT
                                                             : PANGO_ALIGN_LEFT);
  PangoRectangle logical;
  pango_layout_get_extents(layout, nullptr, &logical);
  Text t;
  t.layout_ = std::shared_ptr<PangoLayout>(layout, [](PangoLayout* l) { g_object_unref(l); });
  // A wrapped layout is as wide as its wrap width; its lines may be narrower.
  t.width_ = static_cast<double>(logical.x + logical.width) / PANGO_SCALE;
  t.height_ = static_cast<double>(logical.y + logical.height) / PANGO_SCALE;
  t.baseline_ = static_cast<double>(pango_layout_get_baseline(layout)) / PANGO_SCALE;
  t.plain_ = plain;
  return t;
}

Box text_box(const Text& text, double x, double y, Anchor anchor) {
  const double left = x - anchor.x * text.width();
  double top = y;
  switch (anchor.v) {
    case VAnchor::top: break;
    case VAnchor::middle: top = y - 0.5 * text.height(); break;
    case VAnchor::baseline: top = y - text.baseline(); break;
    case VAnchor::bottom: top = y - text.height(); break;
  }
  return {left, top, left + text.width(), top + text.height()};
}

// ---------------------------------------------------------------------------
// Canvas

// Whole units, so that the page of every format ends where the picture does.
Canvas::Canvas(double width, double height)
    : width_(std::ceil(width)), height_(std::ceil(height)) {}

void Canvas::fill(const Path& path, Colour colour, std::string role) {
  ops_.push_back(Shape{path, true, colour, false, Pen(), std::move(role), {}, {}, {}});
}

void Canvas::stroke(const Path& path, const Pen& pen, std::string role) {
  ops_.push_back(Shape{path, false, Colour(), true, pen, std::move(role), {}, {}, {}});
}

void Canvas::fill_and_stroke(const Path& path, Colour fill, const Pen& pen, std::string role) {
  ops_.push_back(Shape{path, true, fill, true, pen, std::move(role), {}, {}, {}});
}

void Canvas::fill_gradient(const Path& path, Point from, Point to, std::vector<Stop> stops,
                           std::string role) {
  ops_.push_back(
      Shape{path, true, Colour(), false, Pen(), std::move(role), std::move(stops), from, to});
}

Box Canvas::text(const Text& text, double x, double y, Anchor anchor, Colour colour,
                 std::string role, double angle_deg) {
  TextOp t;
  t.text = text;
  const Box upright = text_box(text, x, y, anchor);
  t.x = upright.left;
  t.y = upright.top;
  t.angle_deg = angle_deg;
  t.pivot_x = x;
  t.pivot_y = y;
  t.colour = colour;
  t.role = std::move(role);
  t.box = angle_deg == 0.0 ? upright : rotated_box(upright, x, y, angle_deg);
  const Box box = t.box;
  ops_.push_back(std::move(t));
  return box;
}

void Canvas::clip(const Path& path) {
  ops_.push_back(ClipOp{path});
  ++open_clips_;
}

void Canvas::unclip() {
  if (open_clips_ == 0) return;
  ops_.push_back(UnclipOp{});
  --open_clips_;
}

void Canvas::embed(std::shared_ptr<const Canvas> panel, double dx, double dy) {
  ops_.push_back(EmbedOp{std::move(panel), dx, dy});
}

void Canvas::paint(cairo_t* cr) const {
  int saved = 0;
  for (const Op& op : ops_) {
    if (const Shape* s = std::get_if<Shape>(&op)) {
      trace(cr, s->path);
      cairo_pattern_t* gradient = nullptr;
      if (!s->gradient.empty()) {
        gradient = cairo_pattern_create_linear(s->from.x, s->from.y, s->to.x, s->to.y);
        for (const Stop& stop : s->gradient)
          cairo_pattern_add_color_stop_rgba(gradient, stop.offset, stop.colour.r, stop.colour.g,
                                            stop.colour.b, stop.colour.a);
        cairo_set_source(cr, gradient);
      }
      if (s->filled) {
        if (!gradient) set_colour(cr, s->fill);
        if (s->stroked)
          cairo_fill_preserve(cr);
        else
          cairo_fill(cr);
      }
      if (gradient) cairo_pattern_destroy(gradient);
      if (s->stroked) {
        apply_pen(cr, s->pen);
        cairo_stroke(cr);
      }
    } else if (const TextOp* t = std::get_if<TextOp>(&op)) {
      cairo_save(cr);
      if (t->angle_deg != 0.0) {
        cairo_translate(cr, t->pivot_x, t->pivot_y);
        cairo_rotate(cr, -t->angle_deg * std::numbers::pi / 180.0);
        cairo_translate(cr, -t->pivot_x, -t->pivot_y);
      }
      set_colour(cr, t->colour);
      cairo_move_to(cr, t->x, t->y);
      pango_cairo_show_layout(cr, t->text.layout());
      cairo_restore(cr);
    } else if (const ClipOp* c = std::get_if<ClipOp>(&op)) {
      cairo_save(cr);
      ++saved;
      trace(cr, c->path);
      cairo_clip(cr);
    } else if (std::holds_alternative<UnclipOp>(op)) {
      if (saved > 0) {
        cairo_restore(cr);
        --saved;
      }
    } else if (const EmbedOp* e = std::get_if<EmbedOp>(&op)) {
      cairo_save(cr);
      cairo_translate(cr, e->dx, e->dy);
      e->panel->paint(cr);
      cairo_restore(cr);
    }
  }
  for (; saved > 0; --saved) cairo_restore(cr);
}

void Canvas::collect(std::vector<Mark>* marks, double dx, double dy) const {
  const auto moved = [&](Box b) {
    return Box{b.left + dx, b.top + dy, b.right + dx, b.bottom + dy};
  };
  for (const Op& op : ops_) {
    if (const Shape* s = std::get_if<Shape>(&op)) {
      if (s->role.empty()) continue;
      Box b = s->path.bounds();
      if (s->stroked) b = b.grown(0.5 * s->pen.width);
      marks->push_back({s->role, moved(b), {}, false});
    } else if (const TextOp* t = std::get_if<TextOp>(&op)) {
      marks->push_back({t->role, moved(t->box), t->text.plain(), true});
    } else if (const EmbedOp* e = std::get_if<EmbedOp>(&op)) {
      e->panel->collect(marks, dx + e->dx, dy + e->dy);
    }
  }
}

std::vector<Mark> Canvas::marks() const {
  std::vector<Mark> marks;
  collect(&marks, 0.0, 0.0);
  return marks;
}

}  // namespace cueplan::draw::detail
