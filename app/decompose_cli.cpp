#include "app/decompose_cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "app/cli_values.h"
#include "app/decompose_run.h"
#include "app/machine_files.h"
#include "app/output_set.h"
#include "app/run_job.h"
#include "decompose/decompose_svg.h"
#include "decompose/part_decomposition.h"
#include "dxf/dxf_reader.h"

namespace lcnc::app {
namespace {

using decompose::kG_mm_s2;

constexpr const char* kDecomposeUsage =
    "usage: lasercnc decompose PART.dxf [--speed V] [--step MM] [--mode sync|seed]\n"
    "                          [--main-accel A] [--main-speed V] [--aux-speed V] [--field MM]\n"
    "                          [--goal smooth|short] [--critical-angle DEG]\n"
    "                          [--units auto|mm|cm|m|inch]\n"
    "                          [--csv FILE] [--svg FILE] [--accel-svg FILE]\n"
    "                          [--run [--machine FILE] [--aux-machine FILE] [--origin X,Y]\n"
    "                           [--run-svg FILE] [--fast | --no-realtime]]\n"
    "\n"
    "  Splits every contour of the drawing into a smooth main-axis path S1 (X, Y) and\n"
    "  an auxiliary path S2 = S - S1 (P, Q) whose sum is the contour S.\n"
    "  --speed       contour speed (default 6m/min)\n"
    "  --step        discretization step, mm, >= 0.001 (default 0.01)\n"
    "  --mode        sync: S1(t) + S2(t) = S(t) at constant speed, limits guaranteed\n"
    "                (default); seed: the published algorithm (Kondratenko, Tretiyakova\n"
    "                and Shevchenko 2015, eq. 1-13; docs/design.md 5.7), limits only\n"
    "                reported\n"
    "  --main-accel  main-axis acceleration limit (default 0.5g)\n"
    "  --main-speed  main-axis speed limit (default 40m/min)\n"
    "  --aux-speed   auxiliary speed limit (default 300m/min)\n"
    "  --field       auxiliary field, full width of the square, mm (default 10)\n"
    "  --goal        sync mode: smooth = the smoothest main path the field allows\n"
    "                (default); short = the least main-axis motion before and after\n"
    "                each contour (main acceleration up to its limit)\n"
    "  --critical-angle  seed mode: largest turn kept at a vertex, deg (default 1)\n"
    "  --units       drawing units (default auto: $INSUNITS, unitless read as mm)\n"
    "  --csv         kinematics table: contour,i,x,y,p,q,t,v/a of main and aux, a_eff, S\n"
    "  --svg         picture: S green, S1 blue, S2 red in its field\n"
    "  --accel-svg   effective and main-axis acceleration over time\n"
    "  --run         cut the part on the simulated machine: main axes X, Y (--machine,\n"
    "                default share/machines/default.toml) and auxiliary P, Q (--aux-machine,\n"
    "                default share/machines/aux_stage.toml) as two axis groups on one\n"
    "                period; the limits and field come from the groups' configs unless\n"
    "                given; --origin: where the part's 0,0 is on X, Y (default 0,0)\n"
    "  --run-svg     the run's axis curves X, Y, P, Q over time\n"
    "  --fast        the run on the simulated clock, as `lasercnc run --fast`\n"
    "  Speeds take mm/s (default unit), mm/min, m/min, m/s; accelerations mm/s2\n"
    "  (default), m/s2, g.\n";

int decompose_usage_error(const std::string& msg) {
  return lcnc::app::usage_error("lasercnc decompose", msg, kDecomposeUsage);
}

// "6m/min" → 100 (mm/s). Units: mm/s (bare), mm/min, m/min, m/s.
std::optional<double> parse_speed(std::string_view s) {
  const auto q = parse_quantity(s);
  if (!q) return std::nullopt;
  const auto& [v, unit] = *q;
  if (unit.empty() || unit == "mm/s") return v;
  if (unit == "mm/min") return v / 60.0;
  if (unit == "m/min") return v * 1000.0 / 60.0;
  if (unit == "m/s") return v * 1000.0;
  return std::nullopt;
}

// "0.5g" → 4903.3 (mm/s²). Units: mm/s2 (bare), m/s2, g.
std::optional<double> parse_accel(std::string_view s) {
  const auto q = parse_quantity(s);
  if (!q) return std::nullopt;
  const auto& [v, unit] = *q;
  if (unit.empty() || unit == "mm/s2" || unit == "mm/s^2") return v;
  if (unit == "m/s2" || unit == "m/s^2") return v * 1000.0;
  if (unit == "g") return v * kG_mm_s2;
  return std::nullopt;
}

// `simulated`: the run was on the simulated clock, which measures no wake-up.
void print_group(const GroupReport& g, bool simulated) {
  const bool exact = g.steps_sent == g.steps_commanded;
  std::printf(
      "  %-4s %c %lld / %lld, %c %lld / %lld steps sent / commanded%s; %llu underruns%s\n"
      "       peak %.1f mm/s (limit %.1f, +-%.1f quantization), %.1f mm/s2 (%.3f g; limit "
      "%.1f, +-%.1f quantization); while cutting %.1f mm/s, %.1f mm/s2 (%.3f g)\n",
      g.name.c_str(), g.letters[0], static_cast<long long>(g.steps_sent[0]),
      static_cast<long long>(g.steps_commanded[0]), g.letters[1], static_cast<long long>(g.steps_sent[1]),
      static_cast<long long>(g.steps_commanded[1]), exact ? " (exact)" : " (NOT EXACT)",
      static_cast<unsigned long long>(g.underruns), g.fault ? ", FAULT" : "", g.peak_speed, g.speed_limit,
      g.speed_resolution, g.peak_accel, g.peak_accel / kG_mm_s2, g.accel_limit, g.accel_resolution,
      g.cutting_speed, g.cutting_accel, g.cutting_accel / kG_mm_s2);
  if (simulated)
    std::printf("       simulated clock: no RT wake-up measured\n");
  else
    std::printf("       RT wake-up p99.9 %.0f us, max %.0f us\n", g.latency_p999_us, g.latency_max_us);
}

// The run's outcome: nullopt when it was refused (nothing ran) or its picture
// cannot be written, else whether it passed its own checks.
std::optional<bool> run_part(const decompose::PartResult& res, const MachineConfig& main_m,
                             const MachineConfig& aux_m, const DecomposeRunOptions& run_opt,
                             const std::string& part, const std::string& svg_path, OutputSet& outputs) {
  std::printf(
      "running on the simulated machine: main X, Y ('%s'), auxiliary P, Q ('%s'), "
      "period %u us, origin %.3f, %.3f mm\n",
      main_m.name.c_str(), aux_m.name.c_str(), main_m.period_ns / 1000, run_opt.origin_x_mm,
      run_opt.origin_y_mm);
  std::fflush(stdout);
  Result<DecomposeRunReport> r = run_decomposition(res, main_m, aux_m, run_opt);
  if (!r) {
    Diagnostic e = r.error();
    if (e.file.empty()) e.file = part;
    std::fprintf(stderr, "%s\n", e.to_string().c_str());
    return std::nullopt;
  }
  if (!r->warning.empty()) std::printf("  warning: %s\n", r->warning.c_str());
  std::printf(
      "  %llu periods, cycle %.4f s, cutting %.4f s; beam X+P, Y+Q vs the contour at "
      "the same instant: max %.4f mm\n",
      static_cast<unsigned long long>(r->periods), r->cycle_time_s, r->cutting_time_s, r->beam_deviation_mm);
  const bool simulated = rt::is_simulated(run_opt.clock);
  print_group(r->main, simulated);
  print_group(r->aux, simulated);
  if (!svg_path.empty()) {
    if (!outputs.add(svg_path, [&](OutputFile& f) {
          f.write(decompose::axes_svg(r->curves, part + " — run on the simulated machine"));
        }))
      return std::nullopt;
    std::printf("axis curves: %s\n", svg_path.c_str());
  }
  // the run's own check: each group's measured speed and acceleration
  // within its limit plus what one step of quantization reads as over the
  // windows (a reading beyond that is a real breach)
  bool within = true;
  for (const GroupReport* g : {&r->main, &r->aux}) {
    if (g->peak_speed > g->speed_limit + g->speed_resolution) {
      std::printf("  CHECK FAILED     %s speed %.1f mm/s above its limit %.1f (+%.1f quantization)\n",
                  g->name.c_str(), g->peak_speed, g->speed_limit, g->speed_resolution);
      within = false;
    }
    if (g->peak_accel > g->accel_limit + g->accel_resolution) {
      std::printf(
          "  CHECK FAILED     %s acceleration %.1f mm/s2 above its limit %.1f (+%.1f "
          "quantization)\n",
          g->name.c_str(), g->peak_accel, g->accel_limit, g->accel_resolution);
      within = false;
    }
  }
  const bool ok = r->main.steps_sent == r->main.steps_commanded &&
                  r->aux.steps_sent == r->aux.steps_commanded && !r->main.fault && !r->aux.fault &&
                  r->main.underruns == 0 && r->aux.underruns == 0 && within;
  return ok;
}

}  // namespace

int decompose_main(int argc, char** argv) {
  if (argc < 2) return decompose_usage_error("missing PART.dxf");
  std::string part;
  double step_mm = 0.01;
  decompose::Options opt;
  opt.speed_mm_s = 100.0;  // 6 m/min, the paper's test case
  dxf::ReadOptions read_opt;
  std::string csv_path, svg_path, accel_svg_path, run_svg_path;
  bool run = false;
  DecomposeRunOptions run_opt;
  std::string main_file, aux_file;
  bool main_speed_given = false, main_accel_given = false, aux_speed_given = false, field_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view flag = argv[i];  // the options without a value
    if (flag == "--run") {
      run = true;
      continue;
    }
    if (flag == "--no-realtime") {
      run_opt.realtime = false;
      continue;
    }
    if (flag == "--fast") {
      run_opt.clock = rt::RtClock::Simulated;
      continue;
    }
    std::string_view a, v;
    if (const auto exit = file_or_option("lasercnc decompose", kDecomposeUsage, argc, argv, i, part, a, v))
      return *exit;
    if (a.empty()) continue;  // the drawing
    auto bad = [&](const char* expected) {
      return decompose_usage_error(std::string(a) + " " + std::string(v) + ": expected " + expected);
    };
    if (a == "--speed" || a == "--main-speed" || a == "--aux-speed") {
      const std::optional<double> s = parse_speed(v);
      if (!s || !(*s > 0.0)) return bad("a positive speed (e.g. 6m/min, 100mm/s)");
      (a == "--speed" ? opt.speed_mm_s : a == "--main-speed" ? opt.main_speed_mm_s : opt.aux_speed_mm_s) = *s;
      main_speed_given |= a == "--main-speed";
      aux_speed_given |= a == "--aux-speed";
    } else if (a == "--main-accel") {
      const std::optional<double> s = parse_accel(v);
      if (!s || !(*s > 0.0)) return bad("a positive acceleration (e.g. 0.5g, 4903mm/s2)");
      opt.main_accel_mm_s2 = *s;
      main_accel_given = true;
    } else if (a == "--step") {
      const std::optional<double> s = parse_number(v);
      if (!s || !(*s >= 0.001)) return bad("a step in mm, at least 0.001 (1 um)");
      step_mm = *s;
    } else if (a == "--field") {
      const std::optional<double> s = parse_number(v);
      if (!s || !(*s > 0.0)) return bad("the field's full width in mm, > 0");
      opt.aux_half_field_mm = *s / 2.0;
      field_given = true;
    } else if (a == "--critical-angle") {
      const std::optional<double> s = parse_number(v);
      if (!s || !(*s > 0.0 && *s < 180.0)) return bad("an angle in degrees, 0 < angle < 180");
      opt.critical_angle_deg = *s;
    } else if (a == "--mode") {
      if (v == "sync")
        opt.mode = decompose::Mode::Sync;
      else if (v == "seed")
        opt.mode = decompose::Mode::Seed;
      else
        return bad("sync or seed");
    } else if (a == "--goal") {
      if (v == "smooth")
        opt.goal = decompose::SyncGoal::SmoothestMain;
      else if (v == "short")
        opt.goal = decompose::SyncGoal::ShortestLeadIn;
      else
        return bad("smooth or short");
    } else if (a == "--units") {
      const std::optional<double> u = v == "auto" ? 0.0 : parse_unit_mm(v);
      if (!u) return bad("auto, mm, cm, m or inch");
      read_opt.unit_mm = *u;
    } else if (a == "--csv") {
      csv_path = std::string(v);
    } else if (a == "--svg") {
      svg_path = std::string(v);
    } else if (a == "--accel-svg") {
      accel_svg_path = std::string(v);
    } else if (a == "--run-svg") {
      run_svg_path = std::string(v);
    } else if (a == "--machine") {
      main_file = std::string(v);
    } else if (a == "--aux-machine") {
      aux_file = std::string(v);
    } else if (a == "--origin") {
      const auto xy = parse_xy(v);
      if (!xy) return bad("X,Y in mm (e.g. 100,50)");
      run_opt.origin_x_mm = xy->first;
      run_opt.origin_y_mm = xy->second;
    } else {
      return decompose_usage_error("unknown option " + std::string(a));
    }
  }
  if (part.empty()) return decompose_usage_error("missing PART.dxf");
  if (!run && (!run_svg_path.empty() || !main_file.empty() || !aux_file.empty()))
    return decompose_usage_error("--machine, --aux-machine and --run-svg go with --run");

  // The outputs are checked before any work: none may be an input or
  // another output (nothing is written until the command has done its work).
  if (run) {
    if (main_file.empty()) main_file = shipped_machine_file("default");
    if (aux_file.empty()) aux_file = shipped_machine_file("aux_stage");
  }
  std::vector<std::string> inputs{part};
  if (run) inputs.insert(inputs.end(), {main_file, aux_file});
  if (Status s = check_outputs({csv_path, svg_path, accel_svg_path, run_svg_path}, inputs); !s) {
    std::fprintf(stderr, "lasercnc decompose: %s\n", s.error().to_string().c_str());
    return 2;
  }
  OutputSet outputs(inputs);

  // --run: the groups' configs give the limits the user did not.
  MachineConfig main_m, aux_m;
  if (run) {
    for (auto [file, m] : {std::pair{&main_file, &main_m}, std::pair{&aux_file, &aux_m}}) {
      const std::string& path = *file;
      Result<MachineConfig> loaded = load_machine_config(path);
      if (!loaded) {
        std::fprintf(stderr, "%s\n", loaded.error().to_string().c_str());
        return 1;
      }
      *m = std::move(loaded).value();
    }
    Result<decompose::Options> lim = group_limits(main_m, aux_m, opt);
    if (!lim) {
      std::fprintf(stderr, "lasercnc decompose: %s\n", lim.error().to_string().c_str());
      return 1;
    }
    if (!main_speed_given) opt.main_speed_mm_s = lim->main_speed_mm_s;
    if (!main_accel_given) opt.main_accel_mm_s2 = lim->main_accel_mm_s2;
    if (!aux_speed_given) opt.aux_speed_mm_s = lim->aux_speed_mm_s;
    if (!field_given) opt.aux_half_field_mm = lim->aux_half_field_mm;
  }

  Result<dxf::ReadResult> read = dxf::read_dxf_file(part, read_opt);
  if (!read) {
    std::fprintf(stderr, "%s\n", read.error().to_string().c_str());
    return 1;
  }
  Result<decompose::PartResult> res = decompose::decompose_part(read->drawing, step_mm, opt);
  if (!res) {
    Diagnostic e = res.error();
    if (e.file.empty()) e.file = part;
    std::fprintf(stderr, "%s\n", e.to_string().c_str());
    return 1;
  }

  const bool seed = opt.mode == decompose::Mode::Seed;
  std::printf("%s: %zu contours, %zu points, step %.4f mm, mode %s\n", part.c_str(), res->contours.size(),
              res->points, step_mm, seed ? "seed (Kondratenko et al. 2015 eq. 1-13)" : "sync");
  for (const std::string& n : read->notes) std::printf("  %s\n", n.c_str());
  std::printf(
      "contour speed %.1f mm/s (%.2f m/min); main axes <= %.1f mm/s2 (%.2f g), "
      "<= %.1f mm/s; aux <= %.1f mm/s, field +-%.3f mm\n",
      opt.speed_mm_s, opt.speed_mm_s * 0.06, opt.main_accel_mm_s2, opt.main_accel_mm_s2 / kG_mm_s2,
      opt.main_speed_mm_s, opt.aux_speed_mm_s, opt.aux_half_field_mm);
  std::printf("%3s %-26s %10s %9s %9s %8s %11s %9s %9s %9s %11s\n", "#", "first entity", "length mm",
              "points", "time s", "tau s", "main a", "main v", "aux v", "aux max", "a_eff");
  double total_t = 0, a_main = 0, a_eff = 0, aux_max = 0, exact = 0;
  int warnings = 0;
  for (const decompose::ContourResult& c : res->contours) {
    const decompose::Peaks& p = c.peaks;
    const std::string first =
        std::string(dxf::entity_name(c.contour.first_kind)) + " line " + std::to_string(c.contour.first_line);
    std::printf("%3u %-26s %10.3f %9zu %9.4f %8.4f %11.1f %9.1f %9.1f %9.4f %11.1f\n", c.contour.index,
                first.c_str(), c.polyline.length_mm, c.polyline.size(), p.duration_s, c.tau_s, p.a_main,
                p.v_main, p.v_aux, p.aux_excursion, p.a_eff);
    total_t += p.duration_s;
    a_main = std::max(a_main, p.a_main);
    a_eff = std::max(a_eff, p.a_eff);
    aux_max = std::max(aux_max, p.aux_excursion);
    exact = std::max(exact, p.exactness);
    for (const std::string& w : c.exceeded) {
      std::printf("  warning: %s: %s\n", c.contour.name().c_str(), w.c_str());
      ++warnings;
    }
  }
  std::printf(
      "total time %.4f s; peak main-axis acceleration %.1f mm/s2 (%.3f g); peak "
      "effective acceleration %.1f mm/s2 (%.3f g) = a main-axes-only machine's, %.1fx "
      "the main axes'; aux excursion %.4f mm; |S1 + S2 - S| <= %.1e mm\n",
      total_t, a_main, a_main / kG_mm_s2, a_eff, a_eff / kG_mm_s2, a_main > 0 ? a_eff / a_main : 0.0, aux_max,
      exact);
  if (seed && warnings > 0) {
    std::printf(
        "the published algorithm does not guarantee the limits: %d exceeded "
        "(--mode sync does)\n",
        warnings);
  }

  const std::string title = part + " — " + (seed ? "seed mode" : "sync mode") + ", " +
                            std::to_string(opt.speed_mm_s * 0.06).substr(0, 5) + " m/min";
  if (!csv_path.empty()) {
    std::vector<const decompose::KinematicsTable*> tables;
    for (const decompose::ContourResult& c : res->contours) tables.push_back(&c.table);
    if (!outputs.add(csv_path, [&](OutputFile& f) {
          OutputStreamBuf buf(f);
          std::ostream out(&buf);
          decompose::write_csv(out, tables);
        }))
      return 1;
    std::printf("kinematics table: %s\n", csv_path.c_str());
  }
  if (!svg_path.empty()) {
    if (!outputs.add(svg_path, [&](OutputFile& f) { f.write(decompose::paths_svg(*res, opt, title)); }))
      return 1;
    std::printf("picture: %s\n", svg_path.c_str());
  }
  if (!accel_svg_path.empty()) {
    if (!outputs.add(accel_svg_path, [&](OutputFile& f) { f.write(decompose::accel_svg(*res, opt, title)); }))
      return 1;
    std::printf("acceleration plot: %s\n", accel_svg_path.c_str());
  }
  // The run's own checks failing still leaves a complete run: its outputs
  // are kept (they show what went wrong); a refused run keeps none.
  bool checks_passed = true;
  if (run) {
    const std::optional<bool> ran = run_part(*res, main_m, aux_m, run_opt, part, run_svg_path, outputs);
    if (!ran) return 1;
    checks_passed = *ran;
  }
  if (!outputs.commit_all()) return 1;
  return checks_passed ? 0 : 3;  // 3: the run failed its own checks, as `lasercnc run`
}

}  // namespace lcnc::app
