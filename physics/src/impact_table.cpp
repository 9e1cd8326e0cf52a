// The `table` method: tricubic interpolation of the exact method's scaled outcome,
// with every cell's error measured at build time (see impact_table.hpp). The build's
// stages are listed at ImpactTableAccess::build.
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>
#include <thread>

#include "impact_model.hpp"

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace cueplan::physics {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Scaled outcome (V0 = 1): velocities / V0, spins * R / V0, impulses / (M V0), work
// / (M V0^2). Two parts of it follow exactly from the rest and the incoming state,
// so nodes store only seven numbers:
//   eqs. (14a), (14d), (14e): d(o_y) = -((1 + s) / c) d(o_z) - 5/2 d(u_x);
//   eq. (16b): W_total = (1 - e^2) W_c.
enum Stored : int { kUx = 0, kUy, kOx, kOz, kPc, kPt, kWc, kStored };

struct Outcome {
  double ux = 0.0, uy = 0.0, ox = 0.0, oy = 0.0, oz = 0.0;
  double pc = 0.0, pt = 0.0, wc = 0.0, wt = 0.0;
};

// The full outcome from the stored numbers, for incidence cos(alpha) = ca and spins
// (kt, ks) (alpha <= 90, unmirrored).
Outcome expand(const double q[kStored], double ca, double kt, double ks, double spin_coupling,
               double work_ratio) {
  Outcome o;
  o.ux = q[kUx];
  o.uy = q[kUy];
  o.ox = q[kOx];
  o.oz = q[kOz];
  o.oy = kt * ca - spin_coupling * (q[kOz] - ks) - 2.5 * (q[kUx] - ca);
  o.pc = q[kPc];
  o.pt = q[kPt];
  o.wc = q[kWc];
  o.wt = work_ratio * q[kWc];
  return o;
}

// Per-cell stencil code: shifts (-1, 0, +1) along alpha, k_T, k_S as base-3 digits
// (the natural-roll plane uses the codes with no k_T shift).
constexpr int kStencils = 27;
constexpr int kCentred = 13;
constexpr uint8_t kFallback = 255;
int stencil_shift(int code, int axis) {
  const int digit = axis == 0 ? code / 9 : (axis == 1 ? code / 3 % 3 : code % 3);
  return digit - 1;
}

// Node values come from the exact method at its default tolerance (error ~1e-11).
constexpr double kNodeTolerance = 1e-12;
// A state is of paper form when its spin about the horizontal axis along the
// motion is below this, in units of V0 / R.
constexpr double kPaperFormTolerance = 1e-9;
// A state is in natural roll when |k_T - 1| is below this. The outcome varies like
// d log d in d = k_T - 1, so taking such a state as k_T = 1 errs by ~1e-9.
constexpr double kRollTolerance = 1e-10;
// Slack on the domain's edges, relative to k_max.
constexpr double kEdgeSlack = 1e-12;
// Same dimensionless parameters: relative difference below this.
constexpr double kParamsTolerance = 1e-12;

// atan2(y, x) in radians, within a few units in the last place of std::atan2 but
// several times cheaper (two divisions and a short polynomial): the octant
// reduction brings the ratio t = min/max into [0, 1], the nearest of the nine points
// k/8 takes out atan(k/8) exactly (tan(a - b) = (t - k/8) / (1 + t k/8), here in
// the unrounded form (min - c max) / (max + c min)), and a Taylor polynomial covers
// the rest, |r| <= 1/16, to 1e-19. Zeros, infinities and NaN go to std::atan2.
double fast_atan2(double y, double x) {
  // atan(k / 8), k = 0..8.
  static constexpr double kAtanEighths[9] = {
      0.0,                 0.12435499454676144, 0.24497866312686414,
      0.35877067027057225, 0.46364760900080609, 0.55859931534356244,
      0.64350110879328437, 0.71882999962162453, 0.78539816339744828};
  const double ax = std::abs(x), ay = std::abs(y);
  const bool steep = ay > ax;
  const double lo = steep ? ax : ay, hi = steep ? ay : ax;
  if (!(hi > 0.0 && hi < INFINITY && lo >= 0.0)) return std::atan2(y, x);  // 0, inf, NaN
  const int k = static_cast<int>(lo / hi * 8.0 + 0.5);
  const double c = 0.125 * k;
  const double r = (lo - c * hi) / (hi + c * lo);
  const double r2 = r * r;
  const double poly =
      r2 * (-1.0 / 3 +
            r2 * (1.0 / 5 + r2 * (-1.0 / 7 + r2 * (1.0 / 9 + r2 * (-1.0 / 11 + r2 / 13)))));
  double a = kAtanEighths[k] + (r + r * poly);
  if (steep) a = std::numbers::pi / 2 - a;
  if (std::signbit(x)) a = std::numbers::pi - a;
  return std::copysign(a, y);
}

bool close(double a, double b) {
  return std::abs(a - b) <= kParamsTolerance * std::max(std::abs(a), std::abs(b)) + 1e-300;
}

// Cubic Lagrange weights of nodes 0..3 at position u (in node spacings from node 0).
void lagrange_weights(double u, double w[4]) {
  const double a = u, b = u - 1.0, c = u - 2.0, d = u - 3.0;
  w[0] = -b * c * d / 6.0;
  w[1] = a * c * d / 2.0;
  w[2] = -a * b * d / 2.0;
  w[3] = a * b * c / 6.0;
}

// A point of the table's domain: incidence (deg) and the two spins.
struct Point {
  double alpha_deg, kt, ks;
};

// The exact method's stored outcome for V0 = 1 at each point of some lists, kStored
// numbers per point into the list's out; at alpha = 0 its limit (the ball passes
// unchanged). NaN where the exact method gave no usable answer, which makes every
// cell that needs the value fall back. A point whose out already holds a value (not
// NaN: one known from an earlier stage) is not resolved again. The impacts of all the
// lists are resolved together (resolve_impacts: SIMD lanes, one batch, so that few
// lanes idle at its end), each exactly as resolve_impact would, in buffers a build
// thread reuses.
struct ExactBuffers {
  std::vector<BallState> incoming;
  std::vector<double*> target;
  std::vector<ImpactResult> results;
};

struct PointList {
  const std::vector<Point>& points;
  double* out;
};

void exact_stored(const CushionParams& params, std::initializer_list<PointList> lists,
                  ExactBuffers& buffers) {
  std::vector<BallState>& incoming = buffers.incoming;
  std::vector<double*>& target = buffers.target;
  incoming.clear();
  target.clear();
  for (const PointList& list : lists) {
    for (size_t i = 0; i < list.points.size(); ++i) {
      const Point& pt = list.points[i];
      double* o = list.out + i * kStored;
      if (pt.alpha_deg == 0.0) {
        o[kUx] = 1.0;
        o[kUy] = 0.0;
        o[kOx] = 0.0;
        o[kOz] = pt.ks;
        o[kPc] = o[kPt] = o[kWc] = 0.0;
        continue;
      }
      if (!std::isnan(o[kUx])) continue;
      incoming.push_back(incoming_state_k(1.0, pt.alpha_deg, pt.kt, pt.ks, params.radius));
      target.push_back(o);
    }
  }
  ImpactOptions options;
  options.tolerance = kNodeTolerance;
  std::vector<ImpactResult>& results = buffers.results;
  results.resize(incoming.size());
  resolve_impacts(params, incoming, results, options);
  for (size_t j = 0; j < results.size(); ++j) {
    const ImpactResult& r = results[j];
    double* o = target[j];
    if (!usable(r.status)) {
      std::fill(o, o + kStored, kNaN);
      continue;
    }
    o[kUx] = r.outgoing.velocity.x;
    o[kUy] = r.outgoing.velocity.y;
    o[kOx] = r.outgoing.spin.x * params.radius;
    o[kOz] = r.outgoing.spin.z * params.radius;
    o[kPc] = r.impulse_compression / params.mass;
    o[kPt] = r.impulse_total / params.mass;
    o[kWc] = r.work_compression / params.mass;
  }
}

double rebound_angle(const Outcome& q) { return std::atan2(-q.uy, q.ux); }

// Errors of one interpolated outcome against the exact one, or the largest over
// several points.
struct PointError {
  double speed = 0.0, angle_deg = 0.0, state = 0.0, impulse = 0.0;

  bool unusable() const { return std::isnan(speed + angle_deg + state + impulse); }
  void include(const PointError& e) {
    if (e.unusable()) speed = kNaN;  // an unusable point spoils the cell
    if (unusable()) return;
    speed = std::max(speed, e.speed);
    angle_deg = std::max(angle_deg, e.angle_deg);
    state = std::max(state, e.state);
    impulse = std::max(impulse, e.impulse);
  }
};

// The exact outcome at a test point, with its rebound speed and angle, which every
// stencil tried at the point is compared with.
struct Truth {
  Outcome o;
  double speed = 0.0, angle = 0.0;
  Truth() = default;
  explicit Truth(const Outcome& x)
      : o(x), speed(std::sqrt(x.ux * x.ux + x.uy * x.uy)), angle(rebound_angle(x)) {}
};

PointError point_error(const Outcome& q, const Truth& truth) {
  const Outcome& x = truth.o;
  PointError e;
  e.speed = std::abs(std::sqrt(q.ux * q.ux + q.uy * q.uy) - truth.speed);
  e.angle_deg = std::abs(rebound_angle(q) - truth.angle) / kDegree;
  for (double d : {q.ux - x.ux, q.uy - x.uy, q.ox - x.ox, q.oy - x.oy, q.oz - x.oz})
    e.state = std::max(e.state, std::abs(d));
  for (double d : {q.pc - x.pc, q.pt - x.pt, q.wc - x.wc, q.wt - x.wt})
    e.impulse = std::max(e.impulse, std::abs(d));
  return e;
}

// Test points of a cell, in its local coordinates: the centre and the face centres.
constexpr int kTestPoints = 7;
constexpr double kTestLocal[kTestPoints][3] = {{0.5, 0.5, 0.5}, {0.0, 0.5, 0.5}, {1.0, 0.5, 0.5},
                                               {0.5, 0.0, 0.5}, {0.5, 1.0, 0.5}, {0.5, 0.5, 0.0},
                                               {0.5, 0.5, 1.0}};
// Test points of a cell of the natural-roll plane: its centre and edge midpoints.
constexpr int kRollTestPoints = 5;
constexpr double kRollTestLocal[kRollTestPoints][2] = {
    {0.5, 0.5}, {0.0, 0.5}, {1.0, 0.5}, {0.5, 0.0}, {0.5, 1.0}};

// FNV-1a, for the file checksum and the cache name.
uint64_t fnv1a(const void* data, size_t size, uint64_t h = 1469598103934665603ULL) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

// File format: magic, version, endianness mark, options, params, measured error,
// array sizes, arrays, FNV-1a checksum of everything before it.
constexpr char kMagic[8] = {'C', 'U', 'E', 'P', 'T', 'B', 'L', '\0'};
constexpr uint32_t kFormatVersion = 1;
constexpr uint32_t kEndianMark = 0x01020304u;

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    put_bytes(&value, sizeof value);
  }
  void put_bytes(const void* data, size_t size) {
    const auto* p = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<char>& bytes() { return bytes_; }
  void reserve(size_t size) { bytes_.reserve(size); }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes, size_t end) : bytes_(bytes), end_(end) {}
  template <class T>
  bool get(T* value) {
    return get_bytes(value, sizeof *value);
  }
  bool get_bytes(void* out, size_t size) {
    if (size > end_ - pos_) return false;
    std::memcpy(out, bytes_.data() + pos_, size);
    pos_ += size;
    return true;
  }
  size_t remaining() const { return end_ - pos_; }

 private:
  const std::vector<char>& bytes_;
  size_t end_;
  size_t pos_ = 0;
};

// Sizes a node array to n values of `fill`, asking first (before any page of it is
// written) for transparent huge pages where the system grants them on request: a
// query reads up to sixteen rows far apart in a table of tens of megabytes, and
// with 4 KiB pages each row would cost a TLB miss of its own.
void assign_nodes(std::vector<double>* nodes, size_t n, double fill) {
  nodes->clear();
  nodes->shrink_to_fit();
  nodes->reserve(n);
#ifdef __linux__
  constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
  const auto first = reinterpret_cast<uintptr_t>(nodes->data());
  const uintptr_t begin = (first + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t end = (first + n * sizeof(double)) & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
  nodes->assign(n, fill);
}

// Runs work(i, thread) for i in [0, count) on `threads` threads (this one included).
template <class Work>
void parallel_for(int threads, int count, Work&& work) {
  cueplan::parallel_for(static_cast<size_t>(count), static_cast<unsigned>(threads),
                        [&](size_t i, unsigned id) { work(static_cast<int>(i), static_cast<int>(id)); });
}

}  // namespace

// Build and file code with access to the table's layout.
class ImpactTableAccess {
 public:
  static void lay_out(ImpactTable* t);
  static ImpactTable build(const CushionParams& params, const ImpactTableOptions& options);
  // The build's stages (build() runs them in order).
  struct Build;
  static void volume_nodes(Build& b);
  static void volume_stencils(Build& b);
  static void roll_nodes(Build& b);
  static void roll_stencils(Build& b);
  static void measured_error(Build& b);
  // ImpactTable::interpolate and interpolate_roll at a test point, to the same bits,
  // for a table whose nodes are all finite (see add_terms).
  static void interpolate_test_point(const ImpactTable& t, const int cell[3],
                                     const double local[3], int stencil, double* out);
  static void interpolate_roll_test_point(const ImpactTable& t, const int cell[2],
                                          const double local[2], int stencil, double* out);
  static bool save(const ImpactTable& t, const std::string& path);
  static std::optional<ImpactTable> load(const std::string& path);
  static bool same_shape(const ImpactTableOptions& a, const ImpactTableOptions& b) {
    return a.alpha_nodes == b.alpha_nodes && a.topspin_nodes == b.topspin_nodes &&
           a.sidespin_nodes == b.sidespin_nodes && a.roll_alpha_nodes == b.roll_alpha_nodes &&
           a.roll_sidespin_nodes == b.roll_sidespin_nodes && a.k_max == b.k_max &&
           a.cell_tolerance == b.cell_tolerance;
  }
};

Validation ImpactTableOptions::validate() const {
  auto fail = [](const char* field, const char* rule, double value) {
    return invalid({field}, rule, value);
  };
  if (alpha_nodes < 4) return fail("alpha_nodes", "must be at least 4", alpha_nodes);
  if (topspin_nodes < 4) return fail("topspin_nodes", "must be at least 4", topspin_nodes);
  if (sidespin_nodes < 4) return fail("sidespin_nodes", "must be at least 4", sidespin_nodes);
  if (roll_alpha_nodes < 4) return fail("roll_alpha_nodes", "must be at least 4", roll_alpha_nodes);
  if (roll_sidespin_nodes < 4)
    return fail("roll_sidespin_nodes", "must be at least 4", roll_sidespin_nodes);
  if (!std::isfinite(k_max) || !(k_max > 0.0))
    return fail("k_max", "must be positive and finite", k_max);
  if (k_max > 1.0 && topspin_nodes < 7)
    return fail("topspin_nodes",
                "must be at least 7 when k_max > 1: a node sits on k_T = 1 with a cubic "
                "stencil either side",
                topspin_nodes);
  if (!std::isfinite(cell_tolerance) || !(cell_tolerance > 0.0))
    return fail("cell_tolerance", "must be positive and finite", cell_tolerance);
  if (threads < 0) return fail("threads", "must not be negative (0: all cores)", threads);
  const double nodes = static_cast<double>(alpha_nodes) * topspin_nodes * sidespin_nodes +
                       static_cast<double>(roll_alpha_nodes) * roll_sidespin_nodes;
  if (nodes > 1e8) return fail("alpha_nodes", "times the other node counts is too large", nodes);
  return {};
}

// --- Axis ---------------------------------------------------------------------

ImpactTable::Axis ImpactTable::Axis::uniform(int nodes, double lo, double hi) {
  Axis a;
  a.nodes = nodes;
  a.lo = lo;
  a.hi = hi;
  a.kink = hi;
  a.step_low = a.step_high = (hi - lo) / (nodes - 1);
  a.inv_step_low = a.inv_step_high = 1.0 / a.step_low;
  return a;
}

ImpactTable::Axis ImpactTable::Axis::with_kink(int nodes, double lo, double kink, double hi) {
  const int cells = nodes - 1;
  const long below = std::lround(cells * (kink - lo) / (hi - lo));
  Axis a;
  a.nodes = nodes;
  a.kink_node = static_cast<int>(std::clamp<long>(below, 3, cells - 3));
  a.lo = lo;
  a.kink = kink;
  a.hi = hi;
  a.step_low = (kink - lo) / a.kink_node;
  a.step_high = (hi - kink) / (cells - a.kink_node);
  a.inv_step_low = 1.0 / a.step_low;
  a.inv_step_high = 1.0 / a.step_high;
  return a;
}

double ImpactTable::Axis::node(int i) const {
  if (i == nodes - 1) return hi;
  if (kink_node < 0 || i < kink_node) return lo + i * step_low;
  if (i == kink_node) return kink;
  return kink + (i - kink_node) * step_high;
}

inline int ImpactTable::Axis::cell_of(double x, double* local) const {
  double u;
  int first, last;  // cells of the piece
  if (kink_node < 0 || x < kink) {
    u = (x - lo) * inv_step_low;
    first = 0;
    last = (kink_node < 0 ? nodes : kink_node + 1) - 2;
  } else {
    u = kink_node + (x - kink) * inv_step_high;
    first = kink_node;
    last = nodes - 2;
  }
  const int cell = std::clamp(static_cast<int>(std::floor(u)), first, last);
  *local = u - cell;
  return cell;
}

inline int ImpactTable::Axis::stencil_start(int cell, int shift) const {
  int first = 0, last = nodes - 1;  // nodes of the cell's piece
  if (kink_node >= 0) {
    if (cell < kink_node)
      last = kink_node;
    else
      first = kink_node;
  }
  return std::clamp(cell - 1 + shift, first, last - 3);
}

// --- Interpolation --------------------------------------------------------------

namespace {

// One row of four nodes along k_S, weighted: acc += sum_k w[k] * row[k].
inline void add_row(const double* row, double scale, const double w[4], double acc[kStored]) {
  const double a0 = scale * w[0], a1 = scale * w[1], a2 = scale * w[2], a3 = scale * w[3];
  for (int q = 0; q < kStored; ++q)
    acc[q] +=
        a0 * row[q] + a1 * row[kStored + q] + a2 * row[2 * kStored + q] + a3 * row[3 * kStored + q];
}

// add_row where only the weights w[k] != 0 count, when the row's values are finite:
// a zero weight makes its term a zero, and adding a zero leaves a sum unchanged (acc
// is never -0: it starts at +0 and a sum of round-to-nearest is -0 only when both
// addends are). `only` names the one nonzero weight, or is -1 to take all four.
inline void add_terms(const double* row, double scale, const double w[4], int only,
                      double acc[kStored]) {
  if (only < 0) return add_row(row, scale, w, acc);
  const double a = scale * w[only];
  const double* r = row + only * kStored;
  for (int q = 0; q < kStored; ++q) acc[q] += a * r[q];
}

// The one nonzero weight among four, or -1: a test point on a node plane (local 0 or
// 1) has weights 1 and three zeros along that axis.
inline int one_hot(const double w[4]) {
  int only = -1;
  for (int k = 0; k < 4; ++k) {
    if (w[k] == 0.0) continue;
    if (only >= 0) return -1;
    only = k;
  }
  return only;
}

}  // namespace

void ImpactTableAccess::interpolate_test_point(const ImpactTable& t, const int cell[3],
                                               const double local[3], int stencil,
                                               double* out) {
  int start[3];
  double w[3][4];
  for (int a = 0; a < 3; ++a) {
    start[a] = t.axes_[a].stencil_start(cell[a], stencil_shift(stencil, a));
    lagrange_weights(cell[a] - start[a] + local[a], w[a]);
  }
  const int only = one_hot(w[2]);
  const size_t nt = static_cast<size_t>(t.axes_[1].nodes), ns = static_cast<size_t>(t.axes_[2].nodes);
  double acc[kStored] = {};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double scale = w[0][i] * w[1][j];
      if (scale == 0.0) continue;
      add_terms(&t.nodes_[(((start[0] + i) * nt + start[1] + j) * ns + start[2]) * kStored], scale,
                w[2], only, acc);
    }
  }
  std::copy(acc, acc + kStored, out);
}

void ImpactTableAccess::interpolate_roll_test_point(const ImpactTable& t, const int cell[2],
                                                    const double local[2], int stencil,
                                                    double* out) {
  int start[2];
  double w[2][4];
  for (int a = 0; a < 2; ++a) {
    start[a] = t.roll_axes_[a].stencil_start(cell[a], stencil_shift(stencil, 2 * a));
    lagrange_weights(cell[a] - start[a] + local[a], w[a]);
  }
  const int only = one_hot(w[1]);
  const size_t ns = static_cast<size_t>(t.roll_axes_[1].nodes);
  double acc[kStored] = {};
  for (int i = 0; i < 4; ++i)
    if (w[0][i] != 0.0)
      add_terms(&t.roll_nodes_[((start[0] + i) * ns + start[1]) * kStored], w[0][i], w[1], only,
                acc);
  std::copy(acc, acc + kStored, out);
}

void ImpactTable::interpolate(const int cell[3], const double local[3], int stencil,
                              double* out) const {
  int start[3];
  double w[3][4];
  for (int a = 0; a < 3; ++a) {
    start[a] = axes_[a].stencil_start(cell[a], stencil_shift(stencil, a));
    lagrange_weights(cell[a] - start[a] + local[a], w[a]);
  }
  const size_t nt = static_cast<size_t>(axes_[1].nodes), ns = static_cast<size_t>(axes_[2].nodes);
  const double* rows[16];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      rows[4 * i + j] = &nodes_[(((start[0] + i) * nt + start[1] + j) * ns + start[2]) * kStored];
  // Ask for every cache line of the sixteen rows at once: in a table larger than
  // the cache each is a miss, and they overlap only when requested together.
  for (const double* row : rows) {
    for (int b = 0; b < 4 * kStored; b += 8) __builtin_prefetch(row + b);
    __builtin_prefetch(row + 4 * kStored - 1);
  }
  double acc[kStored] = {};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) add_row(rows[4 * i + j], w[0][i] * w[1][j], w[2], acc);
  std::copy(acc, acc + kStored, out);
}

void ImpactTable::interpolate_roll(const int cell[2], const double local[2], int stencil,
                                   double* out) const {
  int start[2];
  double w[2][4];
  for (int a = 0; a < 2; ++a) {
    start[a] = roll_axes_[a].stencil_start(cell[a], stencil_shift(stencil, 2 * a));
    lagrange_weights(cell[a] - start[a] + local[a], w[a]);
  }
  const size_t ns = static_cast<size_t>(roll_axes_[1].nodes);
  const double* rows[4];
  for (int i = 0; i < 4; ++i) rows[i] = &roll_nodes_[((start[0] + i) * ns + start[1]) * kStored];
  // As in the volume: request the rows' cache lines together.
  for (const double* row : rows) {
    for (int b = 0; b < 4 * kStored; b += 8) __builtin_prefetch(row + b);
    __builtin_prefetch(row + 4 * kStored - 1);
  }
  double acc[kStored] = {};
  for (int i = 0; i < 4; ++i) add_row(rows[i], w[0][i], w[1], acc);
  std::copy(acc, acc + kStored, out);
}

// --- Build ----------------------------------------------------------------------

void ImpactTableAccess::lay_out(ImpactTable* t) {
  const ImpactTableOptions& o = t->options_;
  t->axes_[0] = ImpactTable::Axis::uniform(o.alpha_nodes, 0.0, 90.0);
  t->axes_[1] = o.k_max > 1.0
                    ? ImpactTable::Axis::with_kink(o.topspin_nodes, -o.k_max, 1.0, o.k_max)
                    : ImpactTable::Axis::uniform(o.topspin_nodes, -o.k_max, o.k_max);
  t->axes_[2] = ImpactTable::Axis::uniform(o.sidespin_nodes, -o.k_max, o.k_max);
  t->has_roll_plane_ = o.k_max >= 1.0;
  t->roll_axes_[0] = ImpactTable::Axis::uniform(o.roll_alpha_nodes, 0.0, 90.0);
  t->roll_axes_[1] = ImpactTable::Axis::uniform(o.roll_sidespin_nodes, -o.k_max, o.k_max);
  const CushionParams& p = t->params_;
  t->sin_theta_ = p.sin_theta();
  t->cos_theta_ = p.cos_theta();
  t->spin_coupling_ = (1.0 + t->sin_theta_) / p.cos_theta();
  t->work_ratio_ = 1.0 - p.restitution * p.restitution;
}

namespace {

// How far over the tolerance an error is (see ImpactTableOptions::cell_tolerance):
// <= 1 passes; NaN for an unusable point.
double excess(const PointError& e, double tolerance) {
  if (e.unusable()) return kNaN;
  return std::max({e.speed / tolerance, e.angle_deg / (100.0 * tolerance),
                   std::max(e.state, e.impulse) / (10.0 * tolerance)});
}

// The stencil of a cell: the centred one when its measured error passes, else the
// passing candidate with the smallest (the first in code order among equals);
// kFallback when none passes (`error` is then not set). error_of(code, cutoff)
// measures one stencil at the cell's test points, and may stop early once the excess
// is above `cutoff` (such a stencil is not chosen): above 1 until one passes, then
// above the best. The candidates are measured with `hint` first (a neighbour's
// stencil, or -1), as a low cutoff found early stops the others sooner; the choice
// does not depend on the order.
template <class ErrorOf>
uint8_t choose_stencil(bool roll_plane, double tolerance, int hint, ErrorOf&& error_of,
                       PointError* error) {
  const PointError centred = error_of(kCentred, INFINITY);
  if (excess(centred, tolerance) <= 1.0) {
    *error = centred;
    return kCentred;
  }
  auto candidate = [&](int s) {
    return s >= 0 && s < kStencils && s != kCentred && !(roll_plane && stencil_shift(s, 1) != 0);
  };
  if (!candidate(hint)) hint = -1;
  int best = -1;
  double best_excess = 1.0;
  for (int k = hint < 0 ? 0 : -1; k < kStencils; ++k) {
    const int s = k < 0 ? hint : k;
    if (!candidate(s) || (k >= 0 && s == hint)) continue;
    const PointError e = error_of(s, best_excess);
    const double now = excess(e, tolerance);
    if (now <= 1.0 && (best < 0 || now < best_excess || (now == best_excess && s < best))) {
      best = s;
      best_excess = now;
      *error = e;
    }
  }
  return best < 0 ? kFallback : static_cast<uint8_t>(best);
}

// The order in which a cell's test points are tried. A stencil's measurement stops at
// the first point that takes its excess over the cutoff, and the stencil chosen does
// not depend on the order: a stencil measured in full has the maximum over its points
// whatever the order, and one stopped early is over the cutoff in any order. The
// point that stopped the last stencil goes first (the centred stencil's worst point
// to begin with), as the next stencil most likely fails there too.
template <int N>
class PointOrder {
 public:
  PointOrder() {
    for (int k = 0; k < N; ++k) order_[k] = k;
  }
  int operator[](int k) const { return order_[k]; }
  void to_front(int k) {
    const int p = order_[k];
    for (int i = k; i > 0; --i) order_[i] = order_[i - 1];
    order_[0] = p;
  }

 private:
  int order_[N];
};

// Measures a stencil at the test points in `order`: error_at(p) is its error at point
// p. Stops once the excess is over `cutoff`, moving the point that took it there to
// the front of the order.
template <int N, class ErrorAt>
PointError measure(PointOrder<N>& order, double tolerance, double cutoff, ErrorAt&& error_at) {
  PointError e;
  int worst = 0;
  double worst_excess = -1.0;
  for (int k = 0; k < N; ++k) {
    if (excess(e, tolerance) > cutoff) {
      order.to_front(k - 1);
      return e;
    }
    const PointError at = error_at(order[k]);
    if (cutoff == INFINITY) {
      const double x = excess(at, tolerance);
      if (!(x <= worst_excess)) {
        worst = k;
        worst_excess = std::isnan(x) ? INFINITY : x;
      }
    }
    e.include(at);
  }
  if (cutoff == INFINITY) order.to_front(worst);
  return e;
}

// What one build thread found.
struct Tally {
  PointError worst;
  int64_t fallback = 0;
  int64_t roll_fallback = 0;
  int64_t test_points = 0;
};

}  // namespace

// What the stages of a build share.
struct ImpactTableAccess::Build {
  Build(ImpactTable& table, const CushionParams& params) : t(table), exact_params(params) {}
  ImpactTable& t;
  CushionParams exact_params;  // the ball of the table's params, never flagged
  double tolerance = 0.0;      // cell_tolerance
  double coupling = 0.0, work_ratio = 0.0;
  int threads = 1;
  std::vector<Tally> tallies;  // one per build thread
  std::vector<ExactBuffers> buffers;  // one per build thread
  // Exact outcomes at test points kept from one stage for the next: on the centres of
  // the cell faces normal to alpha (per alpha node), and on the natural-roll plane at
  // the midpoints of the cell edges along k_S (per alpha node).
  std::vector<double> alpha_faces;
  std::vector<double> alpha_edges;

  // The exact outcomes at the points of some lists, on build thread `thread`; an out
  // must hold NaN where a value is wanted.
  void exact(std::initializer_list<PointList> lists, int thread) {
    exact_stored(exact_params, lists, buffers[thread]);
  }
  static double mid(const ImpactTable::Axis& axis, int i) {
    return 0.5 * (axis.node(i) + axis.node(i + 1));
  }
  // For each node of `from`, the node of `to` at exactly the same coordinate, or -1.
  static std::vector<int> same_nodes(const ImpactTable::Axis& from, const ImpactTable::Axis& to) {
    std::vector<double> at(to.nodes);
    for (int j = 0; j < to.nodes; ++j) at[j] = to.node(j);
    std::vector<int> same(from.nodes, -1);
    for (int i = 0; i < from.nodes; ++i) {
      const auto j = std::lower_bound(at.begin(), at.end(), from.node(i));
      if (j != at.end() && *j == from.node(i)) same[i] = static_cast<int>(j - at.begin());
    }
    return same;
  }
  static double at(const ImpactTable::Axis& axis, int i, double local) {
    return axis.node(i) + local * (axis.node(i + 1) - axis.node(i));
  }
};

// The build, stage by stage:
//   1. volume_nodes: per alpha node, the exact outcome at the nodes of its k_T x k_S
//      plane and at the test points in that plane (centres of the cell faces normal to
//      alpha);
//   2. volume_stencils: per alpha slab of cells, the exact outcome at the other test
//      points (cell centres, faces normal to k_T and k_S), then each cell's stencil or
//      fallback;
//   3, 4. roll_nodes, roll_stencils: the same on the natural-roll plane k_T = 1 (nodes
//      and edge midpoints in each alpha line, then centres and the other edge midpoints
//      per slab);
//   5. measured_error: the build threads' tallies summed.
// Each stage runs on the build threads; the exact outcomes of a work item are resolved
// as one batch.
ImpactTable ImpactTableAccess::build(const CushionParams& params,
                                     const ImpactTableOptions& options) {
  ImpactTable t;
  t.options_ = options;
  t.params_ = params;
  if (options.validate() || params.validate()) return t;
  lay_out(&t);
  Build b{t, params};
  b.exact_params.rigid_speed_limit = DBL_MAX;
  b.tolerance = options.cell_tolerance;
  b.coupling = t.spin_coupling_;
  b.work_ratio = t.work_ratio_;
  b.threads = std::max(options.threads > 0 ? options.threads
                                           : static_cast<int>(std::thread::hardware_concurrency()),
                       1);
  b.tallies.resize(b.threads);
  b.buffers.resize(b.threads);

  volume_nodes(b);
  volume_stencils(b);
  if (t.has_roll_plane_) {
    roll_nodes(b);
    roll_stencils(b);
  }
  measured_error(b);
  return t;
}

void ImpactTableAccess::volume_nodes(Build& b) {
  ImpactTable& t = b.t;
  const ImpactTable::Axis* axes = t.axes_;
  const int na = axes[0].nodes, nt = axes[1].nodes, ns = axes[2].nodes;
  const size_t plane_nodes = static_cast<size_t>(nt) * ns;
  const size_t plane_cells = static_cast<size_t>(nt - 1) * (ns - 1);
  assign_nodes(&t.nodes_, na * plane_nodes * kStored, kNaN);
  b.alpha_faces.assign(na * plane_cells * kStored, kNaN);
  parallel_for(b.threads, na, [&](int ia, int id) {
    const double alpha = axes[0].node(ia);
    std::vector<Point> nodes, faces;
    for (int it = 0; it < nt; ++it)
      for (int is = 0; is < ns; ++is) nodes.push_back({alpha, axes[1].node(it), axes[2].node(is)});
    for (int it = 0; it < nt - 1; ++it)
      for (int is = 0; is < ns - 1; ++is)
        faces.push_back({alpha, Build::mid(axes[1], it), Build::mid(axes[2], is)});
    b.exact({{nodes, &t.nodes_[ia * plane_nodes * kStored]},
             {faces, &b.alpha_faces[ia * plane_cells * kStored]}},
            id);
    b.tallies[id].test_points += static_cast<int64_t>(plane_cells);
  });
}

void ImpactTableAccess::volume_stencils(Build& b) {
  ImpactTable& t = b.t;
  const ImpactTable::Axis* axes = t.axes_;
  const int na = axes[0].nodes, nt = axes[1].nodes, ns = axes[2].nodes;
  const size_t plane_cells = static_cast<size_t>(nt - 1) * (ns - 1);
  const double tolerance = b.tolerance, coupling = b.coupling, work_ratio = b.work_ratio;
  t.cell_stencil_.assign((na - 1) * plane_cells, kFallback);
  const bool finite = std::all_of(t.nodes_.begin(), t.nodes_.end(),
                                  [](double x) { return std::isfinite(x); });
  parallel_for(b.threads, na - 1, [&](int ia, int id) {
    Tally& tally = b.tallies[id];
    const double alpha = Build::mid(axes[0], ia);
    double cos_alpha[kTestPoints];
    for (int p = 0; p < kTestPoints; ++p)
      cos_alpha[p] = std::cos(Build::at(axes[0], ia, kTestLocal[p][0]) * kDegree);
    // Exact values at the centres (it, is), k_T faces (node it, mid is) and k_S
    // faces (mid it, node is) of this slab.
    std::vector<Point> centre_points, topspin_points, sidespin_points;
    for (int it = 0; it < nt; ++it) {
      for (int is = 0; is < ns; ++is) {
        if (it < nt - 1 && is < ns - 1)
          centre_points.push_back({alpha, Build::mid(axes[1], it), Build::mid(axes[2], is)});
        if (is < ns - 1) topspin_points.push_back({alpha, axes[1].node(it), Build::mid(axes[2], is)});
        if (it < nt - 1) sidespin_points.push_back({alpha, Build::mid(axes[1], it), axes[2].node(is)});
      }
    }
    std::vector<double> centres(plane_cells * kStored, kNaN),
        topspin_faces(nt * (ns - 1) * kStored, kNaN), sidespin_faces((nt - 1) * ns * kStored, kNaN);
    b.exact({{centre_points, centres.data()},
             {topspin_points, topspin_faces.data()},
             {sidespin_points, sidespin_faces.data()}},
            id);
    tally.test_points += static_cast<int64_t>(plane_cells + nt * (ns - 1) + (nt - 1) * ns);

    for (int it = 0; it < nt - 1; ++it) {
      for (int is = 0; is < ns - 1; ++is) {
        const int cell[3] = {ia, it, is};
        const size_t in_plane = it * (ns - 1) + is;
        const double* exact_at[kTestPoints] = {
            &centres[in_plane * kStored],
            &b.alpha_faces[(ia * plane_cells + in_plane) * kStored],
            &b.alpha_faces[((ia + 1) * plane_cells + in_plane) * kStored],
            &topspin_faces[in_plane * kStored],
            &topspin_faces[((it + 1) * (ns - 1) + is) * kStored],
            &sidespin_faces[(it * ns + is) * kStored],
            &sidespin_faces[(it * ns + is + 1) * kStored]};
        Truth truth[kTestPoints];
        double kt[kTestPoints], ks[kTestPoints];
        for (int p = 0; p < kTestPoints; ++p) {
          kt[p] = Build::at(axes[1], it, kTestLocal[p][1]);
          ks[p] = Build::at(axes[2], is, kTestLocal[p][2]);
          truth[p] = Truth(expand(exact_at[p], cos_alpha[p], kt[p], ks[p], coupling, work_ratio));
        }
        PointOrder<kTestPoints> order;
        auto error_of = [&](int stencil, double cutoff) {
          return measure(order, tolerance, cutoff, [&](int p) {
            double q[kStored];
            if (finite)
              interpolate_test_point(t, cell, kTestLocal[p], stencil, q);
            else
              t.interpolate(cell, kTestLocal[p], stencil, q);
            return point_error(expand(q, cos_alpha[p], kt[p], ks[p], coupling, work_ratio),
                               truth[p]);
          });
        };
        PointError e;
        const int hint = is > 0 ? t.cell_stencil_[ia * plane_cells + in_plane - 1] : -1;
        const uint8_t code = choose_stencil(false, tolerance, hint, error_of, &e);
        t.cell_stencil_[ia * plane_cells + in_plane] = code;
        if (code == kFallback)
          ++tally.fallback;
        else
          tally.worst.include(e);
      }
    }
  });
  b.alpha_faces = {};
}

void ImpactTableAccess::roll_nodes(Build& b) {
  ImpactTable& t = b.t;
  const ImpactTable::Axis* roll = t.roll_axes_;
  const int ra = roll[0].nodes, rs = roll[1].nodes;
  assign_nodes(&t.roll_nodes_, static_cast<size_t>(ra) * rs * kStored, kNaN);
  b.alpha_edges.assign(static_cast<size_t>(ra) * (rs - 1) * kStored, kNaN);
  // Nodes of the plane that are nodes of the volume too (k_T = 1 is a node of its k_T
  // axis; in the default table every fourth node along both axes) take the volume's
  // values instead of being resolved again.
  const ImpactTable::Axis* axes = t.axes_;
  int kt_one = -1;
  for (int it = 0; it < axes[1].nodes; ++it)
    if (axes[1].node(it) == 1.0) kt_one = it;
  const std::vector<int> alpha_in_volume = Build::same_nodes(roll[0], axes[0]);
  const std::vector<int> ks_in_volume = Build::same_nodes(roll[1], axes[2]);
  const size_t nt = static_cast<size_t>(axes[1].nodes), ns = static_cast<size_t>(axes[2].nodes);
  parallel_for(b.threads, ra, [&](int ia, int id) {
    const double alpha = roll[0].node(ia);
    if (kt_one >= 0 && alpha_in_volume[ia] >= 0) {
      for (int is = 0; is < rs; ++is) {
        if (ks_in_volume[is] < 0) continue;
        const double* from =
            &t.nodes_[((alpha_in_volume[ia] * nt + kt_one) * ns + ks_in_volume[is]) * kStored];
        std::copy(from, from + kStored, &t.roll_nodes_[(static_cast<size_t>(ia) * rs + is) * kStored]);
      }
    }
    std::vector<Point> nodes, edges;
    for (int is = 0; is < rs; ++is) nodes.push_back({alpha, 1.0, roll[1].node(is)});
    for (int is = 0; is < rs - 1; ++is) edges.push_back({alpha, 1.0, Build::mid(roll[1], is)});
    b.exact({{nodes, &t.roll_nodes_[static_cast<size_t>(ia) * rs * kStored]},
             {edges, &b.alpha_edges[static_cast<size_t>(ia) * (rs - 1) * kStored]}},
            id);
    b.tallies[id].test_points += rs - 1;
  });
}

void ImpactTableAccess::roll_stencils(Build& b) {
  ImpactTable& t = b.t;
  const ImpactTable::Axis* roll = t.roll_axes_;
  const int ra = roll[0].nodes, rs = roll[1].nodes;
  const double tolerance = b.tolerance, coupling = b.coupling, work_ratio = b.work_ratio;
  t.roll_stencil_.assign(static_cast<size_t>(ra - 1) * (rs - 1), kFallback);
  const bool finite = std::all_of(t.roll_nodes_.begin(), t.roll_nodes_.end(),
                                  [](double x) { return std::isfinite(x); });
  parallel_for(b.threads, ra - 1, [&](int ia, int id) {
    Tally& tally = b.tallies[id];
    const double alpha = Build::mid(roll[0], ia);
    double cos_alpha[kRollTestPoints];
    for (int p = 0; p < kRollTestPoints; ++p)
      cos_alpha[p] = std::cos(Build::at(roll[0], ia, kRollTestLocal[p][0]) * kDegree);
    std::vector<Point> centre_points, edge_points;
    for (int is = 0; is < rs; ++is) {
      if (is < rs - 1) centre_points.push_back({alpha, 1.0, Build::mid(roll[1], is)});
      edge_points.push_back({alpha, 1.0, roll[1].node(is)});
    }
    std::vector<double> centres((rs - 1) * kStored, kNaN), sidespin_edges(rs * kStored, kNaN);
    b.exact({{centre_points, centres.data()}, {edge_points, sidespin_edges.data()}}, id);
    tally.test_points += 2 * rs - 1;
    for (int is = 0; is < rs - 1; ++is) {
      const int cell[2] = {ia, is};
      const double* exact_at[kRollTestPoints] = {
          &centres[is * kStored], &b.alpha_edges[(ia * (rs - 1) + is) * kStored],
          &b.alpha_edges[((ia + 1) * (rs - 1) + is) * kStored], &sidespin_edges[is * kStored],
          &sidespin_edges[(is + 1) * kStored]};
      Truth truth[kRollTestPoints];
      double ks[kRollTestPoints];
      for (int p = 0; p < kRollTestPoints; ++p) {
        ks[p] = Build::at(roll[1], is, kRollTestLocal[p][1]);
        truth[p] = Truth(expand(exact_at[p], cos_alpha[p], 1.0, ks[p], coupling, work_ratio));
      }
      PointOrder<kRollTestPoints> order;
      auto error_of = [&](int stencil, double cutoff) {
        return measure(order, tolerance, cutoff, [&](int p) {
          double q[kStored];
          if (finite)
            interpolate_roll_test_point(t, cell, kRollTestLocal[p], stencil, q);
          else
            t.interpolate_roll(cell, kRollTestLocal[p], stencil, q);
          return point_error(expand(q, cos_alpha[p], 1.0, ks[p], coupling, work_ratio), truth[p]);
        });
      };
      PointError e;
      const int hint = is > 0 ? t.roll_stencil_[ia * (rs - 1) + is - 1] : -1;
      const uint8_t code = choose_stencil(true, tolerance, hint, error_of, &e);
      t.roll_stencil_[ia * (rs - 1) + is] = code;
      if (code == kFallback)
        ++tally.roll_fallback;
      else
        tally.worst.include(e);
    }
  });
  b.alpha_edges = {};
}

void ImpactTableAccess::measured_error(Build& b) {
  ImpactTable& t = b.t;
  ImpactTableError& err = t.error_;
  err.cells = static_cast<int64_t>(t.cell_stencil_.size());
  err.roll_cells = static_cast<int64_t>(t.roll_stencil_.size());
  for (const Tally& tally : b.tallies) {
    err.max_speed_relative = std::max(err.max_speed_relative, tally.worst.speed);
    err.max_angle_deg = std::max(err.max_angle_deg, tally.worst.angle_deg);
    err.max_state_relative = std::max(err.max_state_relative, tally.worst.state);
    err.max_impulse_relative = std::max(err.max_impulse_relative, tally.worst.impulse);
    err.fallback_cells += tally.fallback;
    err.roll_fallback_cells += tally.roll_fallback;
    err.test_points += tally.test_points;
  }
}

ImpactTable ImpactTable::build(const CushionParams& params, const ImpactTableOptions& options) {
  // A table of the Mathavan model, whatever model the parameters name (covers() then
  // refuses other models' parameters).
  CushionParams mathavan = params;
  mathavan.model = CushionModel::mathavan_2010;
  return ImpactTableAccess::build(mathavan, options);
}

double ImpactTable::fallback_fraction() const {
  if (error_.cells == 0) return 1.0;
  return static_cast<double>(error_.fallback_cells) / static_cast<double>(error_.cells);
}

double ImpactTable::roll_fallback_fraction() const {
  if (error_.roll_cells == 0) return 1.0;
  return static_cast<double>(error_.roll_fallback_cells) / static_cast<double>(error_.roll_cells);
}

bool ImpactTable::covers(const CushionParams& params) const {
  return !empty() && params.model == CushionModel::mathavan_2010 && close(params.sin_theta(), sin_theta_) &&
         close(params.mu_cushion, params_.mu_cushion) && close(params.mu_table, params_.mu_table) &&
         close(params.restitution, params_.restitution);
}

// --- Query ----------------------------------------------------------------------

namespace {

constexpr double kRadianToDegree = 180.0 / std::numbers::pi;

// The exact method's choice of stick or slip at the start of an impact (its
// settle_modes): stick wherever the friction fits the cone, trying full stick first.
// A slipping contact takes its slip's direction; one whose slip is zero slides
// against the friction that full stick would have needed (only when both slips are
// zero can such a contact slip beside a sticking one).
detail::Modes starting_modes(const detail::Geometry& g, const detail::Slips& sl, bool zero_i,
                             bool zero_c) {
  if (!zero_i && !zero_c) return {false, false};
  detail::Direction di = zero_i ? detail::Direction{} : detail::direction_of(sl.ix, sl.iy, {}, 0.0);
  detail::Direction dc = zero_c ? detail::Direction{} : detail::direction_of(sl.cx, sl.cy, {}, 0.0);
  if (zero_i && zero_c) {
    const detail::Friction full = detail::friction_for(g, {true, true}, di, dc);
    auto against = [](double x, double y) {
      const double n = std::hypot(x, y);
      return n > 0.0 ? detail::Direction{-x / n, -y / n} : detail::Direction{};
    };
    di = against(full.ix, full.iy);
    dc = against(full.cx, full.cy);
  }
  const detail::Modes candidates[3] = {{zero_i, zero_c}, {zero_i, false}, {false, zero_c}};
  for (const detail::Modes& m : candidates) {
    if (!m.stick_i && !m.stick_c) continue;
    const detail::Friction f = detail::friction_for(g, m, di, dc);
    if ((!m.stick_i || detail::stick_margin_i(g, f) >= 0.0) &&
        (!m.stick_c || detail::stick_margin_c(g, f) >= 0.0))
      return m;
  }
  return {false, false};
}

// resolve_impact's message for a normal speed above the rigid limit ("%.10g"; to_chars
// with a precision prints as printf does, without its cost).
void set_rigid_limit_message(double normal_speed, std::string* message) {
  static constexpr char kText[] = "velocity.y is above the rigid-cushion limit (m/s), got ";
  char buf[sizeof kText + 32];
  std::memcpy(buf, kText, sizeof kText - 1);
  const std::to_chars_result end = std::to_chars(buf + sizeof kText - 1, buf + sizeof buf,
                                                 normal_speed, std::chars_format::general, 10);
  message->assign(buf, end.ptr);
}

}  // namespace

bool ImpactTable::resolve(const CushionParams& params, const BallState& incoming,
                          ImpactResult* result) const {
  const Vec3& v = incoming.velocity;
  const Vec3& w = incoming.spin;
  if (result == nullptr || !covers(params)) return false;
  if (!std::isfinite(params.radius) || !(params.radius > 0.0) || !std::isfinite(params.mass) ||
      !(params.mass > 0.0) || std::isnan(params.rigid_speed_limit))
    return false;
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || v.z != 0.0 || !(v.y > 0.0) || !is_finite(w))
    return false;

  // Section 3.1 read backwards: speed, incidence and the dimensionless spins.
  const double speed = std::sqrt(v.x * v.x + v.y * v.y);
  const double inv_speed = 1.0 / speed;
  const double ca = v.x * inv_speed, sa = v.y * inv_speed;
  const double spin_scale = params.radius * inv_speed;  // rad/s -> multiples of V0 / R
  const double ox = w.x * spin_scale, oy = w.y * spin_scale, oz = w.z * spin_scale;
  const double along = ox * ca + oy * sa;
  if (!(std::abs(along) <= kPaperFormTolerance)) return false;
  const double kt = oy * ca - ox * sa;
  // alpha > 90 mirrors alpha < 90 with the sidespin reversed.
  const bool mirrored = v.x < 0.0;
  const double ks = mirrored ? -oz : oz;
  const double k_max = options_.k_max;
  const double k_edge = k_max * (1.0 + kEdgeSlack);
  if (!(std::abs(kt) <= k_edge) || !(std::abs(ks) <= k_edge)) return false;
  const double alpha = fast_atan2(v.y, std::abs(v.x)) * kRadianToDegree;
  const double ks_in = std::clamp(ks, -k_max, k_max);

  // Interpolate on the natural-roll plane when k_T = 1, else in the volume.
  double stored[kStored];
  if (has_roll_plane_ && std::abs(kt - 1.0) <= kRollTolerance) {
    int cell[2];
    double local[2];
    cell[0] = roll_axes_[0].cell_of(alpha, &local[0]);
    cell[1] = roll_axes_[1].cell_of(ks_in, &local[1]);
    const uint8_t stencil =
        roll_stencil_[static_cast<size_t>(cell[0]) * (roll_axes_[1].nodes - 1) + cell[1]];
    if (stencil == kFallback) return false;
    interpolate_roll(cell, local, stencil, stored);
  } else {
    int cell[3];
    double local[3];
    cell[0] = axes_[0].cell_of(alpha, &local[0]);
    cell[1] = axes_[1].cell_of(std::clamp(kt, -k_max, k_max), &local[1]);
    cell[2] = axes_[2].cell_of(ks_in, &local[2]);
    const size_t c =
        (static_cast<size_t>(cell[0]) * (axes_[1].nodes - 1) + cell[1]) * (axes_[2].nodes - 1) +
        cell[2];
    if (cell_stencil_[c] == kFallback) return false;
    interpolate(cell, local, cell_stencil_[c], stored);
  }
  Outcome q = expand(stored, std::abs(ca), kt, ks, spin_coupling_, work_ratio_);
  if (mirrored) {
    q.ux = -q.ux;
    q.oy = -q.oy;
    q.oz = -q.oz;
  }

  // Physical units: V0 for velocities, V0 / R for spins, M V0 for impulses.
  const double spin_unit = speed / params.radius;
  const double impulse_unit = params.mass * speed;
  const double work_unit = impulse_unit * speed;
  ImpactResult& r = *result;
  r.status = ImpactStatus::ok;
  r.message.clear();
  r.method_used = ImpactMethod::table;
  r.outgoing.velocity = {q.ux * speed, q.uy * speed, 0.0};
  r.outgoing.spin = {q.ox * spin_unit, q.oy * spin_unit, q.oz * spin_unit};
  r.rebound_speed = std::sqrt(q.ux * q.ux + q.uy * q.uy) * speed;
  r.rebound_angle_deg = fast_atan2(-q.uy, q.ux) * kRadianToDegree;
  r.impulse_compression = q.pc * impulse_unit;
  r.impulse_total = q.pt * impulse_unit;
  r.work_compression = q.wc * work_unit;
  r.work_total = q.wt * work_unit;
  r.transition_count = 0;
  r.rhs_evaluations = 0;

  // Slipping at the start unless the incoming slip is zero and a stick holds there
  // (the exact method's choice, which prefers stick).
  {
    detail::Geometry g;
    g.s = sin_theta_;
    g.c = cos_theta_;
    const detail::Slips sl = detail::slips_of(g, {ca, sa, ox, oy, oz});
    constexpr double kZeroSlip = 1e-10;  // as the exact method
    const bool zero_i = sl.ix * sl.ix + sl.iy * sl.iy <= kZeroSlip * kZeroSlip;
    const bool zero_c = sl.cx * sl.cx + sl.cy * sl.cy <= kZeroSlip * kZeroSlip;
    detail::Modes start{false, false};
    if (zero_i || zero_c) {
      g.mu_w = params_.mu_cushion;
      g.mu_s = params_.mu_table;
      g.a = 1.0 - 2.5 * g.s;
      g.b = g.s * g.s + 2.5;
      g.d = 2.5 - g.s;
      start = starting_modes(g, sl, zero_i, zero_c);
    }
    r.cushion_slipping_at_start = !start.stick_i;
    r.table_slipping_at_start = !start.stick_c;
  }

  if (v.y > params.rigid_speed_limit) {
    r.status = ImpactStatus::rigid_limit_exceeded;
    set_rigid_limit_message(v.y, &r.message);
  }
  return true;
}

// --- Files ----------------------------------------------------------------------

std::string ImpactTable::cache_file_name(const CushionParams& params,
                                         const ImpactTableOptions& options) {
  // The hash takes the parameters to 12 digits, so that a ball of another size
  // (whose sin(theta) differs in the last bits) finds the same file; load_or_build
  // still checks that the loaded table covers the parameters.
  const double s = params.sin_theta();
  const std::string key = fmt::format(
      "v{} {:.12g} {:.12g} {:.12g} {:.12g} {:.17g} {:.17g} {} {} {} {} {}", kFormatVersion, s,
      params.mu_cushion, params.mu_table, params.restitution, options.k_max,
      options.cell_tolerance, options.alpha_nodes, options.topspin_nodes, options.sidespin_nodes,
      options.roll_alpha_nodes, options.roll_sidespin_nodes);
  const uint64_t h = fnv1a(key.data(), key.size());
  return fmt::format(
      "impact_table_v{}_s{:.6g}_mw{:.6g}_ms{:.6g}_e{:.6g}_n{}x{}x{}_r{}x{}_k{:g}_tol{:g}_{:016x}.bin",
      kFormatVersion, s, params.mu_cushion, params.mu_table, params.restitution,
      options.alpha_nodes, options.topspin_nodes, options.sidespin_nodes, options.roll_alpha_nodes,
      options.roll_sidespin_nodes, options.k_max, options.cell_tolerance, h);
}

bool ImpactTableAccess::save(const ImpactTable& t, const std::string& path) {
  if (t.empty()) return false;
  Writer out;
  // The header and checksum take well under a kilobyte; one buffer for the whole file.
  out.reserve(1024 + (t.nodes_.size() + t.roll_nodes_.size()) * sizeof(double) +
              t.cell_stencil_.size() + t.roll_stencil_.size());
  out.put_bytes(kMagic, sizeof kMagic);
  out.put(kFormatVersion);
  out.put(kEndianMark);
  const ImpactTableOptions& o = t.options_;
  for (int32_t n : {o.alpha_nodes, o.topspin_nodes, o.sidespin_nodes, o.roll_alpha_nodes,
                    o.roll_sidespin_nodes, int32_t{kStored}})
    out.put(n);
  out.put(o.k_max);
  out.put(o.cell_tolerance);
  const CushionParams& p = t.params_;
  for (double x : {p.mass, p.radius, p.cushion_height, p.mu_cushion, p.mu_table, p.restitution,
                   p.rigid_speed_limit})
    out.put(x);
  const ImpactTableError& e = t.error_;
  for (double x :
       {e.max_speed_relative, e.max_angle_deg, e.max_state_relative, e.max_impulse_relative})
    out.put(x);
  for (int64_t n : {e.cells, e.fallback_cells, e.roll_cells, e.roll_fallback_cells, e.test_points})
    out.put(n);
  for (size_t n :
       {t.nodes_.size(), t.cell_stencil_.size(), t.roll_nodes_.size(), t.roll_stencil_.size()})
    out.put(static_cast<uint64_t>(n));
  out.put_bytes(t.nodes_.data(), t.nodes_.size() * sizeof(double));
  out.put_bytes(t.cell_stencil_.data(), t.cell_stencil_.size());
  out.put_bytes(t.roll_nodes_.data(), t.roll_nodes_.size() * sizeof(double));
  out.put_bytes(t.roll_stencil_.data(), t.roll_stencil_.size());
  const uint64_t checksum = fnv1a(out.bytes().data(), out.bytes().size());
  out.put(checksum);

  // Write beside the target, then rename over it: readers never see a partial file.
  std::random_device random;
  const std::string temp = path + ".tmp" + std::to_string(random()) + std::to_string(random());
  std::error_code ec;
  {
    std::ofstream file(temp, std::ios::binary | std::ios::trunc);
    if (!file) return false;
    file.write(out.bytes().data(), static_cast<std::streamsize>(out.bytes().size()));
    file.close();
    if (!file) {
      std::filesystem::remove(temp, ec);
      return false;
    }
  }
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    return false;
  }
  return true;
}

std::optional<ImpactTable> ImpactTableAccess::load(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(file)),
                                std::istreambuf_iterator<char>());
  if (bytes.size() < sizeof(uint64_t)) return std::nullopt;

  // The checksum covers everything before it.
  const size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t checksum;
  std::memcpy(&checksum, bytes.data() + body, sizeof checksum);
  if (checksum != fnv1a(bytes.data(), body)) return std::nullopt;

  Reader in(bytes, body);
  char magic[sizeof kMagic];
  uint32_t version = 0, endian = 0;
  if (!in.get_bytes(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    return std::nullopt;
  if (!in.get(&version) || version != kFormatVersion) return std::nullopt;
  if (!in.get(&endian) || endian != kEndianMark) return std::nullopt;

  ImpactTable t;
  ImpactTableOptions& o = t.options_;
  int32_t stored = 0;
  if (!in.get(&o.alpha_nodes) || !in.get(&o.topspin_nodes) || !in.get(&o.sidespin_nodes) ||
      !in.get(&o.roll_alpha_nodes) || !in.get(&o.roll_sidespin_nodes) || !in.get(&stored) ||
      stored != kStored || !in.get(&o.k_max) || !in.get(&o.cell_tolerance))
    return std::nullopt;
  o.threads = 0;
  CushionParams& p = t.params_;
  for (double* x : {&p.mass, &p.radius, &p.cushion_height, &p.mu_cushion, &p.mu_table,
                    &p.restitution, &p.rigid_speed_limit})
    if (!in.get(x)) return std::nullopt;
  ImpactTableError& e = t.error_;
  for (double* x :
       {&e.max_speed_relative, &e.max_angle_deg, &e.max_state_relative, &e.max_impulse_relative})
    if (!in.get(x)) return std::nullopt;
  for (int64_t* n :
       {&e.cells, &e.fallback_cells, &e.roll_cells, &e.roll_fallback_cells, &e.test_points})
    if (!in.get(n)) return std::nullopt;
  if (o.validate() || p.validate()) return std::nullopt;
  lay_out(&t);

  // Sizes must be the ones these options lay out, and fill the file exactly.
  const uint64_t cells =
      static_cast<uint64_t>(o.alpha_nodes - 1) * (o.topspin_nodes - 1) * (o.sidespin_nodes - 1);
  const uint64_t roll_nodes = t.has_roll_plane_ ? static_cast<uint64_t>(o.roll_alpha_nodes) *
                                                      o.roll_sidespin_nodes * kStored
                                                : 0;
  const uint64_t roll_cells = t.has_roll_plane_ ? static_cast<uint64_t>(o.roll_alpha_nodes - 1) *
                                                      (o.roll_sidespin_nodes - 1)
                                                : 0;
  const uint64_t expected[4] = {
      static_cast<uint64_t>(o.alpha_nodes) * o.topspin_nodes * o.sidespin_nodes * kStored, cells,
      roll_nodes, roll_cells};
  uint64_t sizes[4];
  for (int i = 0; i < 4; ++i)
    if (!in.get(&sizes[i]) || sizes[i] != expected[i]) return std::nullopt;
  if (in.remaining() != (sizes[0] + sizes[2]) * sizeof(double) + sizes[1] + sizes[3])
    return std::nullopt;
  assign_nodes(&t.nodes_, sizes[0], 0.0);
  t.cell_stencil_.resize(sizes[1]);
  assign_nodes(&t.roll_nodes_, sizes[2], 0.0);
  t.roll_stencil_.resize(sizes[3]);
  if (!in.get_bytes(t.nodes_.data(), sizes[0] * sizeof(double)) ||
      !in.get_bytes(t.cell_stencil_.data(), sizes[1]) ||
      !in.get_bytes(t.roll_nodes_.data(), sizes[2] * sizeof(double)) ||
      !in.get_bytes(t.roll_stencil_.data(), sizes[3]))
    return std::nullopt;
  for (const std::vector<uint8_t>* codes : {&t.cell_stencil_, &t.roll_stencil_})
    for (uint8_t s : *codes)
      if (s >= kStencils && s != kFallback) return std::nullopt;
  return t;
}

bool ImpactTable::save(const std::string& path) const {
  return ImpactTableAccess::save(*this, path);
}

std::optional<ImpactTable> ImpactTable::load(const std::string& path) {
  return ImpactTableAccess::load(path);
}

bool ImpactTable::built_with(const ImpactTableOptions& options) const {
  return ImpactTableAccess::same_shape(options_, options);
}

}  // namespace cueplan::physics
