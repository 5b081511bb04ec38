#include "app/decompose_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <deque>
#include <memory>
#include <thread>

#include "drivers/sim_machine.h"
#include "rt/rt_kernel.h"

namespace lcnc::app {
namespace {

using decompose::KinematicsTable;
using dxf::Vec2;

// Picture samples kept at most (the run's periods are thinned to these).
constexpr std::size_t kCurveSamples = 6000;

// One period's targets of both groups.
struct Target {
  Vec2 main, aux;  // mm: machine coordinates of X, Y; stage coordinates of P, Q
  Vec2 beam;       // mm: where the contour's beam is at this instant (cutting)
  bool laser = false;
};

// Rest-to-rest along a straight line at v, a: the distance covered at t.
struct Trapezoid {
  double d = 0, v = 0, a = 0, t_acc = 0, t_total = 0;
  Trapezoid(double dist, double vmax, double amax) : d(dist), v(vmax), a(amax) {
    if (d <= 0.0) return;
    if (d <= v * v / a) {  // triangle
      t_acc = std::sqrt(d / a);
      v = a * t_acc;
      t_total = 2.0 * t_acc;
    } else {
      t_acc = v / a;
      t_total = d / v + t_acc;
    }
  }
  [[nodiscard]] double at(double t) const {
    if (t >= t_total) return d;
    if (t <= t_acc) return 0.5 * a * t * t;
    if (t <= t_total - t_acc) return 0.5 * a * t_acc * t_acc + v * (t - t_acc);
    const double r = t_total - t;
    return d - 0.5 * a * r * r;
  }
};

struct GroupLimits {
  double v = 0, a = 0;
};
GroupLimits limits_of(const MachineConfig& m) {
  const AxisConfig& x = m.axis(Axis::X);
  const AxisConfig& y = m.axis(Axis::Y);
  return {std::min(x.max_velocity, y.max_velocity), std::min(x.max_acceleration, y.max_acceleration)};
}

// Both groups from where they stand to (main_to, aux_to), each on its own
// trapezoid; the one done first waits. Laser off.
void traverse(std::vector<Target>& out, double T, Vec2& main, Vec2& aux, const Vec2& main_to,
              const Vec2& aux_to, const GroupLimits& lm, const GroupLimits& la) {
  const Trapezoid pm((main_to - main).norm(), lm.v, lm.a);
  const Trapezoid pa((aux_to - aux).norm(), la.v, la.a);
  const double t_end = std::max(pm.t_total, pa.t_total);
  if (t_end <= 0.0) return;
  const Vec2 dm = pm.d > 0 ? Vec2((main_to - main) / pm.d) : Vec2(0, 0);
  const Vec2 da = pa.d > 0 ? Vec2((aux_to - aux) / pa.d) : Vec2(0, 0);
  const auto periods = static_cast<std::size_t>(std::ceil(t_end / T));
  for (std::size_t k = 1; k <= periods; ++k) {
    const double t = static_cast<double>(k) * T;
    Target g;
    g.main = k == periods ? main_to : Vec2(main + dm * pm.at(t));
    g.aux = k == periods ? aux_to : Vec2(aux + da * pa.at(t));
    g.beam = g.main + g.aux;
    out.push_back(g);
  }
  main = main_to;
  aux = aux_to;
}

// A contour's table sampled at the periods' end times (linear between rows,
// as the table's motion is).
void cut(std::vector<Target>& out, double T, const KinematicsTable& tab, const Vec2& origin) {
  const double t_end = tab.t_s.back();
  const auto periods = static_cast<std::size_t>(std::ceil(t_end / T));
  std::size_t row = 0;
  Vec2 last_beam = tab.beam.front();
  for (std::size_t k = 1; k <= periods; ++k) {
    const double t = std::min(static_cast<double>(k) * T, t_end);
    while (row + 1 < tab.size() && tab.t_s[row + 1] < t) ++row;
    const std::size_t r1 = std::min(row + 1, tab.size() - 1);
    const double span = tab.t_s[r1] - tab.t_s[row];
    const double f = span > 0.0 ? std::clamp((t - tab.t_s[row]) / span, 0.0, 1.0) : 1.0;
    Target g;
    const Vec2 m = tab.main[row] + f * (tab.main[r1] - tab.main[row]);
    const Vec2 b = tab.beam[row] + f * (tab.beam[r1] - tab.beam[row]);
    g.main = origin + m;
    g.aux = b - m;
    g.beam = origin + b;
    g.laser = (b - last_beam).norm() > 1e-9;  // the beam moves: cutting
    last_beam = b;
    out.push_back(g);
  }
}

Status within_travel(const MachineConfig& m, const Vec2& p, const char* group,
                     const std::array<char, 2>& letters, const std::string& where) {
  for (int i = 0; i < 2; ++i) {
    const AxisConfig& ax = m.axes[i];
    const double v = p[i];
    if (v < ax.min - 1e-9 || v > ax.max + 1e-9) {
      char msg[320];
      std::snprintf(msg, sizeof msg, "%s: the %s axes reach %c = %.4f mm, outside the travel %g … %g mm%s",
                    where.c_str(), group, letters[i], v, ax.min, ax.max,
                    group[0] == 'm' ? " (move the part's origin)" : " (lower the field)");
      return make_error(ErrorCode::DecomposeBeyondTravel, msg);
    }
  }
  return {};
}

std::int64_t steps(double mm, double spu) { return std::llround(mm * spu); }

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// One axis group: its kernel, buffer, drives and trace.
struct Group {
  const MachineConfig& m;
  std::array<std::int64_t, kAxisCount> start{};
  std::unique_ptr<rt::PositionBuffer> buffer = std::make_unique<rt::PositionBuffer>();
  std::unique_ptr<rt::TraceRing> trace = std::make_unique<rt::TraceRing>();
  std::unique_ptr<drivers::SimMachine> sim;
  std::unique_ptr<rt::RtKernel> kernel;
  std::vector<PeriodIncrement> entries;
  std::size_t pushed = 0;
  std::deque<rt::TraceRecord> records;

  Group(const MachineConfig& machine, const Vec2& at) : m(machine) {
    for (int i = 0; i < 2; ++i) start[i] = steps(at[i], m.axes[i].steps_per_unit);
    sim = std::make_unique<drivers::SimMachine>(start, drivers::wired_switches(m));
    kernel = std::make_unique<rt::RtKernel>(m, *buffer, *sim, trace.get(), start);
  }
  void quantize(const std::vector<Target>& targets, bool main_group) {
    entries.resize(targets.size());
    std::array<std::int64_t, 2> at{start[0], start[1]};
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const Vec2& p = main_group ? targets[k].main : targets[k].aux;
      PeriodIncrement& e = entries[k];
      for (int i = 0; i < 2; ++i) {
        const std::int64_t s = steps(p[i], m.axes[i].steps_per_unit);
        e.steps[i] = static_cast<std::int32_t>(s - at[i]);
        at[i] = s;
      }
      e.power_pct = main_group && targets[k].laser ? 100.0f : 0.0f;
      e.segment = static_cast<std::uint32_t>(k);
    }
    if (!entries.empty()) entries.back().end_of_program = true;
  }
  [[nodiscard]] std::array<std::int64_t, 2> commanded() const {
    std::array<std::int64_t, 2> c{start[0], start[1]};
    for (const PeriodIncrement& e : entries)
      for (int i = 0; i < 2; ++i) c[i] += e.steps[i];
    return c;
  }
  void feed() {
    while (pushed < entries.size() && buffer->try_push(entries[pushed])) ++pushed;
    if (pushed == entries.size()) kernel->stream_end();
  }
  void drain() {
    rt::TraceRecord r;
    while (trace->try_pop(r)) records.push_back(r);
  }
  [[nodiscard]] Vec2 mm(const rt::TraceRecord& r) const {
    return Vec2(static_cast<double>(r.pos_steps[0]) / m.axes[0].steps_per_unit,
                static_cast<double>(r.pos_steps[1]) / m.axes[1].steps_per_unit);
  }
};

// Peak speed and acceleration of one group from its executed positions,
// over windows (see the header).
struct PeakMeter {
  double T;
  std::deque<std::pair<Vec2, bool>> hist;  // position, laser on
  double v = 0, a = 0, v_cut = 0, a_cut = 0;
  explicit PeakMeter(double period_s) : T(period_s) {}
  void add(const Vec2& p, bool cutting) {
    hist.emplace_back(p, cutting);
    if (hist.size() > 2 * kAccelWindow + 1) hist.pop_front();
    const std::size_t n = hist.size();
    if (n > kSpeedWindow) {
      const double vn = (hist[n - 1].first - hist[n - 1 - kSpeedWindow].first).norm() / (kSpeedWindow * T);
      v = std::max(v, vn);
      if (hist[n - 1].second && hist[n - 1 - kSpeedWindow].second) v_cut = std::max(v_cut, vn);
    }
    if (n == 2 * kAccelWindow + 1) {
      const double w = kAccelWindow * T;
      const double an = (hist[n - 1].first - 2.0 * hist[kAccelWindow].first + hist[0].first).norm() / (w * w);
      a = std::max(a, an);
      if (hist[0].second && hist[n - 1].second) a_cut = std::max(a_cut, an);
    }
  }
};

}  // namespace

Result<decompose::Options> group_limits(const MachineConfig& main, const MachineConfig& aux,
                                        decompose::Options opt) {
  for (const MachineConfig* m : {&main, &aux}) {
    if (!m->axis(Axis::X).present || !m->axis(Axis::Y).present)
      return make_error(ErrorCode::DecomposeBadOption,
                        "machine '" + m->name + "' has no X and Y axes for an axis group");
  }
  const GroupLimits lm = limits_of(main), la = limits_of(aux);
  opt.main_speed_mm_s = lm.v;
  opt.main_accel_mm_s2 = lm.a;
  opt.aux_speed_mm_s = la.v;
  double half = 1e300;
  for (Axis a : {Axis::X, Axis::Y}) half = std::min({half, -aux.axis(a).min, aux.axis(a).max});
  if (!(half > 0.0))
    return make_error(ErrorCode::DecomposeBadOption,
                      "the auxiliary stage '" + aux.name + "': its travel must contain its centre 0");
  opt.aux_half_field_mm = std::min(opt.aux_half_field_mm, half);
  return opt;
}

Result<DecomposeRunReport> run_decomposition(const decompose::PartResult& part, const MachineConfig& main,
                                             const MachineConfig& aux, const DecomposeRunOptions& options) {
  if (main.period_ns != aux.period_ns) {
    return make_error(ErrorCode::DecomposeBadOption,
                      "the axis groups need one period: main " + std::to_string(main.period_ns / 1000) +
                          " µs, auxiliary " + std::to_string(aux.period_ns / 1000) + " µs");
  }
  if (part.contours.empty()) return make_error(ErrorCode::DecomposeBadOption, "the part has no contour");
  const double T = main.period_s();
  const GroupLimits lm = limits_of(main), la = limits_of(aux);
  const Vec2 origin(options.origin_x_mm, options.origin_y_mm);
  DecomposeRunReport rep;
  rep.main.name = "main";
  rep.main.letters = {'X', 'Y'};
  rep.aux.name = "aux";
  rep.aux.letters = {'P', 'Q'};
  rep.main.speed_limit = lm.v;
  rep.main.accel_limit = lm.a;
  rep.aux.speed_limit = la.v;
  rep.aux.accel_limit = la.a;

  // The periods the run will take, counted (traverses and cuts as below)
  // before any is computed.
  {
    double periods = 0.0;
    Vec2 m_at = origin, a_at(0, 0);
    auto traverse_periods = [&](const Vec2& m_to, const Vec2& a_to) {
      const double t = std::max(Trapezoid((m_to - m_at).norm(), lm.v, lm.a).t_total,
                                Trapezoid((a_to - a_at).norm(), la.v, la.a).t_total);
      periods += std::ceil(t / T);
      m_at = m_to;
      a_at = a_to;
    };
    for (const decompose::ContourResult& c : part.contours) {
      const KinematicsTable& tab = c.table;
      if (tab.size() < 2) continue;
      traverse_periods(origin + tab.main.front(), tab.aux(0));
      periods += std::ceil(tab.t_s.back() / T);
      m_at = origin + tab.main.back();
      a_at = tab.aux(tab.size() - 1);
    }
    traverse_periods(m_at, Vec2(0, 0));
    if (!(periods <= static_cast<double>(kMaxRunPeriods))) {
      char msg[320];
      std::snprintf(msg, sizeof msg,
                    "the run would take %.0f periods (%.1f s of machine time at %.0f us), more "
                    "than the %llu allowed (%.0f s); expected a faster contour speed or a "
                    "smaller part",
                    periods, periods * T, T * 1e6, static_cast<unsigned long long>(kMaxRunPeriods),
                    static_cast<double>(kMaxRunPeriods) * T);
      return make_error(ErrorCode::DecomposeTooLarge, msg);
    }
  }

  // The targets of every period, checked against both groups' travel.
  std::vector<Target> targets;
  Vec2 main_at = origin, aux_at(0, 0);
  if (Status s = within_travel(main, main_at, "main", rep.main.letters, "the part's origin"); !s)
    return s.error();
  for (const decompose::ContourResult& c : part.contours) {
    const KinematicsTable& tab = c.table;
    if (tab.size() < 2) continue;
    for (std::size_t i = 0; i < tab.size(); ++i) {
      const std::string where = c.contour.name() + " at (" + std::to_string(tab.beam[i].x()) + ", " +
                                std::to_string(tab.beam[i].y()) + ")";
      if (Status s = within_travel(main, origin + tab.main[i], "main", rep.main.letters, where); !s)
        return s.error();
      if (Status s = within_travel(aux, tab.aux(i), "auxiliary", rep.aux.letters, where); !s)
        return s.error();
    }
    traverse(targets, T, main_at, aux_at, origin + tab.main.front(), tab.aux(0), lm, la);
    cut(targets, T, tab, origin);
    main_at = origin + tab.main.back();
    aux_at = tab.aux(tab.size() - 1);
  }
  traverse(targets, T, main_at, aux_at, main_at, Vec2(0, 0), lm, la);
  rep.periods = targets.size();

  Group gm(main, origin), ga(aux, Vec2(0, 0));
  gm.quantize(targets, true);
  ga.quantize(targets, false);
  const std::array<std::int64_t, 2> cm = gm.commanded(), ca = ga.commanded();
  // The entries stream in from this thread: a kernel whose buffer runs low
  // slows along the path on the wall clock, and waits on the simulated one.
  gm.kernel->stream_begin();
  ga.kernel->stream_begin();
  gm.feed();
  ga.feed();
  rt::RtOptions o;
  o.try_realtime = options.realtime && options.clock == rt::RtClock::Wall;
  o.clock = options.clock;
  o.epoch_ns = now_ns() + 5'000'000;  // both start on the same period boundary
  gm.kernel->start(o);
  ga.kernel->start(o);
  rep.warning = gm.kernel->warning();

  PeakMeter pm(T), pa(T);
  const std::size_t every = std::max<std::size_t>(1, targets.size() / kCurveSamples);
  const auto analyse = [&] {
    while (!gm.records.empty() && !ga.records.empty()) {
      const rt::TraceRecord rm = gm.records.front(), ra = ga.records.front();
      if (rm.period != ra.period) {  // a trace dropped records: realign
        (rm.period < ra.period ? gm.records : ga.records).pop_front();
        continue;
      }
      gm.records.pop_front();
      ga.records.pop_front();
      ++rep.traced_periods;
      const Vec2 xm = gm.mm(rm), xa = ga.mm(ra);
      const bool on = rm.power_pct > 0.0f;
      pm.add(xm, on);
      pa.add(xa, on);
      const std::size_t k = rm.segment;  // the entry the period executed
      if (k < targets.size() && on) {
        rep.beam_deviation_mm = std::max(rep.beam_deviation_mm, (xm + xa - targets[k].beam).norm());
        rep.cutting_time_s += T;
      }
      if (k % every == 0) rep.curves.add(static_cast<double>(rm.t_ns) * 1e-9, xm, xa, on);
    }
  };
  while (!(gm.kernel->finished() && ga.kernel->finished())) {
    gm.feed();
    ga.feed();
    gm.drain();
    ga.drain();
    analyse();
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  gm.kernel->join();
  ga.kernel->join();
  gm.drain();
  ga.drain();
  analyse();

  rep.cycle_time_s = static_cast<double>(gm.kernel->machine_time_ns()) * 1e-9;
  for (int i = 0; i < 2; ++i) {
    rep.main.steps_sent[i] = gm.sim->position_steps(i);
    rep.aux.steps_sent[i] = ga.sim->position_steps(i);
  }
  rep.main.steps_commanded = cm;
  rep.aux.steps_commanded = ca;
  for (GroupReport* g : {&rep.main, &rep.aux}) {
    const MachineConfig& m = g == &rep.main ? main : aux;
    const double step = 1.0 / std::min(m.axes[0].steps_per_unit, m.axes[1].steps_per_unit);
    const double w = kAccelWindow * T;
    g->speed_resolution = std::sqrt(2.0) * step / (kSpeedWindow * T);
    g->accel_resolution = 2.0 * std::sqrt(2.0) * step / (w * w);
  }
  rep.main.peak_speed = pm.v;
  rep.main.peak_accel = pm.a;
  rep.main.cutting_speed = pm.v_cut;
  rep.main.cutting_accel = pm.a_cut;
  rep.aux.peak_speed = pa.v;
  rep.aux.peak_accel = pa.a;
  rep.aux.cutting_speed = pa.v_cut;
  rep.aux.cutting_accel = pa.a_cut;
  rep.main.underruns = gm.kernel->underruns();
  rep.aux.underruns = ga.kernel->underruns();
  rep.main.latency_p999_us = gm.kernel->latency().quantile_us(0.999);
  rep.aux.latency_p999_us = ga.kernel->latency().quantile_us(0.999);
  rep.main.latency_max_us = static_cast<double>(gm.kernel->latency().max_ns()) * 1e-3;
  rep.aux.latency_max_us = static_cast<double>(ga.kernel->latency().max_ns()) * 1e-3;
  rep.main.fault = gm.kernel->fault().active;
  rep.aux.fault = ga.kernel->fault().active;
  return rep;
}

}  // namespace lcnc::app
