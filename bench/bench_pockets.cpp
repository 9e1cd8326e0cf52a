// Effective target size of jawed pool pockets by simulation, against Alciatore's
// technical proofs TP 3.6 (corner) and TP 3.5 (side): the width of the band of parallel
// lines of approach along which a slowly rolling ball drops, scanned in 0.1 mm steps of
// lateral offset for each approach angle. Prints a Markdown table and writes the plot
// (docs/pockets.png by default; the first argument names another file, .svg or .png).
//
//   build/bench/bench_pockets docs/pockets.png
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/draw/plot.hpp"
#include "cueplan/physics/shot.hpp"

namespace {

using namespace cueplan::physics;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kInch = 0.0254;

// TP 3.6's corner pocket and a WPA side pocket (TP 3.5), with 1/16 in point roundings;
// an 8-ft table (88 x 44 in), pool balls (R = 1.125 in, 6 oz).
Scene pool_scene() {
  Scene s;
  s.length = 88.0 * kInch;
  s.width = 44.0 * kInch;
  s.ball_and_cushion = params_for_radius(1.125 * kInch);
  s.ball_and_cushion.mass = 0.17;
  const PocketShape corner{4.5875 * kInch, 7.0, 1.125 * kInch, 2.75 * kInch, 0.0625 * kInch};
  const PocketShape side{5.0 * kInch, 14.0, 0.375 * kInch, 2.75 * kInch, 0.0625 * kInch};
  s.pockets = jawed_pockets(s.length, s.width, corner, side);
  return s;
}

// Whether a ball rolled at `speed` (m/s) on the line at `angle` (rad) from the pocket's
// centre line, `offset` (m) to its left, 0.3 m before the mouth, drops in `pocket`.
bool drops(const CompiledScene& scene, int pocket, double angle, double offset, double speed) {
  const PocketJaws& j = *scene.scene().pockets[static_cast<size_t>(pocket)].jaws;
  const Vec2 d{j.inward.x * std::cos(angle) - j.inward.y * std::sin(angle),
               j.inward.x * std::sin(angle) + j.inward.y * std::cos(angle)};
  const Vec2 start{j.mouth_centre.x - 0.3 * d.x - offset * d.y,
                   j.mouth_centre.y - 0.3 * d.y + offset * d.x};
  if (scene.scene().check_position(start, {"cue_ball"})) return false;
  SimulationOptions o;
  o.record_path = false;
  const ShotResult r = simulate(scene, start, {speed, std::atan2(d.y, d.x) / kDeg, 1.0, 0.0}, o);
  return r.status == ShotStatus::pocketed && r.balls[0].pocket == pocket;
}

double target_size_in(const CompiledScene& scene, int pocket, double angle_deg, double speed) {
  constexpr double step = 0.1e-3;
  int n = 0;
  for (double b = -0.12; b <= 0.12; b += step) n += drops(scene, pocket, angle_deg * kDeg, b, speed);
  return n * step / kInch;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "docs/pockets.png";
  const CompiledScene scene(pool_scene());
  namespace draw = cueplan::draw;
  draw::PlotPanel corner{"corner pocket (TP 3.6)", {"approach angle from the bisector (deg)", 0.0, 45.0, 5.0},
                         {"effective target size (in)", 0.0, 4.5, std::nullopt}, {}, {}, ""};
  draw::PlotPanel side{"side pocket (TP 3.5 geometry)", {"approach angle from straight in (deg)", 0.0, 70.0, 10.0},
                       {"effective target size (in)", 0.0, 4.5, std::nullopt}, {}, {}, ""};
  std::printf("| pocket | angle (deg) | 0.5 m/s (in) | 1.5 m/s (in) |\n|---|---|---|---|\n");
  for (const double speed : {0.5, 1.5}) {
    draw::PlotSeries c{"cueplan, " + std::string(speed < 1.0 ? "0.5" : "1.5") + " m/s", {}, {}, speed > 1.0, ""};
    for (double a = 0.0; a <= 45.0; a += 2.5) {
      c.x.push_back(a);
      c.y.push_back(target_size_in(scene, 0, a, speed));
    }
    corner.series.push_back(c);
    draw::PlotSeries m{c.label, {}, {}, speed > 1.0, ""};
    for (double a = 0.0; a <= 70.0; a += 5.0) {
      m.x.push_back(a);
      m.y.push_back(target_size_in(scene, 1, a, speed));
    }
    side.series.push_back(m);
  }
  for (size_t i = 0; i < corner.series[0].x.size(); ++i)
    std::printf("| corner | %.1f | %.3f | %.3f |\n", corner.series[0].x[i], corner.series[0].y[i],
                corner.series[1].y[i]);
  for (size_t i = 0; i < side.series[0].x.size(); ++i)
    std::printf("| side | %.1f | %.3f | %.3f |\n", side.series[0].x[i], side.series[0].y[i],
                side.series[1].y[i]);
  // TP 3.6's published points: about 1.5 in straight in, 1.3 in at 30 deg, 3-3.5 in
  // near 45 deg.
  draw::PlotSeries published{"Alciatore TP 3.6 (slow)", {0.0, 30.0, 44.0}, {1.5, 1.3, 3.25}, true, "#000000"};
  corner.series.push_back(published);
  draw::PlotFigure figure{"Effective target size of pool pockets, slowly rolling ball",
                          "Width of the band of parallel approach lines along which the ball drops, by "
                          "simulation (0.1 mm scan). Corner: mouth 4.5875 in, wall 7 deg, shelf 1.125 in, "
                          "hole radius 2.75 in. Side: mouth 5 in, wall 14 deg, shelf 0.375 in.",
                          {corner, side}};
  const draw::Picture picture = draw::plot_picture(figure);
  const draw::Encoded e = draw::encode(
      picture, out.size() > 4 && out.substr(out.size() - 4) == ".png" ? draw::Format::png : draw::Format::svg);
  if (!e.ok()) {
    std::fprintf(stderr, "%s\n", e.error.c_str());
    return 1;
  }
  std::ofstream(out, std::ios::binary) << e.bytes;
  return 0;
}
