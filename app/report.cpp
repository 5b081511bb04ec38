// The run report, as text for people and as one JSON object for programs.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "app/json_text.h"
#include "app/run_job.h"

namespace lcnc::app {
namespace {

std::string printf_string(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace

std::string format_report(const RunReport& r) {
  std::string s;
  s += "LaserCNC run report (simulated machine)\n";
  s += printf_string("  program          %s (%u %s, %llu segments)\n", r.program.c_str(), r.lines,
                     r.line_unit.c_str(), static_cast<unsigned long long>(r.segments));
  s += printf_string("  machine          %s, RT period %.1f us\n", r.machine.c_str(), r.period_s * 1e6);
  s += printf_string("  feed override    %.1f %% (a period lasts %.1f us)\n", r.feed_override * 100.0,
                     r.feed_override > 0.0 ? r.period_s * 1e6 / r.feed_override : 0.0);
  s += printf_string("  cycle time       %.6f s (%llu periods)\n", r.cycle_time_s,
                     static_cast<unsigned long long>(r.periods));
  s += printf_string("  path length      %.3f mm (%.3f mm at feed)\n", r.path_length_mm, r.feed_length_mm);
  s += printf_string("  max deviation    %.4f mm (executed vs programmed path)\n", r.max_deviation_mm);
  s += printf_string("  laser on         %.4f s\n", r.laser_on_s);
  s += "  axis  peak velocity     peak acceleration      steps sent   steps commanded\n";
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisReport& a = r.axes[i];
    if (!a.present) continue;
    const bool rot = is_rotary(static_cast<Axis>(i));
    s += printf_string("  %c     %10.3f %-6s %12.1f %-7s %12lld %14lld %s\n", kAxisLetters[i],
                       a.peak_velocity, rot ? "deg/s" : "mm/s", a.peak_acceleration, rot ? "deg/s2" : "mm/s2",
                       static_cast<long long>(a.steps_sent), static_cast<long long>(a.steps_commanded),
                       a.steps_sent == a.steps_commanded ? "=" : "MISMATCH");
  }
  const double window_ms = r.period_s * 1e3;
  s += printf_string(
      "  measured from the RT trace: velocity over %d periods (%.2f ms), "
      "acceleration over %d (%.2f ms)\n",
      r.velocity_window, r.velocity_window * window_ms, r.acceleration_window,
      r.acceleration_window * window_ms);
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisReport& a = r.axes[i];
    if (!a.present) continue;
    const bool rot = is_rotary(static_cast<Axis>(i));
    s += printf_string("  %c     %10.3f %-6s %12.1f %-7s   limits %g %s, %g %s\n", kAxisLetters[i],
                       a.measured_velocity, rot ? "deg/s" : "mm/s", a.measured_acceleration,
                       rot ? "deg/s2" : "mm/s2", a.velocity_limit, rot ? "deg/s" : "mm/s",
                       a.acceleration_limit, rot ? "deg/s2" : "mm/s2");
  }
  s += printf_string("  steps            %s\n", r.steps_match ? "sent = commanded on every axis"
                                                              : "MISMATCH between sent and commanded");
  s += printf_string(
      "  underruns        %llu   overruns %llu   trace drops %llu   bad frames %llu\n",
      static_cast<unsigned long long>(r.underruns), static_cast<unsigned long long>(r.overruns),
      static_cast<unsigned long long>(r.trace_drops), static_cast<unsigned long long>(r.bad_frames));
  if (r.starvations > 0)
    s += printf_string("  planner behind   %llu times: decelerated along the path to refill the buffer\n",
                       static_cast<unsigned long long>(r.starvations));
  if (!r.fault.empty()) s += "  FAULT            " + r.fault + " (stopped before the end)\n";
  if (r.breaches.empty()) {
    s += "  check            passed: every axis within its limits, the path within its tolerance\n";
  } else {
    for (const std::string& b : r.breaches) s += "  CHECK FAILED     " + b + "\n";
  }
  if (r.trace_drops > 0)  // the reader starved of the CPU; every entry still passed the guard
    s += "  warning          the RT trace lost records: those periods were held to the increment "
         "guard only, not measured\n";
  if (rt::is_simulated(r.clock)) {
    s += printf_string(
        "  clock            simulated: %.3f s of machine time run in %.3f s (x%.0f), "
        "RT latency not measured\n",
        r.cycle_time_s, r.wall_time_s, r.wall_time_s > 0.0 ? r.cycle_time_s / r.wall_time_s : 0.0);
  } else {
    s += printf_string("  RT latency       p50 %.0f us, p99 %.0f us, max %.1f us (%s)\n", r.latency_p50_us,
                       r.latency_p99_us, r.latency_max_us, r.schedule.c_str());
    if (!r.rt_warning.empty()) s += "  warning          " + r.rt_warning + "\n";
  }
  for (const std::string& w : r.program_warnings) s += "  warning          " + w + "\n";
  if (r.program_pauses > 0)
    s += printf_string("  program pauses   %u (M0/M1/M60), each resumed after --pause\n", r.program_pauses);
  const PeripheralReport& p = r.peripherals;
  if (p.used) {
    s += "  laser source     " + p.laser + (p.simulated ? " (simulator)" : "") + "\n";
    s += printf_string("                   rated %.1f W, %llu setpoint updates, peak pump %.1f C, alarm %s\n",
                       p.rated_power_w, static_cast<unsigned long long>(p.setpoint_writes),
                       p.peak_temperature_c, p.alarm.empty() ? "none" : p.alarm.c_str());
    if (!p.meter.empty()) {
      s += "  power meter      " + p.meter + (p.simulated ? " (simulator)" : "") + "\n";
      s += printf_string(
          "                   %llu readings; while lasing mean %.2f W measured, %.2f W commanded; peak %.2f "
          "W\n",
          static_cast<unsigned long long>(p.meter_samples), p.meter_mean_lasing_w, p.commanded_mean_lasing_w,
          p.meter_peak_w);
    }
    s += printf_string("  Modbus           %llu requests, %llu failed%s%s\n",
                       static_cast<unsigned long long>(p.requests), static_cast<unsigned long long>(p.failed),
                       p.error.empty() ? "" : ": ", p.error.c_str());
  }
  return s;
}

std::string report_json(const RunReport& r) {
  nlohmann::json j;
  j["program"] = r.program;
  j["machine"] = r.machine;
  j["lines"] = r.lines;
  j["line_unit"] = r.line_unit;
  j["segments"] = r.segments;
  j["period_s"] = r.period_s;
  j["periods"] = r.periods;
  j["cycle_time_s"] = r.cycle_time_s;
  j["feed_override"] = r.feed_override;
  j["path_length_mm"] = r.path_length_mm;
  j["feed_length_mm"] = r.feed_length_mm;
  j["max_deviation_mm"] = r.max_deviation_mm;
  j["laser_on_s"] = r.laser_on_s;
  nlohmann::json axes = nlohmann::json::object();
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisReport& a = r.axes[i];
    if (!a.present) continue;
    axes[std::string(1, kAxisLetters[i])] = {
        {"peak_velocity", a.peak_velocity},
        {"peak_acceleration", a.peak_acceleration},
        {"steps_sent", a.steps_sent},
        {"steps_commanded", a.steps_commanded},
        {"measured_velocity", a.measured_velocity},
        {"measured_acceleration", a.measured_acceleration},
        {"velocity_limit", a.velocity_limit},
        {"acceleration_limit", a.acceleration_limit},
    };
  }
  j["axes"] = axes;
  j["steps_match"] = r.steps_match;
  j["underruns"] = r.underruns;
  j["starvations"] = r.starvations;
  j["fault"] = r.fault;
  j["check"] = {{"passed", r.breaches.empty()},
                {"breaches", r.breaches},
                {"velocity_window_periods", r.velocity_window},
                {"acceleration_window_periods", r.acceleration_window}};
  j["succeeded"] = run_succeeded(r);
  j["overruns"] = r.overruns;
  j["trace_drops"] = r.trace_drops;
  j["bad_frames"] = r.bad_frames;
  j["latency_us"] = {{"p50", r.latency_p50_us}, {"p99", r.latency_p99_us}, {"max", r.latency_max_us}};
  j["schedule"] = r.schedule;
  j["clock"] = rt::is_simulated(r.clock) ? "simulated" : "wall";
  j["wall_time_s"] = r.wall_time_s;
  j["rt_warning"] = r.rt_warning;
  j["program_warnings"] = r.program_warnings;
  j["program_pauses"] = r.program_pauses;
  if (const PeripheralReport& p = r.peripherals; p.used) {
    j["peripherals"] = {
        {"laser", p.laser},
        {"power_meter", p.meter},
        {"simulated", p.simulated},
        {"rated_power_w", p.rated_power_w},
        {"setpoint_writes", p.setpoint_writes},
        {"peak_temperature_c", p.peak_temperature_c},
        {"alarm", p.alarm},
        {"meter_samples", p.meter_samples},
        {"meter_mean_lasing_w", p.meter_mean_lasing_w},
        {"commanded_mean_lasing_w", p.commanded_mean_lasing_w},
        {"meter_peak_w", p.meter_peak_w},
        {"modbus_requests", p.requests},
        {"modbus_failed", p.failed},
        {"error", p.error},
    };
  }
  return json_text(j);
}

}  // namespace lcnc::app
