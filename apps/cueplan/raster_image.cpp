#include "raster_image.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cueplan::cli {
namespace {

// The font: 5 columns by 8 rows per glyph, capitals and digits on rows 0-6 (row 6 is
// the baseline), lower case from row 2, descenders on row 7. '#' marks a pixel.
struct Glyph {
  char32_t code;
  const char* rows;  // 8 groups of 5, separated by spaces
};

constexpr Glyph kFont[] = {
    {U' ', "..... ..... ..... ..... ..... ..... ..... ....."},
    {U'!', "..#.. ..#.. ..#.. ..#.. ..#.. ..... ..#.. ....."},
    {U'"', ".#.#. .#.#. ..... ..... ..... ..... ..... ....."},
    {U'%', "##... ##..# ...#. ..#.. .#... #..## ...## ....."},
    {U'\'', "..#.. ..#.. ..... ..... ..... ..... ..... ....."},
    {U'(', "...#. ..#.. .#... .#... .#... ..#.. ...#. ....."},
    {U')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#... ....."},
    {U'*', "..... ..#.. #.#.# .###. #.#.# ..#.. ..... ....."},
    {U'+', "..... ..#.. ..#.. ##### ..#.. ..#.. ..... ....."},
    {U',', "..... ..... ..... ..... ..... .##.. ..#.. .#..."},
    {U'-', "..... ..... ..... .###. ..... ..... ..... ....."},
    {U'.', "..... ..... ..... ..... ..... .##.. .##.. ....."},
    {U'/', "..... ....# ...#. ..#.. .#... #.... ..... ....."},
    {U'0', ".###. #...# #..## #.#.# ##..# #...# .###. ....."},
    {U'1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'2', ".###. #...# ....# ...#. ..#.. .#... ##### ....."},
    {U'3', "##### ...#. ..#.. ...#. ....# #...# .###. ....."},
    {U'4', "...#. ..##. .#.#. #..#. ##### ...#. ...#. ....."},
    {U'5', "##### #.... ####. ....# ....# #...# .###. ....."},
    {U'6', "..##. .#... #.... ####. #...# #...# .###. ....."},
    {U'7', "##### ....# ...#. ..#.. .#... .#... .#... ....."},
    {U'8', ".###. #...# #...# .###. #...# #...# .###. ....."},
    {U'9', ".###. #...# #...# .#### ....# ...#. .##.. ....."},
    {U':', "..... .##.. .##.. ..... .##.. .##.. ..... ....."},
    {U';', "..... .##.. .##.. ..... .##.. ..#.. .#... ....."},
    {U'<', "...#. ..#.. .#... #.... .#... ..#.. ...#. ....."},
    {U'=', "..... ..... ##### ..... ##### ..... ..... ....."},
    {U'>', ".#... ..#.. ...#. ....# ...#. ..#.. .#... ....."},
    {U'?', ".###. #...# ....# ...#. ..#.. ..... ..#.. ....."},
    {U'A', ".###. #...# #...# ##### #...# #...# #...# ....."},
    {U'B', "####. #...# #...# ####. #...# #...# ####. ....."},
    {U'C', ".###. #...# #.... #.... #.... #...# .###. ....."},
    {U'D', "####. #...# #...# #...# #...# #...# ####. ....."},
    {U'E', "##### #.... #.... ####. #.... #.... ##### ....."},
    {U'F', "##### #.... #.... ####. #.... #.... #.... ....."},
    {U'G', ".###. #...# #.... #.### #...# #...# .#### ....."},
    {U'H', "#...# #...# #...# ##### #...# #...# #...# ....."},
    {U'I', ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'J', "..### ...#. ...#. ...#. ...#. #..#. .##.. ....."},
    {U'K', "#...# #..#. #.#.. ##... #.#.. #..#. #...# ....."},
    {U'L', "#.... #.... #.... #.... #.... #.... ##### ....."},
    {U'M', "#...# ##.## #.#.# #.#.# #...# #...# #...# ....."},
    {U'N', "#...# #...# ##..# #.#.# #..## #...# #...# ....."},
    {U'O', ".###. #...# #...# #...# #...# #...# .###. ....."},
    {U'P', "####. #...# #...# ####. #.... #.... #.... ....."},
    {U'Q', ".###. #...# #...# #...# #.#.# #..#. .##.# ....."},
    {U'R', "####. #...# #...# ####. #.#.. #..#. #...# ....."},
    {U'S', ".#### #.... #.... .###. ....# ....# ####. ....."},
    {U'T', "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ....."},
    {U'U', "#...# #...# #...# #...# #...# #...# .###. ....."},
    {U'V', "#...# #...# #...# #...# #...# .#.#. ..#.. ....."},
    {U'W', "#...# #...# #...# #.#.# #.#.# #.#.# .#.#. ....."},
    {U'X', "#...# #...# .#.#. ..#.. .#.#. #...# #...# ....."},
    {U'Y', "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.. ....."},
    {U'Z', "##### ....# ...#. ..#.. .#... #.... ##### ....."},
    {U'[', ".###. .#... .#... .#... .#... .#... .###. ....."},
    {U']', ".###. ...#. ...#. ...#. ...#. ...#. .###. ....."},
    {U'^', "..#.. .#.#. #...# ..... ..... ..... ..... ....."},
    {U'_', "..... ..... ..... ..... ..... ..... ..... #####"},
    {U'a', "..... ..... .###. ....# .#### #...# .#### ....."},
    {U'b', "#.... #.... #.##. ##..# #...# #...# ####. ....."},
    {U'c', "..... ..... .###. #.... #.... #...# .###. ....."},
    {U'd', "....# ....# .##.# #..## #...# #...# .#### ....."},
    {U'e', "..... ..... .###. #...# ##### #.... .###. ....."},
    {U'f', "..##. .#..# .#... ###.. .#... .#... .#... ....."},
    {U'g', "..... ..... .#### #...# #...# .#### ....# .###."},
    {U'h', "#.... #.... #.##. ##..# #...# #...# #...# ....."},
    {U'i', "..#.. ..... .##.. ..#.. ..#.. ..#.. .###. ....."},
    {U'j', "...#. ..... ..##. ...#. ...#. ...#. #..#. .##.."},
    {U'k', "#.... #.... #..#. #.#.. ##... #.#.. #..#. ....."},
    {U'l', ".##.. ..#.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'm', "..... ..... ##.#. #.#.# #.#.# #.#.# #.#.# ....."},
    {U'n', "..... ..... #.##. ##..# #...# #...# #...# ....."},
    {U'o', "..... ..... .###. #...# #...# #...# .###. ....."},
    {U'p', "..... ..... ####. #...# #...# ####. #.... #...."},
    {U'q', "..... ..... .#### #...# #...# .#### ....# ....#"},
    {U'r', "..... ..... #.##. ##..# #.... #.... #.... ....."},
    {U's', "..... ..... .###. #.... .###. ....# ####. ....."},
    {U't', ".#... .#... ###.. .#... .#... .#..# ..##. ....."},
    {U'u', "..... ..... #...# #...# #...# #..## .##.# ....."},
    {U'v', "..... ..... #...# #...# #...# .#.#. ..#.. ....."},
    {U'w', "..... ..... #...# #...# #.#.# #.#.# .#.#. ....."},
    {U'x', "..... ..... #...# .#.#. ..#.. .#.#. #...# ....."},
    {U'y', "..... ..... #...# #...# #...# .#### ....# .###."},
    {U'z', "..... ..... ##### ...#. ..#.. .#... ##### ....."},
    {U'|', "..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."},
    {U'\u00b0', ".##.. #..#. .##.. ..... ..... ..... ..... ....."},  // degree sign
    {U'\u00d7', "..... #...# .#.#. ..#.. .#.#. #...# ..... ....."},  // multiplication sign
    {U'\u2212', "..... ..... ..... ##### ..... ..... ..... ....."},  // minus sign
};

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 8;
constexpr int kAdvance = 6;   // glyph width and one column of space
constexpr int kBaseline = 6;  // row of the baseline

const Glyph* find_glyph(char32_t code) {
  for (const Glyph& g : kFont)
    if (g.code == code) return &g;
  return nullptr;
}

// The next code point of UTF-8 text (invalid bytes read as '?').
char32_t next_code_point(std::string_view text, size_t* i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(*i);
  const int extra = lead < 0x80           ? 0
                    : (lead >> 5) == 0x6  ? 1
                    : (lead >> 4) == 0xE  ? 2
                    : (lead >> 3) == 0x1E ? 3
                                          : -1;
  if (extra < 0 || *i + static_cast<size_t>(extra) >= text.size()) {
    ++*i;
    return U'?';
  }
  char32_t code = extra == 0 ? lead : lead & (0x3F >> extra);
  for (int k = 1; k <= extra; ++k) code = (code << 6) | (byte(*i + static_cast<size_t>(k)) & 0x3F);
  *i += static_cast<size_t>(extra) + 1;
  return code;
}

// Text split at subscripts written `k_{T}`, as code points with a lowered flag.
struct Character {
  char32_t code;
  bool lowered;
};

std::vector<Character> characters(std::string_view label) {
  std::vector<Character> out;
  bool lowered = false;
  for (size_t i = 0; i < label.size();) {
    if (!lowered && label.compare(i, 2, "_{") == 0 &&
        label.find('}', i) != std::string_view::npos) {
      lowered = true;
      i += 2;
      continue;
    }
    if (lowered && label[i] == '}') {
      lowered = false;
      ++i;
      continue;
    }
    out.push_back({next_code_point(label, &i), lowered});
  }
  return out;
}

uint8_t mix(uint8_t under, uint8_t over, double alpha) {
  return static_cast<uint8_t>(std::lround(under + (over - under) * alpha));
}

// PNG chunks: length, type, data, CRC-32 of type and data.
void append_u32(std::string* out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out->push_back(static_cast<char>((v >> shift) & 0xFF));
}

void append_chunk(std::string* out, const char type[5], const std::string& data) {
  append_u32(out, static_cast<uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out->append(body);
  const uLong crc =
      crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()));
  append_u32(out, static_cast<uint32_t>(crc));
}

}  // namespace

Rgb parse_colour(std::string_view hex) {
  if (hex.size() != 7 || hex[0] != '#') return {};
  const auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  const auto channel = [&](size_t at) {
    return static_cast<uint8_t>(nibble(hex[at]) * 16 + nibble(hex[at + 1]));
  };
  return {channel(1), channel(3), channel(5)};
}

Raster::Raster(int width, int height, Rgb background)
    : width_(std::max(1, width)),
      height_(std::max(1, height)),
      pixels_(static_cast<size_t>(width_) * static_cast<size_t>(height_), background) {}

Rgb Raster::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return {};
  return pixels_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
}

void Raster::blend(int x, int y, Rgb colour, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0)) return;
  Rgb& p = pixels_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
  alpha = std::min(alpha, 1.0);
  p = {mix(p.r, colour.r, alpha), mix(p.g, colour.g, alpha), mix(p.b, colour.b, alpha)};
}

template <typename Inside>
void Raster::fill_shape(double x0, double y0, double x1, double y1, Rgb colour, double opacity,
                        const Inside& inside) {
  constexpr int kSamples = 4;
  const int px0 = std::max(0, static_cast<int>(std::floor(x0)));
  const int py0 = std::max(0, static_cast<int>(std::floor(y0)));
  const int px1 = std::min(width_ - 1, static_cast<int>(std::ceil(x1)));
  const int py1 = std::min(height_ - 1, static_cast<int>(std::ceil(y1)));
  for (int py = py0; py <= py1; ++py)
    for (int px = px0; px <= px1; ++px) {
      int hits = 0;
      for (int sy = 0; sy < kSamples; ++sy)
        for (int sx = 0; sx < kSamples; ++sx)
          hits += inside(px + (sx + 0.5) / kSamples, py + (sy + 0.5) / kSamples) ? 1 : 0;
      if (hits > 0) blend(px, py, colour, opacity * hits / (kSamples * kSamples));
    }
}

void Raster::fill_rect(double x, double y, double w, double h, Rgb colour, double opacity) {
  fill_shape(x, y, x + w, y + h, colour, opacity,
             [&](double px, double py) { return px >= x && px < x + w && py >= y && py < y + h; });
}

void Raster::fill_circle(double cx, double cy, double r, Rgb colour, double opacity) {
  fill_shape(cx - r, cy - r, cx + r, cy + r, colour, opacity, [&](double px, double py) {
    return (px - cx) * (px - cx) + (py - cy) * (py - cy) <= r * r;
  });
}

void Raster::stroke_circle(double cx, double cy, double r, double width, Rgb colour, double opacity,
                           double dash) {
  const double outer = r + 0.5 * width;
  const double inner = std::max(0.0, r - 0.5 * width);
  // Dashes: an even number of equal arcs round the circle.
  const double circumference = 2.0 * std::numbers::pi * r;
  const int pieces =
      dash > 0.0 ? std::max(2, 2 * static_cast<int>(circumference / (2.0 * dash))) : 0;
  fill_shape(cx - outer, cy - outer, cx + outer, cy + outer, colour, opacity,
             [&](double px, double py) {
               const double d2 = (px - cx) * (px - cx) + (py - cy) * (py - cy);
               if (d2 > outer * outer || d2 < inner * inner) return false;
               if (pieces == 0) return true;
               const double turn =
                   (std::atan2(py - cy, px - cx) + std::numbers::pi) / (2.0 * std::numbers::pi);
               return static_cast<int>(turn * pieces) % 2 == 0;
             });
}

void Raster::line(double x1, double y1, double x2, double y2, double width, Rgb colour,
                  double opacity) {
  const double half = 0.5 * width;
  const double dx = x2 - x1;
  const double dy = y2 - y1;
  const double length2 = dx * dx + dy * dy;
  fill_shape(std::min(x1, x2) - half, std::min(y1, y2) - half, std::max(x1, x2) + half,
             std::max(y1, y2) + half, colour, opacity, [&](double px, double py) {
               double t = length2 > 0.0 ? ((px - x1) * dx + (py - y1) * dy) / length2 : 0.0;
               t = std::clamp(t, 0.0, 1.0);
               const double ex = x1 + t * dx - px;
               const double ey = y1 + t * dy - py;
               return ex * ex + ey * ey <= half * half;
             });
}

void Raster::hatch_rect(double x, double y, double w, double h, double spacing, Rgb colour) {
  fill_shape(x, y, x + w, y + h, colour, 1.0, [&](double px, double py) {
    if (px < x || px >= x + w || py < y || py >= y + h) return false;
    const double phase = std::fmod(px + py, spacing);
    return phase < 1.2;
  });
}

double Raster::text_width(std::string_view label, int scale) {
  const size_t n = characters(label).size();
  return n == 0 ? 0.0 : static_cast<double>(n * kAdvance - 1) * scale;
}

double Raster::text(double x, double y, std::string_view label, int scale, Rgb colour,
                    double anchor) {
  const double width = text_width(label, scale);
  int left = static_cast<int>(std::lround(x - anchor * width));
  const int top = static_cast<int>(std::lround(y)) - kBaseline * scale;
  for (const Character& c : characters(label)) {
    const Glyph* glyph = find_glyph(c.code);
    if (!glyph) glyph = find_glyph(U'?');
    const int drop = c.lowered ? 3 * scale : 0;
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (glyph->rows[row * (kGlyphWidth + 1) + col] != '#') continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx)
            blend(left + col * scale + sx, top + drop + row * scale + sy, colour, 1.0);
      }
    left += kAdvance * scale;
  }
  return width;
}

std::string encode_png(const Raster& image) {
  // Rows, each led by filter type 0 (none).
  const size_t w = static_cast<size_t>(image.width());
  const size_t h = static_cast<size_t>(image.height());
  std::string raw;
  raw.reserve(h * (1 + 3 * w));
  for (size_t y = 0; y < h; ++y) {
    raw.push_back('\0');
    for (size_t x = 0; x < w; ++x) {
      const Rgb p = image.at(static_cast<int>(x), static_cast<int>(y));
      raw.push_back(static_cast<char>(p.r));
      raw.push_back(static_cast<char>(p.g));
      raw.push_back(static_cast<char>(p.b));
    }
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                Z_BEST_COMPRESSION) != Z_OK)
    throw std::runtime_error("zlib could not compress the image");
  packed.resize(packed_size);

  std::string png = "\x89PNG\r\n\x1a\n";
  std::string header;
  append_u32(&header, static_cast<uint32_t>(w));
  append_u32(&header, static_cast<uint32_t>(h));
  header +=
      std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter, no interlace
  append_chunk(&png, "IHDR", header);
  append_chunk(&png, "IDAT", packed);
  append_chunk(&png, "IEND", {});
  return png;
}

}  // namespace cueplan::cli
