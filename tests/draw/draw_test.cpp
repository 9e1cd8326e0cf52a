// Tests of the drawing layer (cueplan::draw): every format's file is valid and read back
// by an independent reader (Cairo's PNG reader, libxml2, librsvg, poppler's pdftocairo and
// a PDF cross-reference walk), the formats agree pixel for pixel within a tolerance, the
// table shows what players expect, labels never overlap, text never leaves the canvas,
// extreme scenes stay bounded, and the spin map's cells fill the disc without seams.
#include <cairo.h>
#include <gtest/gtest.h>
#include <librsvg/rsvg.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cueplan/draw/picture.hpp"
#include "cueplan/draw/plot.hpp"
#include "cueplan/draw/spin_map.hpp"
#include "cueplan/draw/table.hpp"
#include "cueplan/planner/spin_map.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::draw {
namespace {

namespace fs = std::filesystem;
namespace phys = cueplan::physics;
namespace plan = cueplan::planner;
namespace prob = cueplan::problems;

// ---------------------------------------------------------------------------
// Shared scenes: the shipped problems, drawn as the commands draw them.

prob::Problem shipped(const std::string& stem) {
  const prob::LoadResult r =
      prob::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + stem + ".yaml");
  if (!r.ok()) ADD_FAILURE() << r.error;
  return r.ok() ? *r.problem : prob::Problem{};
}

phys::ShotResult shot_on(const prob::Problem& p, phys::Vec2 from, const phys::Shot& shot) {
  phys::SimulationOptions o;
  o.record_path = true;
  return phys::simulate(p.scene, from, shot, o);
}

// The witness stroke of one_rail_position.yaml's header (one cushion, to the target).
constexpr phys::Shot kOneRail{1.002, -60.36, 0.8, 0.0};

// As `cueplan simulate --svg` composes it: the problem's table and the cue ball's path.
TableScene simulated(const prob::Problem& p, const phys::Shot& shot,
                     phys::ShotResult* result = nullptr) {
  TableScene t = problem_table(p);
  const phys::ShotResult r = shot_on(p, p.cue_ball, shot);
  t.balls.front().paths.push_back({r.path, r.events, false});
  t.title = p.name + ": V = " + std::to_string(shot.speed) +
            " m/s, k_{T} = " + std::to_string(shot.topspin_k);
  t.caption = {
      "A caption long enough to need wrapping once the picture is narrow: it says where the ball "
      "stops, after how many cushions, and what the table is."};
  if (result) *result = r;
  return t;
}

size_t count(const Picture& p, const std::string& role) {
  return p.marks_of(role).size();
}

std::vector<std::string> texts(const Picture& p, const std::string& role) {
  std::vector<std::string> out;
  for (const Mark& m : p.marks_of(role)) out.push_back(m.text);
  return out;
}

bool has_text(const Picture& p, const std::string& role, const std::string& words) {
  const std::vector<std::string> t = texts(p, role);
  return std::find(t.begin(), t.end(), words) != t.end();
}

Box canvas_of(const Picture& p) {
  return {0.0, 0.0, p.width(), p.height()};
}

// ---------------------------------------------------------------------------
// Images, read back by independent readers.

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // 3 bytes a pixel, composited over white

  const unsigned char* at(int x, int y) const {
    return &rgb[3 * (static_cast<size_t>(y) * width + x)];
  }
  double luminance(int x, int y) const {
    const unsigned char* p = at(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
  }
};

Image from_surface(cairo_surface_t* s) {
  cairo_surface_flush(s);
  Image im;
  im.width = cairo_image_surface_get_width(s);
  im.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const cairo_format_t format = cairo_image_surface_get_format(s);
  im.rgb.resize(3 * static_cast<size_t>(im.width) * im.height);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      unsigned char* out = &im.rgb[3 * (static_cast<size_t>(y) * im.width + x)];
      if (format == CAIRO_FORMAT_RGB24 || format == CAIRO_FORMAT_ARGB32) {
        uint32_t v;
        std::memcpy(&v, data + y * stride + 4 * x, 4);
        const unsigned a = format == CAIRO_FORMAT_ARGB32 ? (v >> 24) & 0xff : 255;
        // Premultiplied colour over white.
        out[0] = static_cast<unsigned char>(((v >> 16) & 0xff) + (255 - a));
        out[1] = static_cast<unsigned char>(((v >> 8) & 0xff) + (255 - a));
        out[2] = static_cast<unsigned char>((v & 0xff) + (255 - a));
      }
    }
  return im;
}

struct Reading {
  const std::string* bytes;
  size_t at = 0;
};

cairo_status_t read_bytes(void* closure, unsigned char* data, unsigned int length) {
  Reading* r = static_cast<Reading*>(closure);
  if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(data, r->bytes->data() + r->at, length);
  r->at += length;
  return CAIRO_STATUS_SUCCESS;
}

// A PNG file's pixels through Cairo's own PNG reader; empty when it cannot be read.
Image read_png(const std::string& bytes) {
  Reading r{&bytes};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(read_bytes, &r);
  Image im;
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) im = from_surface(s);
  cairo_surface_destroy(s);
  return im;
}

// An SVG file rasterised by librsvg at its own size; empty when librsvg refuses it.
Image rasterise_svg(const std::string& bytes) {
  GError* error = nullptr;
  RsvgHandle* h = rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(bytes.data()),
                                            bytes.size(), &error);
  if (!h) {
    ADD_FAILURE() << "librsvg: " << (error ? error->message : "?");
    if (error) g_error_free(error);
    return {};
  }
  gdouble w = 0.0, hgt = 0.0;
  rsvg_handle_set_dpi(h, 96.0);
  if (!rsvg_handle_get_intrinsic_size_in_pixels(h, &w, &hgt)) ADD_FAILURE() << "no intrinsic size";
  cairo_surface_t* s = cairo_image_surface_create(
      CAIRO_FORMAT_ARGB32, static_cast<int>(std::lround(w)), static_cast<int>(std::lround(hgt)));
  cairo_t* cr = cairo_create(s);
  RsvgRectangle viewport{0.0, 0.0, w, hgt};
  if (!rsvg_handle_render_document(h, cr, &viewport, &error)) {
    ADD_FAILURE() << "librsvg: " << (error ? error->message : "?");
    if (error) g_error_free(error);
  }
  cairo_destroy(cr);
  Image im = from_surface(s);
  cairo_surface_destroy(s);
  g_object_unref(h);
  return im;
}

fs::path scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("cueplan_draw_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// A PDF file rendered by poppler (pdftocairo) at 72 dpi: one PDF point to a pixel.
Image render_pdf(const std::string& bytes) {
  const std::string pdftocairo = CUEPLAN_PDFTOCAIRO;
  if (pdftocairo.empty() || pdftocairo.find("NOTFOUND") != std::string::npos) {
    ADD_FAILURE() << "pdftocairo not found (poppler-utils; scripts/setup.sh installs it)";
    return {};
  }
  const fs::path in = scratch() / "picture.pdf";
  const fs::path out = scratch() / "rendered";
  std::ofstream(in, std::ios::binary) << bytes;
  const std::string command =
      "'" + pdftocairo + "' -r 72 -png -singlefile '" + in.string() + "' '" + out.string() + "'";
  if (std::system(command.c_str()) != 0) {
    ADD_FAILURE() << command << " failed";
    return {};
  }
  std::ifstream file(out.string() + ".png", std::ios::binary);
  std::stringstream png;
  png << file.rdbuf();
  return read_png(png.str());
}

struct Difference {
  double mean = INFINITY;     // mean absolute channel difference (0-255)
  double far_fraction = 1.0;  // fraction of pixels with a channel differing by more than 64
};

Difference compare(const Image& a, const Image& b) {
  Difference d;
  if (a.width != b.width || a.height != b.height || a.rgb.empty()) return d;
  double total = 0.0;
  size_t far = 0, pixels = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3) {
    ++pixels;
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(a.rgb[i + c] - b.rgb[i + c]);
      total += diff;
      worst = std::max(worst, diff);
    }
    if (worst > 64) ++far;
  }
  d.mean = total / static_cast<double>(3 * pixels);
  d.far_fraction = static_cast<double>(far) / static_cast<double>(pixels);
  return d;
}

// Two renderings of one drawing: antialiasing differs at edges, nothing else.
void expect_same_picture(const Image& a, const Image& b, const std::string& what) {
  const Difference d = compare(a, b);
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_LT(d.mean, 1.5) << what;
  EXPECT_LT(d.far_fraction, 0.004) << what;
}

// Each pixel the mean of the 3 x 3 around it: a hairline drawn as one dark pixel or as
// two half-dark ones (a renderer that snaps lines to the pixel grid, as poppler does,
// against one that does not) comes out the same.
Image blurred(const Image& im) {
  Image out = im;
  for (int y = 1; y + 1 < im.height; ++y)
    for (int x = 1; x + 1 < im.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) sum += im.at(x + dx, y + dy)[c];
        out.rgb[3 * (static_cast<size_t>(y) * im.width + x) + c] =
            static_cast<unsigned char>(sum / 9);
      }
  return out;
}

std::string encoded(const Picture& p, Format f) {
  const Encoded e = encode(p, f);
  EXPECT_TRUE(e.ok()) << e.error;
  return e.bytes;
}

// ---------------------------------------------------------------------------
// Formats

TEST(Formats, ChosenByTheExtensionInAnyLetterCase) {
  EXPECT_EQ(format_of("plan.svg"), Format::svg);
  EXPECT_EQ(format_of("dir.d/PLAN.PNG"), Format::png);
  EXPECT_EQ(format_of("a/b/c.Pdf"), Format::pdf);
  EXPECT_FALSE(format_of("plan.jpg").has_value());
  EXPECT_FALSE(format_of("plan").has_value());
  EXPECT_FALSE(format_of("svg").has_value());
  EXPECT_FALSE(format_of("plan.svg.tmp").has_value());
}

TEST(Formats, EachFileStartsWithItsMagicBytes) {
  const Picture p = table_picture(simulated(shipped("one_rail_position"), kOneRail));
  EXPECT_EQ(encoded(p, Format::png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(encoded(p, Format::pdf).substr(0, 5), "%PDF-");
  const std::string svg = encoded(p, Format::svg);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
}

TEST(Formats, PngReadsBackThroughCairoAtThePictureSize) {
  const Picture p = table_picture(simulated(shipped("pool_table"), {1.497, 37.98, 0.0, 0.0}));
  const Image im = read_png(encoded(p, Format::png));
  EXPECT_EQ(im.width, static_cast<int>(std::ceil(p.width())));
  EXPECT_EQ(im.height, static_cast<int>(std::ceil(p.height())));
  const Encoded twice = encode(p, Format::png, {2.0});
  ASSERT_TRUE(twice.ok());
  EXPECT_EQ(read_png(twice.bytes).width, 2 * im.width);
  EXPECT_FALSE(encode(p, Format::png, {0.0}).ok());
  EXPECT_FALSE(encode(Picture(), Format::png).ok());
}

// The PDF's cross-reference table is walked as a reader would: every object it lists
// must stand at its offset, and the page must have the picture's size.
TEST(Formats, PdfObjectsStandWhereTheCrossReferenceTableSays) {
  const Picture p = table_picture(simulated(shipped("one_rail_position"), kOneRail));
  const std::string pdf = encoded(p, Format::pdf);
  ASSERT_EQ(pdf.rfind("%PDF-1.", 0), 0u);
  const size_t eof = pdf.rfind("%%EOF");
  ASSERT_NE(eof, std::string::npos);
  const size_t startxref = pdf.rfind("startxref");
  ASSERT_NE(startxref, std::string::npos);
  const size_t xref = std::stoul(pdf.substr(startxref + 9, eof - startxref - 9));
  ASSERT_LT(xref, pdf.size());
  ASSERT_EQ(pdf.compare(xref, 4, "xref"), 0);
  std::istringstream table(pdf.substr(xref + 4));
  int first = -1, objects = 0;
  table >> first >> objects;
  ASSERT_EQ(first, 0);
  ASSERT_GT(objects, 3);
  int found = 0;
  for (int i = 0; i < objects; ++i) {
    std::string offset, generation, kind;
    table >> offset >> generation >> kind;
    if (kind != "n") continue;
    const size_t at = std::stoul(offset);
    const std::string header =
        std::to_string(first + i) + " " + std::to_string(std::stoi(generation)) + " obj";
    EXPECT_EQ(pdf.compare(at, header.size(), header), 0) << "object " << i << " at " << at;
    ++found;
  }
  EXPECT_EQ(found, objects - 1);  // all but the free head of the list
  const std::string media = "/MediaBox [ 0 0 " +
                            std::to_string(static_cast<int>(std::ceil(p.width()))) + " " +
                            std::to_string(static_cast<int>(std::ceil(p.height()))) + " ]";
  EXPECT_NE(pdf.find(media), std::string::npos) << media;
}

TEST(Formats, SvgIsWellFormedXmlWithTheTitleAndSizeInPixels) {
  const Picture p = table_picture(simulated(shipped("one_rail_position"), kOneRail));
  const std::string svg = encoded(p, Format::svg);
  xmlDocPtr doc = xmlReadMemory(svg.data(), static_cast<int>(svg.size()), "picture.svg", nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  ASSERT_NE(doc, nullptr) << "not well-formed XML";
  xmlNodePtr root = xmlDocGetRootElement(doc);
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(reinterpret_cast<const char*>(root->name), "svg");
  const auto attribute = [&](const char* name) {
    xmlChar* v = xmlGetProp(root, reinterpret_cast<const xmlChar*>(name));
    std::string s = v ? reinterpret_cast<const char*>(v) : "";
    xmlFree(v);
    return s;
  };
  EXPECT_EQ(attribute("width"), std::to_string(static_cast<int>(std::ceil(p.width()))) + "px");
  EXPECT_EQ(attribute("height"), std::to_string(static_cast<int>(std::ceil(p.height()))) + "px");
  std::string title;
  for (xmlNodePtr n = root->children; n; n = n->next)
    if (n->type == XML_ELEMENT_NODE &&
        std::string(reinterpret_cast<const char*>(n->name)) == "title") {
      xmlChar* t = xmlNodeGetContent(n);
      title = reinterpret_cast<const char*>(t);
      xmlFree(t);
    }
  EXPECT_EQ(title, p.title());
  EXPECT_NE(title.find("one-rail position"), std::string::npos);
  xmlFreeDoc(doc);
}

TEST(Formats, SvgRasterisedByLibrsvgMatchesCairosPng) {
  const Picture table =
      table_picture(simulated(shipped("two_rail_position"), {1.227, 30.22, 1.0, 0.0}));
  expect_same_picture(read_png(encoded(table, Format::png)),
                      rasterise_svg(encoded(table, Format::svg)), "table");
  PlotPanel panel;
  panel.title = "Rebound speed";
  panel.x_axis.label = "incidence angle \u03b1 (deg)";
  panel.y_axis.label = "rebound speed (m/s)";
  PlotSeries s;
  s.label = "V_{0} = 1 m/s";
  for (int i = 0; i <= 90; ++i) {
    s.x.push_back(i);
    s.y.push_back(0.8 + 0.1 * std::cos(i * 0.05));
  }
  panel.series = {s};
  const Picture plot = plot_picture({"Fig.", "caption", {panel}});
  expect_same_picture(read_png(encoded(plot, Format::png)),
                      rasterise_svg(encoded(plot, Format::svg)), "plot");
}

// Poppler snaps hairlines and hinted glyphs to whole pixels, which Cairo's PNG does not:
// both are compared after a 3 x 3 blur.
TEST(Formats, PdfRenderedByPopplerMatchesCairosPng) {
  const Picture p =
      table_picture(simulated(shipped("carom_three_cushion"), {1.75, 119.1, 0.0, 0.0}));
  const Image png = blurred(read_png(encoded(p, Format::png)));
  const Image pdf = blurred(render_pdf(encoded(p, Format::pdf)));
  expect_same_picture(png, pdf, "table");
  // The blur hides no real difference: another stroke's picture does not pass.
  const Picture other =
      table_picture(simulated(shipped("carom_three_cushion"), {1.75, 110.0, 0.0, 0.0}));
  EXPECT_GT(compare(png, blurred(render_pdf(encoded(other, Format::pdf)))).far_fraction, 0.004);
}

// The comparison above can fail: two different pictures of the same size differ.
TEST(Formats, DifferentDrawingsDoNotPassForTheSame) {
  const prob::Problem problem = shipped("one_rail_position");
  const Picture a = table_picture(simulated(problem, kOneRail));
  const Picture b = table_picture(simulated(problem, {1.002, -50.0, 0.8, 0.0}));
  ASSERT_EQ(std::ceil(a.width()), std::ceil(b.width()));
  ASSERT_EQ(std::ceil(a.height()), std::ceil(b.height()));
  const Difference d =
      compare(read_png(encoded(a, Format::png)), rasterise_svg(encoded(b, Format::svg)));
  EXPECT_GT(d.far_fraction, 0.004);
}

// ---------------------------------------------------------------------------
// The table as players know it

TEST(Table, SnookerHasSixPocketsTheBaulkLineTheDAndSixSpots) {
  const Picture p = table_picture(simulated(shipped("one_rail_position"), kOneRail));
  EXPECT_EQ(count(p, "pocket"), 6u);
  // The snooker preset's jawed pockets: two facings and two rounded points each, no
  // capture circle.
  EXPECT_EQ(count(p, "pocket-capture"), 0u);
  EXPECT_EQ(count(p, "pocket-facing"), 12u);
  EXPECT_EQ(count(p, "pocket-point"), 12u);
  EXPECT_EQ(count(p, "baulk-line"), 1u);
  EXPECT_EQ(count(p, "d"), 1u);
  EXPECT_EQ(count(p, "spot"), 6u);
  EXPECT_EQ(count(p, "diamond"), 0u);
  EXPECT_EQ(count(p, "cloth"), 1u);
  EXPECT_EQ(count(p, "cushion"), 1u);
  // The baulk line stands 737 mm from the bottom cushion: 0.2065 of the table's length.
  const Box cloth = p.marks_of("cloth").front().box;
  const Box baulk = p.marks_of("baulk-line").front().box;
  const double fraction = (0.5 * (baulk.left + baulk.right) - cloth.left) / (cloth.width() - 1.0);
  EXPECT_NEAR(fraction, 0.737 / 3.569, 0.002);
}

TEST(Table, TwoToOneTablesHaveDiamondsAndNoSnookerMarkings) {
  const Picture pool = table_picture(simulated(shipped("pool_table"), {1.497, 37.98, 0.0, 0.0}));
  EXPECT_EQ(count(pool, "diamond"), 2u * 6u + 2u * 3u) << "three between pockets on every rail";
  EXPECT_EQ(count(pool, "baulk-line"), 0u);
  EXPECT_EQ(count(pool, "spot"), 0u);
  EXPECT_EQ(count(pool, "pocket"), 6u);
  const Picture carom =
      table_picture(simulated(shipped("carom_three_cushion"), {1.75, 119.1, 0.0, 0.0}));
  EXPECT_EQ(count(carom, "diamond"), 2u * 7u + 2u * 3u) << "no pockets to leave room for";
  EXPECT_EQ(count(carom, "pocket"), 0u);
  EXPECT_EQ(markings_for(phys::Scene{}), TableMarkings::snooker);
  phys::Scene square;
  square.length = square.width = 2.0;
  EXPECT_EQ(markings_for(square), TableMarkings::none);
}

// A pocket is a hole behind the cushion nose; a ball stands on the cloth.
TEST(Table, PocketHolesSitBehindTheNosesBallsOnTheCloth) {
  const Picture p =
      table_picture(simulated(shipped("blocked_direct_route"), {1.695, 30.06, 0.0, 0.0}));
  const Box cloth = p.marks_of("cloth").front().box;
  const auto centre_inside = [&](const Box& b) {
    const double x = 0.5 * (b.left + b.right), y = 0.5 * (b.top + b.bottom);
    return x > cloth.left && x < cloth.right && y > cloth.top && y < cloth.bottom;
  };
  ASSERT_EQ(count(p, "pocket"), 6u);
  for (const Mark& m : p.marks_of("pocket")) EXPECT_FALSE(centre_inside(m.box));
  ASSERT_EQ(count(p, "ball"), 4u) << "the cue ball and three obstacles";
  for (const Mark& m : p.marks_of("ball")) EXPECT_TRUE(centre_inside(m.box));
}

TEST(Table, SimulatedShotShowsItsMotionsContactsAndRest) {
  phys::ShotResult r;
  const Picture p = table_picture(simulated(shipped("one_rail_position"), kOneRail, &r));
  ASSERT_EQ(r.status, phys::ShotStatus::rest);
  EXPECT_EQ(count(p, "cushion-contact"), static_cast<size_t>(r.cushion_hits));
  EXPECT_EQ(count(p, "cushion-number"), static_cast<size_t>(r.cushion_hits));
  EXPECT_EQ(count(p, "rest"), 1u);
  EXPECT_GE(count(p, "path-sliding"), 1u);
  EXPECT_GE(count(p, "path-rolling"), 1u);
  EXPECT_EQ(count(p, "target-zone"), 1u);
  EXPECT_TRUE(has_text(p, "label", "cue ball"));
  EXPECT_TRUE(has_text(p, "label", "target"));
  EXPECT_TRUE(has_text(p, "legend-text", "sliding"));
  EXPECT_TRUE(has_text(p, "legend-text", "rolling"));
  const std::string title = texts(p, "title").front();
  EXPECT_NE(title.find("kT = 0.8"), std::string::npos) << title << ": k_{T} set as a subscript";
  EXPECT_EQ(title.find("_{"), std::string::npos) << title;
  // The rest ghost stands where the simulation stopped.
  const Box cloth = p.marks_of("cloth").front().box;
  const double scale = (cloth.width() - 1.0) / 3.569;
  const Box ghost = p.marks_of("rest").front().box;
  EXPECT_NEAR(0.5 * (ghost.left + ghost.right), cloth.left + 0.5 + r.final_position.x * scale, 0.5);
  EXPECT_NEAR(0.5 * (ghost.top + ghost.bottom), cloth.bottom - 0.5 - r.final_position.y * scale,
              0.5);
}

TEST(Table, OpenCaromTableHasNoPocketsAndMarksEveryContact) {
  phys::ShotResult r;
  const Picture p =
      table_picture(simulated(shipped("carom_three_cushion"), {1.75, 119.1, 0.0, 0.0}, &r));
  EXPECT_EQ(count(p, "pocket"), 0u);
  EXPECT_EQ(r.cushion_hits, 3);
  EXPECT_EQ(count(p, "cushion-contact"), 3u);
  EXPECT_FALSE(has_text(p, "legend-text", "pocket (a ball whose centre enters r = 45 mm drops)"));
}

TEST(Table, ObstaclesAreRedBallsWithNames) {
  const TableScene t = problem_table(shipped("blocked_direct_route"));
  ASSERT_EQ(t.balls.size(), 4u);
  EXPECT_EQ(t.balls[0].name, "cue ball");
  EXPECT_EQ(t.balls[3].name, "obstacle 3");
  EXPECT_EQ(t.balls[1].colour.to_hex(), ball_colour("red")->to_hex());
  const Picture p = table_picture(t);
  for (const char* name : {"cue ball", "obstacle 1", "obstacle 2", "obstacle 3"})
    EXPECT_TRUE(has_text(p, "label", name)) << name;
  EXPECT_FALSE(ball_colour("purple").has_value());
  EXPECT_EQ(ball_colour("8")->to_hex(), ball_colour("black")->to_hex());
}

TEST(Table, PoolBallsCarryTheirNumbersAndStripesTheirBand) {
  prob::Problem problem = shipped("pots/pool_two_ball_position");
  problem.scene.balls = {{"9", {2.05, 0.35}}, {"2", {0.9, 0.85}}, {"ball12", {0.6, 0.35}},
                         {"8", {1.2, 0.5}}, {"red3", {1.8, 0.9}}};
  const TableScene t = problem_table(problem);
  ASSERT_EQ(t.balls.size(), 6u);
  // The 9 is a stripe in the 1's yellow, the 12 in the 4's purple; the 2 and the 8 are
  // solids; a snooker red keeps its colour by name, without a number.
  EXPECT_TRUE(t.balls[1].striped);
  EXPECT_EQ(t.balls[1].number, 9);
  EXPECT_EQ(t.balls[1].colour.to_hex(), ball_colour("1")->to_hex());
  EXPECT_FALSE(t.balls[2].striped);
  EXPECT_EQ(t.balls[2].number, 2);
  EXPECT_TRUE(t.balls[3].striped);
  EXPECT_EQ(t.balls[3].number, 12);
  EXPECT_EQ(t.balls[3].colour.to_hex(), ball_colour("4")->to_hex());
  EXPECT_EQ(t.balls[4].number, 8);
  EXPECT_EQ(t.balls[5].number, 0);
  EXPECT_EQ(t.balls[5].colour.to_hex(), ball_colour("red")->to_hex());
  EXPECT_EQ(t.balls[0].number, 0);
  const Picture p = table_picture(t);
  // One band for each stripe, one number disc and number for each pool ball, every ball
  // still one "ball" mark.
  EXPECT_EQ(count(p, "ball-stripe"), 2u);
  EXPECT_EQ(count(p, "ball-number-disc"), 4u);
  std::vector<std::string> numbers = texts(p, "ball-number");
  std::sort(numbers.begin(), numbers.end());
  EXPECT_EQ(numbers, (std::vector<std::string>{"12", "2", "8", "9"}));
  EXPECT_EQ(count(p, "ball"), 6u);
}

TEST(Table, ObjectBallsStandInTheirColoursAndMoveAlongTheirPaths) {
  const prob::Problem problem = shipped("pots/plant_two_balls");
  const TableScene t = problem_table(problem);
  ASSERT_EQ(t.balls.size(), 3u);
  EXPECT_EQ(t.balls[1].name, "red");
  EXPECT_EQ(t.balls[2].name, "blue");
  EXPECT_EQ(t.balls[2].colour.to_hex(), ball_colour("blue")->to_hex());
  EXPECT_EQ(t.balls[2].start.x, problem.scene.balls[1].position.x);
  EXPECT_EQ(ball_colour("red_12")->to_hex(), ball_colour("red")->to_hex());
  EXPECT_EQ(ball_colour("yellow3")->to_hex(), ball_colour("yellow")->to_hex());
  EXPECT_FALSE(ball_colour("16").has_value());
  EXPECT_FALSE(ball_colour("lilac2").has_value());
  // The plant: red sends blue into the top-right pocket; each ball's path is drawn and
  // the blue is marked pocketed.
  // (The cue aimed off by the squirt of its side, so that the cue ball leaves at 23.88 deg.)
  const double squirt = phys::squirt_angle_deg(problem.scene.cue, problem.scene.ball_and_cushion.mass,
                                               problem.scene.radius(), 0.2);
  const phys::ShotResult r =
      phys::simulate(problem.scene, problem.cue_ball, {2.86, 23.88 - squirt, -1.2, 0.2});
  ASSERT_TRUE(r.balls.at(2).pocketed);
  TableScene moved = t;
  moved.balls[0].paths.push_back({r.path, r.events, false});
  for (size_t k = 1; k < 3; ++k)
    moved.balls[k].paths.push_back(
        {r.balls[k].path, r.balls[k].events, false, 0, moved.balls[k].colour});
  const Picture still = table_picture(t), p = table_picture(moved);
  for (const char* name : {"cue ball", "red", "blue"}) EXPECT_TRUE(has_text(p, "label", name)) << name;
  EXPECT_EQ(count(still, "end-cross"), 0u);
  EXPECT_EQ(count(p, "end-cross"), 1u);
  TableScene cue_only = t;
  cue_only.balls[0].paths.push_back({r.path, r.events, false});
  const Picture q = table_picture(cue_only);
  // The object balls' paths in their own colours, the cue ball's as before.
  EXPECT_EQ(count(p, "path-sliding") + count(p, "path-rolling"),
            count(q, "path-sliding") + count(q, "path-rolling"));
  EXPECT_GE(count(p, "path-ball-sliding") + count(p, "path-ball-rolling"), 2u);
  EXPECT_EQ(count(q, "path-ball-sliding") + count(q, "path-ball-rolling"), 0u);
  EXPECT_TRUE(has_text(p, "legend-text", "an object ball's path, in its colour (dashed while it slides)"));
  EXPECT_FALSE(has_text(q, "legend-text", "an object ball's path, in its colour (dashed while it slides)"));
  // Each contact is ringed on both its balls: cue-red, then red-blue (and any later).
  size_t contacts = 0;
  for (const phys::BallOutcome& b : r.balls)
    for (const phys::ShotEvent& e : b.events) contacts += e.type == phys::EventType::ball_contact;
  EXPECT_GE(contacts, 4u);
  EXPECT_EQ(count(p, "ball-contact"), contacts);
  EXPECT_TRUE(has_text(p, "legend-text", "ball at a contact (cushion contacts numbered on the cushion)"));
}

// Two strokes of a route, the second back along the first's line.
TableScene there_and_back(phys::ShotResult* first, phys::ShotResult* second) {
  const prob::Problem p = shipped("routes/two_stroke_speed_limit");
  TableScene t = problem_table(p);
  *first = shot_on(p, p.cue_ball, {0.5, 0.0, 1.0, 0.0});
  *second = shot_on(p, first->final_position, {0.45, 180.0, 1.0, 0.0});
  t.balls.front().paths.push_back({first->path, first->events, false, 1});
  t.balls.front().paths.push_back({second->path, second->events, false, 2});
  return t;
}

TEST(Table, RouteStrokesAreNumberedOnTheTable) {
  phys::ShotResult a, b;
  const Picture p = table_picture(there_and_back(&a, &b));
  EXPECT_EQ(texts(p, "stroke-number"), (std::vector<std::string>{"1", "2"}));
  EXPECT_EQ(count(p, "stroke-badge"), 2u);
  EXPECT_EQ(count(p, "rest"), 2u) << "a ghost where each stroke stops";
}

// The second stroke runs back over the first: it is drawn beside it, not on it.
TEST(Table, RetracedStrokeIsDrawnBesideTheFirst) {
  phys::ShotResult a, b;
  const Picture p = table_picture(there_and_back(&a, &b));
  const std::vector<Mark> rolling = p.marks_of("path-rolling");
  ASSERT_EQ(rolling.size(), 2u);
  const double y1 = 0.5 * (rolling[0].box.top + rolling[0].box.bottom);
  const double y2 = 0.5 * (rolling[1].box.top + rolling[1].box.bottom);
  EXPECT_GE(std::abs(y2 - y1), 4.0) << "lines 2 px wide stay apart";
  EXPECT_LE(std::abs(y2 - y1), 25.0) << "but near enough to read as the same line";
}

// A crowd of named balls with a route through it: no two labels overlap.
TEST(Table, LabelsNeverOverlapInACrowd) {
  const prob::Problem problem = shipped("one_rail_position");
  TableScene t = problem_table(problem);
  const char* names[] = {"red",   "yellow", "green", "brown", "blue", "pink",
                         "black", "1",      "2",     "3",     "4",    "5"};
  for (int i = 0; i < 12; ++i) {
    const phys::Vec2 at{1.7 + 0.06 * (i % 4), 0.8 + 0.06 * (i / 4)};
    t.balls.push_back({names[i], *ball_colour(names[i]), at, {}});
  }
  const phys::ShotResult r = shot_on(problem, problem.cue_ball, {1.8, -20.0, 0.5, 0.3});
  t.balls.front().paths.push_back({r.path, r.events, false, 1});
  const Picture p = table_picture(t);
  std::vector<Mark> labels;
  for (const char* role : {"label", "stroke-number", "cushion-number"})
    for (const Mark& m : p.marks_of(role)) labels.push_back(m);
  ASSERT_EQ(p.marks_of("label").size(), 14u);  // 13 balls and the target
  for (size_t i = 0; i < labels.size(); ++i)
    for (size_t k = i + 1; k < labels.size(); ++k)
      EXPECT_FALSE(labels[i].box.overlaps(labels[k].box))
          << labels[i].text << " and " << labels[k].text;
}

void expect_text_on_canvas(const Picture& p, const std::string& what) {
  size_t n = 0;
  for (const Mark& m : p.marks()) {
    if (!m.is_text) continue;
    ++n;
    EXPECT_TRUE(m.box.inside(canvas_of(p)))
        << what << ": '" << m.text << "' at " << m.box.left << "," << m.box.top << " - "
        << m.box.right << "," << m.box.bottom << " on " << p.width() << " x " << p.height();
  }
  EXPECT_GT(n, 5u) << what;
}

TEST(Table, TextNeverLeavesTheCanvas) {
  for (const char* stem : {"one_rail_position", "pool_table", "carom_three_cushion", "near_pocket",
                           "blocked_direct_route", "routes/two_stroke_blocked"}) {
    TableScene t = simulated(shipped(stem), {1.5, 20.0, 0.5, 0.5});
    t.title = std::string(stem) +
              ": a title long enough to wrap on the narrowest table the layer draws, "
              "with k_{T} and k_{S} in it, 1.14 m/s and 45.5\u00b0";
    expect_text_on_canvas(table_picture(t), stem);
  }
}

// ---------------------------------------------------------------------------
// Extreme scenes

TableScene scaled_scene(double length, double width, double radius) {
  TableScene t;
  t.scene.length = length;
  t.scene.width = width;
  t.scene.ball_and_cushion.radius = radius;
  t.scene.pockets = {{{0.0, 0.0}, 2.0 * radius}, {{length, width}, 2.0 * radius}};
  t.balls.push_back({"cue ball", *ball_colour("cue ball"), {0.25 * length, 0.5 * width}, {}});
  t.target = TargetZone{{0.75 * length, 0.5 * width}, radius};
  t.title = "A table of " + std::to_string(length) + " m";
  return t;
}

TEST(Table, HugeAndTinyTablesGiveBoundedReadablePictures) {
  for (const auto& [length, width, radius] :
       {std::tuple{1e9, 5e8, 0.02625}, std::tuple{0.06, 0.03, 0.004}, std::tuple{1e9, 0.5e9, 1e7},
        std::tuple{3.569, 1.778, 0.02625}}) {
    const std::string what = std::to_string(length) + " m";
    const Picture p = table_picture(scaled_scene(length, width, radius));
    EXPECT_LE(p.width(), kMaxCanvasSide) << what;
    EXPECT_LE(p.height(), kMaxCanvasSide) << what;
    EXPECT_GE(p.width(), 400.0) << what;
    const Box cloth = p.marks_of("cloth").front().box;
    EXPECT_GE(cloth.width(), 400.0) << what << ": the table is drawn large enough to read";
    // Ticks chosen from the scene: a handful along each side, their labels apart.
    std::vector<Mark> ticks = p.marks_of("tick-label");
    EXPECT_GE(ticks.size(), 3u + 2u) << what;
    EXPECT_LE(ticks.size(), 12u + 8u) << what;
    for (size_t i = 0; i < ticks.size(); ++i)
      for (size_t k = i + 1; k < ticks.size(); ++k)
        EXPECT_FALSE(ticks[i].box.overlaps(ticks[k].box))
            << what << ": " << ticks[i].text << ", " << ticks[k].text;
    expect_text_on_canvas(p, what);
    // Balls stay visible however small they are.
    for (const Mark& m : p.marks_of("ball")) EXPECT_GE(m.box.width(), 5.0) << what;
    const std::string svg = encoded(p, Format::svg);
    EXPECT_LT(svg.size(), 2'000'000u) << what;
    const Image png = read_png(encoded(p, Format::png));
    EXPECT_EQ(png.width, static_cast<int>(std::ceil(p.width()))) << what;
  }
}

TEST(Table, TickLabelsWritePowersOfTenForHugeTables) {
  const Picture p = table_picture(scaled_scene(1e9, 5e8, 0.02625));
  const std::vector<std::string> labels = texts(p, "tick-label");
  ASSERT_FALSE(labels.empty());
  EXPECT_EQ(labels.front(), "0");
  EXPECT_TRUE(std::any_of(labels.begin(), labels.end(), [](const std::string& s) {
    return s.find("\u00d710") != std::string::npos;
  })) << labels[1];
}

// ---------------------------------------------------------------------------
// Spin maps

struct MapCase {
  prob::Problem problem;
  plan::SpinMap map;
};

MapCase one_rail_map(int grid, double speed = 1.002, double aim = -60.36) {
  MapCase c{shipped("one_rail_position"), {}};
  plan::SpinMapOptions o;
  o.grid = grid;
  o.simulation.impact_method = phys::ImpactMethod::exact;
  c.map = plan::spin_map(c.problem, speed, aim, o);
  return c;
}

SpinMapScene scene_of(const MapCase& c, bool with_paths) {
  SpinMapScene s;
  s.title = "What spin lands here? one-rail position";
  s.caption = {"Each cell is one tip offset struck at this speed and aim."};
  s.problem = c.problem;
  s.map = c.map;
  if (with_paths)
    for (size_t i : sparse_subset(c.map, 5)) {
      const plan::SpinMapPoint& p = c.map.points[i];
      const phys::ShotResult r = shot_on(c.problem, c.problem.cue_ball,
                                         {c.map.speed, c.map.aim_deg, p.topspin_k, p.sidespin_k});
      s.sample_paths.push_back({r.path, r.events, true});
    }
  return s;
}

TEST(SpinMap, OneCellAndOneRestDotPerSpin) {
  const MapCase c = one_rail_map(17);
  ASSERT_FALSE(c.map.points.empty());
  SpinMapScene s = scene_of(c, true);
  s.marked_shot = kOneRail;
  const Picture p = spin_map_picture(s);
  EXPECT_EQ(count(p, "cell"), c.map.points.size());
  EXPECT_EQ(count(p, "dot"), c.map.points.size());
  EXPECT_EQ(count(p, "miscue-limit"), 1u);
  EXPECT_EQ(count(p, "planned-spin"), 1u);
  EXPECT_EQ(count(p, "colour-bar"), 1u);
  EXPECT_EQ(count(p, "pocket"), 6u) << "the table panel";
  EXPECT_LE(p.width(), kMaxCanvasSide);
  EXPECT_LE(p.height(), kMaxCanvasSide);
  EXPECT_EQ(count(p, "landing-outline"), c.map.landing > 0 ? 1u : 0u);
  expect_text_on_canvas(p, "spin map");
}

// Cells fill the disc to the spin limit and nothing shows outside it: pixels just inside
// the limit circle are coloured, pixels just outside are the white page.
TEST(SpinMap, CellsFillTheDiscAndStopAtItsEdge) {
  const MapCase c = one_rail_map(21);
  const Picture p = spin_map_picture(scene_of(c, false));
  const Box disc = p.marks_of("miscue-limit").front().box;
  const double cx = 0.5 * (disc.left + disc.right), cy = 0.5 * (disc.top + disc.bottom);
  const double r = 0.5 * (disc.width() - 1.5);
  for (const std::string& bytes : {encoded(p, Format::png), std::string()}) {
    const Image im = bytes.empty() ? rasterise_svg(encoded(p, Format::svg)) : read_png(bytes);
    ASSERT_FALSE(im.rgb.empty());
    for (int k = 0; k < 36; ++k) {
      const double a = k * 10.0 * M_PI / 180.0 + 0.05;
      const int xi = static_cast<int>(cx + (r - 4.0) * std::cos(a)),
                yi = static_cast<int>(cy + (r - 4.0) * std::sin(a));
      const int xo = static_cast<int>(cx + (r + 4.0) * std::cos(a)),
                yo = static_cast<int>(cy + (r + 4.0) * std::sin(a));
      EXPECT_LT(im.luminance(xi, yi), 240.0) << "inside the limit at " << k * 10 << " deg";
      EXPECT_GT(im.luminance(xo, yo), 250.0) << "outside the limit at " << k * 10 << " deg";
    }
  }
}

// Along rows and columns of cells through the disc, no pixel between two cells is
// lighter than both cells' centres: the white page does not show through between
// neighbours, in Cairo's PNG nor in librsvg's rendering of the SVG.
TEST(SpinMap, NoSeamsBetweenCells) {
  const MapCase c = one_rail_map(41);
  const Picture p = spin_map_picture(scene_of(c, false));
  const Box disc = p.marks_of("miscue-limit").front().box;
  const double cx = 0.5 * (disc.left + disc.right), cy = 0.5 * (disc.top + disc.bottom);
  const double cell =
      (disc.width() - 1.5) / (c.map.grid - 1);  // the limit is (grid - 1) / 2 cells out
  for (int pass = 0; pass < 2; ++pass) {
    const Image im =
        pass == 0 ? read_png(encoded(p, Format::png)) : rasterise_svg(encoded(p, Format::svg));
    ASSERT_FALSE(im.rgb.empty());
    int checked = 0;
    // Rows and columns of cell centres away from the centre cross, within the disc.
    for (int j : {-14, -9, -5, 6, 11, 15}) {
      for (int k = -12; k < 12; ++k) {
        for (bool across : {true, false}) {
          // From the centre of cell k to that of cell k + 1 along row (or column) j.
          const double a = k * cell, b = (k + 1) * cell, line = j * cell;
          const auto lum = [&](double along) {
            return across ? im.luminance(static_cast<int>(std::lround(cx + along)),
                                         static_cast<int>(std::lround(cy + line)))
                          : im.luminance(static_cast<int>(std::lround(cx + line)),
                                         static_cast<int>(std::lround(cy + along)));
          };
          const double brighter = std::max(lum(a), lum(b));
          for (double t = a + 1.0; t < b - 1.0; t += 0.5) {
            EXPECT_LE(lum(t), brighter + 3.0)
                << (pass == 0 ? "png" : "svg") << (across ? " row " : " column ") << j
                << " between cells " << k << " and " << k + 1;
            ++checked;
          }
        }
      }
    }
    EXPECT_GT(checked, 2000);
  }
}

DrawnPath path_with(double side_rad_s, std::vector<std::pair<phys::EventType, double>> events) {
  DrawnPath p;
  phys::ShotEvent strike;
  strike.type = phys::EventType::strike;
  strike.spin = {0.0, 0.0, side_rad_s};
  p.events.push_back(strike);
  for (const auto& [type, time] : events) {
    phys::ShotEvent e;
    e.type = type;
    e.time = time;
    p.events.push_back(e);
  }
  return p;
}

TEST(SpinMap, SidespinSpentBeforeTheFirstCushionIsSaid) {
  using phys::EventType;
  const DrawnPath spent = path_with(20.0, {{EventType::spin_stop, 0.4}, {EventType::cushion, 1.1}});
  const DrawnPath kept = path_with(20.0, {{EventType::cushion, 0.3}, {EventType::spin_stop, 0.9}});
  const DrawnPath none = path_with(0.0, {{EventType::cushion, 0.3}});
  EXPECT_NE(sidespin_note({spent, none}), "");
  EXPECT_NE(sidespin_note({spent}).find("before the first cushion"), std::string::npos);
  EXPECT_EQ(sidespin_note({spent, kept}), "") << "one stroke keeps its side to the cushion";
  EXPECT_EQ(sidespin_note({none}), "") << "no sidespin at all";
  EXPECT_EQ(sidespin_note({}), "");

  // On the picture, from simulated strokes. With the cloth's spinning friction at 0.044
  // (sidespin falls at 41 rad/s^2) the most side the disc allows, 48 rad/s at 1 m/s, is
  // gone in 1.2 s, before the cushion 1.5 s away; at 0.0117 (10.9 rad/s^2) it lasts 4 s.
  for (const double mu_spin : {0.044, 0.0117}) {
    MapCase c{shipped("one_rail_position"), {}};
    c.problem.scene.cloth.mu_spin = mu_spin;
    plan::SpinMapOptions o;
    o.grid = 9;
    o.simulation.impact_method = phys::ImpactMethod::exact;
    c.map = plan::spin_map(c.problem, 1.002, -60.36, o);
    const SpinMapScene s = scene_of(c, true);
    const Picture p = spin_map_picture(s);
    if (mu_spin > 0.04) {
      EXPECT_EQ(count(p, "note"), 1u);
      EXPECT_NE(texts(p, "note").front().find("left and right change nothing"), std::string::npos);
    } else {
      EXPECT_EQ(count(p, "note"), 0u);
    }
  }
}

// ---------------------------------------------------------------------------
// Plots

PlotFigure broken_line_figure() {
  PlotSeries line;
  line.label = "k_{T} < 1 & more";
  line.x = {0.0, 1.0, NAN, 2.0, 3.0};
  line.y = {0.0, 1.0, 1.5, 2.0, 1.0};
  line.colour = "#0072B2";
  PlotPanel panel;
  panel.title = "Panel";
  panel.x_axis = {"x (m)", 0.0, 3.0, 1.0};
  panel.y_axis = {"y (m/s)", 0.0, 2.0, 0.5};
  panel.series = {line};
  return {"Title", "", {panel, panel}};
}

TEST(Plot, LabelsKeepTheirWordsWithSubscriptsSet) {
  const Picture p = plot_picture(broken_line_figure());
  EXPECT_TRUE(has_text(p, "legend-text", "kT < 1 & more"))
      << "escaped, the subscript's markup gone";
  EXPECT_EQ(count(p, "series"), 2u);
  EXPECT_EQ(count(p, "frame"), 2u);
  expect_text_on_canvas(p, "plot");
}

// The point between x = 1 and x = 2 is not finite: the line stops there. Pixels on the
// segment from (0, 0) to (1, 1) carry the series colour; those where (1, 1)-(2, 2) would
// run do not.
TEST(Plot, NonFiniteValuesBreakTheLine) {
  const Picture p = plot_picture(broken_line_figure());
  const Box frame = p.marks_of("frame").front().box;
  const double left = frame.left + 0.5, bottom = frame.bottom - 0.5;
  const double sx = (frame.width() - 1.0) / 3.0, sy = (frame.height() - 1.0) / 2.0;
  const Image im = read_png(encoded(p, Format::png));
  const auto blue_at = [&](double x, double y) {
    const unsigned char* px = im.at(static_cast<int>(std::lround(left + x * sx)),
                                    static_cast<int>(std::lround(bottom - y * sy)));
    return px[2] > 140 && px[0] < 60;
  };
  EXPECT_TRUE(blue_at(0.5, 0.5));
  EXPECT_TRUE(blue_at(2.5, 1.5));
  EXPECT_FALSE(blue_at(1.5, 1.5)) << "no line across the gap";
}

}  // namespace
}  // namespace cueplan::draw

namespace cueplan::draw {
namespace {

// A field over the cloth (cueplan zone): shaded cells, the zone's edge where values
// cross the level, legend entries for both; outline only when not shaded; named
// obstacles keep their names and colours.
TEST(Table, FieldIsShadedAndItsZoneOutlined) {
  const prob::LoadResult r = prob::parse_problem(
      "obstacles: {pink: [2.7, 0.9], blue: [1.78, 0.9]}\ncue_ball: [1, 1]\ntarget: [2, 1.3]\n",
      "<field>");
  ASSERT_TRUE(r.ok()) << r.error;
  TableScene t = problem_table(*r.problem);
  ASSERT_EQ(t.balls.size(), 3u);
  EXPECT_EQ(t.balls[1].name, "pink");
  EXPECT_EQ(t.balls[1].colour.to_hex(), ball_colour("pink")->to_hex());
  TableField f;
  f.cell = 0.1;
  f.columns = 36;
  f.rows = 18;
  for (int j = 0; j < f.rows; ++j)
    for (int i = 0; i < f.columns; ++i)
      f.values.push_back(std::max(0.0, 1.0 - std::hypot(i - 10.0, j - 9.0) / 8.0));
  f.outline_level = 0.8;
  f.shade_legend = "P(next pot)";
  f.outline_legend = "zone";
  t.field = f;
  const Picture shaded = table_picture(t);
  EXPECT_GT(count(shaded, "field"), 10u);
  EXPECT_EQ(count(shaded, "zone-edge"), 2u);  // dark under white
  const Box edge = shaded.marks_of("zone-edge").front().box;
  const Box cloth = shaded.marks_of("cloth").front().box;
  EXPECT_TRUE(edge.inside(cloth));
  EXPECT_LT(edge.width(), 0.3 * cloth.width());  // the zone, not the table
  EXPECT_TRUE(has_text(shaded, "legend-text", "P(next pot)"));
  EXPECT_TRUE(has_text(shaded, "legend-text", "zone"));
  t.field->shade = false;
  const Picture outlined = table_picture(t);
  EXPECT_EQ(count(outlined, "field"), 0u);
  EXPECT_EQ(count(outlined, "zone-edge"), 2u);
}

}  // namespace
}  // namespace cueplan::draw
