#include "figures_command.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <optional>
#include <ostream>
#include <vector>

#include "csv.hpp"
#include "cueplan/draw/plot.hpp"
#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/api/exit_codes.hpp"
#include "cueplan/api/output_file.hpp"

namespace cueplan::cli {
using namespace cueplan::batch;  // batch streaming (batch/)
namespace {

namespace phys = cueplan::physics;
using draw::palette_colour;
using draw::PlotAxis;
using draw::PlotFigure;
using draw::PlotMarker;
using draw::PlotPanel;
using draw::PlotSeries;

constexpr const char* kCommandName = "cueplan figures";
constexpr const char* kAlphaLabel = "incidence angle \u03b1 (deg)";
constexpr const char* kReferenceGrey = "#9a9a9a";

// One curve of a rebound-versus-incidence figure: the ball's speed and spins.
struct IncidenceCurve {
  std::string label;   // legend entry
  double speed = 1.0;  // m/s, V0
  double topspin_k = 1.0;
  double sidespin_k = 0.0;
};

// Figures 8 to 10: rebound speed and angle over alpha in (0, 90] for several balls.
struct IncidenceFigure {
  std::string file_stem;
  std::string title;
  std::string caption;
  std::string legend_title;
  std::vector<IncidenceCurve> curves;
  std::string angle_note;  // added to the angle panel's title, e.g. "curves coincide"
};

// What one figure writes: the picture and the numbers behind it.
struct RenderedFigure {
  std::string file_stem;
  draw::Picture picture;
  std::string csv;
  int unusable_points = 0;  // impacts without a usable result (left out of the plot)
};

std::string parameters_caption(const phys::CushionParams& p) {
  return "e_{e} = " + format_number(p.restitution) +
         ", \u03bc_{w} = " + format_number(p.mu_cushion) +
         ", \u03bc_{s} = " + format_number(p.mu_table) +
         ", R = " + format_number(p.radius * 1000.0) + " mm, h = 7R/5; exact method";
}

// (0, 90] in steps of `step_deg`, ending on 90.
std::vector<double> incidence_angles(double step_deg) {
  std::vector<double> alphas;
  for (int k = 1; k * step_deg < 90.0 - 1e-9; ++k) alphas.push_back(k * step_deg);
  alphas.push_back(90.0);
  return alphas;
}

PlotAxis axis(std::string label, std::optional<double> min = std::nullopt,
              std::optional<double> max = std::nullopt,
              std::optional<double> tick_step = std::nullopt) {
  PlotAxis a;
  a.label = std::move(label);
  a.min = min;
  a.max = max;
  a.tick_step = tick_step;
  return a;
}

PlotSeries series(std::string label, std::string colour = {}, bool dashed = false) {
  PlotSeries s;
  s.label = std::move(label);
  s.colour = std::move(colour);
  s.dashed = dashed;
  return s;
}

PlotPanel panel(std::string title, PlotAxis x_axis, PlotAxis y_axis, std::string legend_title) {
  PlotPanel p;
  p.title = std::move(title);
  p.x_axis = std::move(x_axis);
  p.y_axis = std::move(y_axis);
  p.legend_title = std::move(legend_title);
  return p;
}

PlotSeries mirror_reference() {
  PlotSeries mirror = series("mirror reflection (\u03b2 = \u03b1)", kReferenceGrey, true);
  mirror.x = {0.0, 90.0};
  mirror.y = {0.0, 90.0};
  return mirror;
}

RenderedFigure render_incidence_figure(const IncidenceFigure& figure,
                                       const phys::CushionParams& params,
                                       const std::vector<double>& alphas) {
  CsvTable table({"speed", "angle_deg", "topspin_k", "sidespin_k", "rebound_speed",
                  "rebound_angle_deg", "vx", "vy", "wx", "wy", "wz", "status"});
  const PlotAxis alpha_axis = axis(kAlphaLabel, 0.0, 90.0, 15.0);
  PlotPanel speed_panel =
      panel("Rebound speed", alpha_axis, axis("rebound speed (m/s)"), figure.legend_title);
  PlotPanel angle_panel = panel(
      figure.angle_note.empty() ? "Rebound angle" : "Rebound angle (" + figure.angle_note + ")",
      alpha_axis, axis("rebound angle \u03b2 (deg)"), figure.legend_title);
  RenderedFigure rendered{figure.file_stem, {}, {}, 0};

  for (const IncidenceCurve& curve : figure.curves) {
    PlotSeries speeds = series(curve.label);
    PlotSeries angles = series(curve.label);
    for (double alpha : alphas) {
      const phys::BallState incoming = phys::incoming_state_k(curve.speed, alpha, curve.topspin_k,
                                                              curve.sidespin_k, params.radius);
      const phys::ImpactResult r = phys::resolve_impact(params, incoming);
      const bool usable = phys::usable(r.status);
      if (!usable) ++rendered.unusable_points;
      const double speed = usable ? r.rebound_speed : NAN;
      const double angle = usable ? r.rebound_angle_deg : NAN;
      speeds.x.push_back(alpha);
      speeds.y.push_back(speed);
      angles.x.push_back(alpha);
      angles.y.push_back(angle);
      const phys::Vec3& v = r.outgoing.velocity;
      const phys::Vec3& w = r.outgoing.spin;
      std::vector<std::string> row;
      for (double x : {curve.speed, alpha, curve.topspin_k, curve.sidespin_k, speed, angle, v.x,
                       v.y, w.x, w.y, w.z})
        row.push_back(format_number(x));
      row.push_back(phys::to_string(r.status));
      table.add_row(std::move(row));
    }
    speed_panel.series.push_back(std::move(speeds));
    angle_panel.series.push_back(std::move(angles));
  }
  angle_panel.series.push_back(mirror_reference());

  PlotFigure plot{figure.title,
                  figure.caption + "; " + parameters_caption(params),
                  {std::move(speed_panel), std::move(angle_panel)}};
  rendered.picture = draw::plot_picture(plot);
  rendered.csv = table.to_string();
  return rendered;
}

// A slip direction is undefined while its contact sticks: blank it there, and break
// the line where it wraps round from +180 to -180 degrees.
std::vector<double> plotted_slip_angles(const std::vector<phys::TraceSample>& trace,
                                        bool at_cushion, double speed_scale,
                                        std::vector<double>* impulses) {
  std::vector<double> angles;
  impulses->clear();
  double previous = NAN;
  for (const phys::TraceSample& t : trace) {
    const double slip = at_cushion ? t.slip_cushion : t.slip_table;
    const double angle = at_cushion ? t.phi_cushion_deg : t.phi_table_deg;
    const double shown = slip > 1e-9 * speed_scale ? angle : NAN;
    if (std::isfinite(previous) && std::isfinite(shown) && std::abs(shown - previous) > 180.0) {
      impulses->push_back(NAN);
      angles.push_back(NAN);
    }
    impulses->push_back(t.impulse);
    angles.push_back(shown);
    previous = shown;
  }
  return angles;
}

// The trace in increasing P_I up to the end of the impact. The exact integrator may
// record a step that overshoots the end event before it locates the event; such
// samples lie past impulse_total and are dropped.
std::vector<phys::TraceSample> impact_history(std::vector<phys::TraceSample> trace,
                                              double impulse_total) {
  std::vector<phys::TraceSample> kept;
  for (const phys::TraceSample& t : trace) {
    if (t.impulse > impulse_total) continue;
    if (!kept.empty() && t.impulse < kept.back().impulse) continue;
    kept.push_back(t);
  }
  return kept;
}

// Figure 12: slip speeds and directions at both contacts over the cushion impulse.
RenderedFigure render_slip_figure(const phys::CushionParams& params) {
  constexpr double kSpeed = 2.0;   // m/s
  constexpr double kAlpha = 45.0;  // deg
  constexpr double kTopspinK = 1.5;
  constexpr double kSidespinK = 2.0;
  std::vector<phys::TraceSample> trace;
  phys::ImpactOptions options;
  options.method = phys::ImpactMethod::exact;
  options.trace = &trace;
  const phys::ImpactResult r = phys::resolve_impact(
      params, phys::incoming_state_k(kSpeed, kAlpha, kTopspinK, kSidespinK, params.radius),
      options);
  trace = impact_history(std::move(trace), r.impulse_total);

  RenderedFigure rendered{"fig12_slip_vs_impulse", {}, {}, phys::usable(r.status) ? 0 : 1};
  CsvTable table({"impulse", "slip_cushion", "phi_cushion_deg", "slip_table", "phi_table_deg",
                  "work", "vx", "vy", "wx", "wy", "wz"});
  // Cushion solid, table dashed, in both panels.
  PlotSeries s = series("s (cushion, I)", palette_colour(0));
  PlotSeries s_table = series("s\u2032 (table, C)", palette_colour(1), true);
  for (const phys::TraceSample& t : trace) {
    table.add_numbers({t.impulse, t.slip_cushion, t.phi_cushion_deg, t.slip_table, t.phi_table_deg,
                       t.work, t.state.velocity.x, t.state.velocity.y, t.state.spin.x,
                       t.state.spin.y, t.state.spin.z});
    s.x.push_back(t.impulse);
    s.y.push_back(t.slip_cushion);
    s_table.x.push_back(t.impulse);
    s_table.y.push_back(t.slip_table);
  }
  PlotSeries phi = series("\u03a6 (cushion, I)", palette_colour(0));
  PlotSeries phi_table = series("\u03a6\u2032 (table, C)", palette_colour(1), true);
  phi.y = plotted_slip_angles(trace, true, kSpeed, &phi.x);
  phi_table.y = plotted_slip_angles(trace, false, kSpeed, &phi_table.x);

  std::vector<PlotMarker> markers;
  if (phys::usable(r.status)) markers.push_back({r.impulse_compression, "end of compression"});
  const PlotAxis impulse_axis = axis("cushion impulse P_{I} (N s)", 0.0);
  PlotPanel speeds = panel("Slip speeds", impulse_axis, axis("slip speed (m/s)", 0.0), "contact");
  speeds.series = {std::move(s), std::move(s_table)};
  speeds.markers = markers;
  PlotPanel angles =
      panel("Slip directions", impulse_axis, axis("slip angle (deg, from X)"), "contact");
  angles.series = {std::move(phi), std::move(phi_table)};
  angles.markers = markers;
  PlotFigure plot{"Fig. 12  Slip at the cushion and at the table during the impact",
                  "V_{0} = 2 m/s, \u03b1 = 45\u00b0, \u03c9_{S} = 2V_{0}/R, "
                  "\u03c9_{T} = 1.5V_{0}/R; " +
                      parameters_caption(params),
                  {std::move(speeds), std::move(angles)}};
  rendered.picture = draw::plot_picture(plot);
  rendered.csv = table.to_string();
  return rendered;
}

// A spin value with a typographic minus and an optional note: "−1 (draw)".
std::string spin_label(double k, const char* note) {
  std::string label = k < 0.0 ? "\u2212" + format_number(-k) : format_number(k);
  if (note) label += std::string(" (") + note + ")";
  return label;
}

// Figures 8, 9 and 10 as the paper draws them.
std::vector<IncidenceFigure> paper_incidence_figures() {
  IncidenceFigure rolling{"fig08_rolling",
                          "Fig. 8  Rolling ball without sidespin: rebound versus incidence",
                          "k_{T} = 1 (\u03c9_{T} = V_{0}/R), k_{S} = 0",
                          "V_{0} (m/s)",
                          {},
                          "the curves coincide: \u03b2 does not depend on V_{0}"};
  for (double speed : {0.5, 1.0, 1.5, 2.0, 2.5})
    rolling.curves.push_back({format_number(speed), speed, 1.0, 0.0});

  IncidenceFigure topspin{"fig09_topspin",
                          "Fig. 9  Topspin: rebound versus incidence",
                          "V_{0} = 1 m/s, \u03c9_{T} = k_{T} V_{0}/R, k_{S} = 0",
                          "topspin k_{T}",
                          {},
                          {}};
  for (double k : {-1.0, 0.0, 0.5, 1.0, 1.5, 2.0}) {
    const char* note = k == 1.0 ? "rolling" : k == 0.0 ? "stun" : k < 0.0 ? "draw" : nullptr;
    topspin.curves.push_back({spin_label(k, note), 1.0, k, 0.0});
  }

  IncidenceFigure sidespin{"fig10_sidespin",
                           "Fig. 10  Sidespin: rebound versus incidence",
                           "V_{0} = 1 m/s, rolling (k_{T} = 1), \u03c9_{S} = k_{S} V_{0}/R",
                           "sidespin k_{S}",
                           {},
                           {}};
  for (double k : {-2.0, -1.0, 0.0, 1.0, 2.0})
    sidespin.curves.push_back({spin_label(k, k > 0.0   ? "right"
                                             : k < 0.0 ? "left"
                                                       : nullptr),
                               1.0, 1.0, k});

  return {rolling, topspin, sidespin};
}

}  // namespace

FiguresCommand::FiguresCommand(CLI::App& parent) {
  command_ = parent.add_subcommand(
      "figures",
      "Redraw figures 8, 9, 10 and 12 of Mathavan, Jackson & Parkin (2010) as SVG, PNG or PDF "
      "files, each with a CSV of the plotted numbers beside it.");
  CLI::App& c = *command_;
  c.add_option("--out", args_.out_dir, "Directory for the files (created if missing)")
      ->type_name("DIR")
      ->required();
  c.add_option("--format", args_.format, "Picture format: svg, png or pdf")
      ->type_name("FORMAT")
      ->capture_default_str();
  c.add_option("--alpha-step", args_.alpha_step_deg,
               "Spacing of the incidence angles over (0, 90] (deg), in (0, 90]")
      ->type_name("deg")
      ->capture_default_str();
  c.footer(
      "Files: fig08_rolling, fig09_topspin, fig10_sidespin (rebound speed and angle versus "
      "incidence angle) and fig12_slip_vs_impulse (slip speeds s, s' and angles Phi, Phi' "
      "versus the cushion impulse P_I), each as a picture (.svg, .png or .pdf, by --format) and "
      ".csv. CSV numbers are SI (m/s, "
      "rad/s, N s, J) unless the column name ends in _deg; the rebound CSVs have the columns "
      "of `cueplan rebound --batch` output except its message. Paper defaults (snooker), exact method.\n"
      "Exit codes: 0 done, 1 some impacts had no usable result, 2 bad input or unwritable "
      "directory.");
}

bool FiguresCommand::selected() const { return command_->parsed(); }

std::string FiguresCommand::check_flags() const {
  const double step = args_.alpha_step_deg;
  if (!std::isfinite(step) || !(step > 0.0) || !(step <= 90.0))
    return "--alpha-step must lie in (0, 90] degrees, got " + format_number(step);
  if (args_.out_dir.empty()) return "--out must name a directory, got ''";
  if (!draw::format_of("figure." + args_.format))
    return "--format must be svg, png or pdf, got '" + args_.format + "'";
  // A directory that is missing is created by run(); a file in its place is an error.
  std::error_code ec;
  if (std::filesystem::exists(args_.out_dir, ec) &&
      !std::filesystem::is_directory(args_.out_dir, ec))
    return "--out: " + args_.out_dir + " exists and is not a directory";
  return {};
}

int FiguresCommand::validate(std::ostream& err) const {
  const std::string why = check_flags();
  return why.empty() ? kExitOk : usage_error(err, kCommandName, why);
}

int FiguresCommand::run(std::ostream& out, std::ostream& err) const {
  const auto usage = [&](const std::string& why) { return usage_error(err, kCommandName, why); };
  if (std::string why = check_flags(); !why.empty()) return usage(why);
  const double step = args_.alpha_step_deg;
  const std::filesystem::path dir = args_.out_dir;
  if (std::string why = ensure_directory(dir); !why.empty()) return usage("--out: " + why);

  const phys::CushionParams params;  // the paper's snooker values
  const std::vector<double> alphas = incidence_angles(step);
  std::vector<RenderedFigure> figures;
  for (const IncidenceFigure& figure : paper_incidence_figures())
    figures.push_back(render_incidence_figure(figure, params, alphas));
  figures.push_back(render_slip_figure(params));

  int unusable = 0;
  for (const RenderedFigure& figure : figures) {
    const std::filesystem::path picture = dir / (figure.file_stem + "." + args_.format);
    if (std::string why = write_picture(picture, figure.picture); !why.empty())
      return usage("--out: " + why);
    out << picture.string() << '\n';
    const std::filesystem::path csv = dir / (figure.file_stem + ".csv");
    if (std::string why = write_file_atomically(csv, figure.csv); !why.empty())
      return usage("--out: " + why);
    out << csv.string() << '\n';
    unusable += figure.unusable_points;
  }
  if (unusable > 0) {
    err << kCommandName << ": " << unusable
        << " impacts had no usable result and are left out of the plots (see the CSV status)\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace cueplan::cli
