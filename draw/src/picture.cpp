#include "cueplan/draw/picture.hpp"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "canvas.hpp"

namespace cueplan::draw {
namespace {

cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Cairo writes glyphs as outlines, so an SVG's words are not in its text: its title and
// description go in as <title> and <desc>, right after the root element opens.
void add_svg_metadata(std::string* svg, const std::string& title, const std::string& description) {
  const size_t root = svg->find("<svg");
  const size_t open_end = root == std::string::npos ? root : svg->find('>', root);
  if (open_end == std::string::npos) return;
  std::string metadata = "\n<title>" + detail::escape_xml(title) + "</title>";
  if (!description.empty()) metadata += "\n<desc>" + detail::escape_xml(description) + "</desc>";
  svg->insert(open_end + 1, metadata);
}

}  // namespace

std::string Colour::to_hex() const {
  const auto byte = [](double v) {
    return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  };
  return fmt::format("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b));
}

const char* to_string(Format format) {
  switch (format) {
    case Format::svg: return "svg";
    case Format::png: return "png";
    case Format::pdf: return "pdf";
  }
  return "?";
}

std::optional<Format> format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return Format::svg;
  if (ext == ".png") return Format::png;
  if (ext == ".pdf") return Format::pdf;
  return std::nullopt;
}

bool Box::overlaps(const Box& o) const {
  return left < o.right && o.left < right && top < o.bottom && o.top < bottom;
}

bool Box::inside(const Box& o) const {
  return left >= o.left && right <= o.right && top >= o.top && bottom <= o.bottom;
}

Picture::Picture() = default;

Picture::Picture(std::shared_ptr<const detail::Canvas> canvas, std::string title,
                 std::string description)
    : canvas_(std::move(canvas)),
      width_(canvas_->width()),
      height_(canvas_->height()),
      marks_(canvas_->marks()),
      title_(std::move(title)),
      description_(std::move(description)) {}

std::vector<Mark> Picture::marks_of(std::string_view role) const {
  std::vector<Mark> out;
  for (const Mark& m : marks_)
    if (m.role == role) out.push_back(m);
  return out;
}

Encoded encode(const Picture& picture, Format format, const EncodeOptions& options) {
  Encoded result;
  if (!picture.canvas()) {
    result.error = "the picture is empty";
    return result;
  }
  if (!(options.png_scale > 0.0 && options.png_scale <= 8.0)) {
    result.error = fmt::format("png_scale must lie in (0, 8], got {}", options.png_scale);
    return result;
  }
  // Whole units, so that a PNG's pixels and an SVG's or a PDF's page agree.
  const double width = std::ceil(picture.width());
  const double height = std::ceil(picture.height());
  const double scale = format == Format::png ? options.png_scale : 1.0;
  cairo_surface_t* surface = nullptr;
  switch (format) {
    case Format::svg:
      surface = cairo_svg_surface_create_for_stream(append_bytes, &result.bytes, width, height);
      cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
      break;
    case Format::pdf:
      surface = cairo_pdf_surface_create_for_stream(append_bytes, &result.bytes, width, height);
      cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, picture.title().c_str());
      cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "cueplan");
      break;
    case Format::png:
      // Opaque: every picture paints its white page first, so no alpha channel is stored.
      surface =
          cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(std::ceil(width * scale)),
                                     static_cast<int>(std::ceil(height * scale)));
      break;
  }
  cairo_t* cr = cairo_create(surface);
  if (format == Format::png) {  // the page beyond a fractional picture's edge, too
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
  }
  cairo_scale(cr, scale, scale);
  picture.canvas()->paint(cr);
  cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  if (status == CAIRO_STATUS_SUCCESS && format == Format::png)
    status = cairo_surface_write_to_png_stream(surface, append_bytes, &result.bytes);
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    result.bytes.clear();
    result.error = std::string("cannot draw the picture: ") + cairo_status_to_string(status);
    return result;
  }
  if (format == Format::svg)
    add_svg_metadata(&result.bytes, picture.title(), picture.description());
  return result;
}

}  // namespace cueplan::draw
