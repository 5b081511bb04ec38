#include "app/cut_cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/cli_values.h"
#include "app/output_set.h"
#include "cut/cut_program.h"
#include "cut/cut_svg.h"
#include "dxf/dxf_reader.h"

namespace lcnc::app {
namespace {

constexpr const char* kCutUsage =
    "usage: lasercnc cut PART.dxf -o PROGRAM.ngc|- [--svg FILE] [--process TABLE.csv]\n"
    "                    [--feed MM_MIN] [--power PCT] [--pierce S] [--kerf MM]\n"
    "                    [--lead-in MM] [--lead-out MM] [--direction cw|ccw]\n"
    "                    [--units mm|inch|cm|m] [--origin X,Y]\n"
    "\n"
    "  Makes a laser cutting program from the closed contours of a DXF part:\n"
    "  contours inside others are holes (and parts inside holes parts again);\n"
    "  everything inside a contour is cut before it, inner before outer, nearest\n"
    "  first; each path is offset by kerf/2 to the scrap side (outward of an\n"
    "  outline, inward of a hole) and pierced off the part at the start of a\n"
    "  straight lead-in from the scrap side. See docs/laser_cutting.md.\n"
    "  -o           the G-code (- for standard output; the summary then goes to\n"
    "               standard error)\n"
    "  --svg        picture: drawing, cut paths, lead-ins, pierce points, order\n"
    "  --process    CSV table per DXF layer: layer,feed_mm_min,power_pct,pierce_s,\n"
    "               kerf_mm (an empty field or a layer not listed: the defaults below)\n"
    "  --feed       cutting feed, mm/min (default 3000)\n"
    "  --power      laser power, % of rated: M3 S<power> (default 80)\n"
    "  --pierce     pierce time, s: G4 with the beam on (default 0.5)\n"
    "  --kerf       kerf width, mm; the path runs kerf/2 off the drawing (default 0.2;\n"
    "               0 = no compensation)\n"
    "  --lead-in    straight lead-in from the scrap side, mm (default 2; 0 = pierce\n"
    "               on the path); shortened with a warning where it does not fit\n"
    "  --lead-out   overcut past the start along the path, mm (default 0.5; 0 = none)\n"
    "  --direction  outlines cw (default: holes ccw, the part on the right of the\n"
    "               beam's travel) or ccw (holes cw)\n"
    "  --units      the drawing's units, when $INSUNITS is missing or wrong\n"
    "               (the command refuses a drawing without units, or a part under\n"
    "               1 mm or over 10 m across, until they are given)\n"
    "  --origin     where the drawing's 0,0 is in the program, mm (default 0,0)\n";

int cut_usage_error(const std::string& msg) { return lcnc::app::usage_error("lasercnc cut", msg, kCutUsage); }

void print_summary(std::FILE* out, const std::string& part, const cut::CutPlan& plan,
                   const std::vector<std::string>& notes) {
  std::fprintf(out, "%s: %zu contours: %zu outlines, %zu holes\n", part.c_str(), plan.contours.size(),
               plan.parts, plan.holes);
  for (const std::string& n : notes) std::fprintf(out, "  %s\n", n.c_str());
  std::fprintf(out, "%5s %-7s %-48s %-10s %7s %8s %9s %7s\n", "order", "kind", "contour", "layer", "kerf",
               "lead-in", "feed", "power");
  for (std::size_t k = 0; k < plan.contours.size(); ++k) {
    const cut::CutContour& c = plan.contours[k];
    std::string name = c.name.substr(0, c.name.find(", layer"));
    if (name.back() != ')') name += ")";
    std::fprintf(out, "%5zu %-7s %-48s %-10s %7.3f %8.3f %9.0f %6.1f%%\n", k + 1, c.hole ? "hole" : "outline",
                 name.c_str(), c.layer.c_str(), c.process.kerf_mm, c.entry.lead_in_mm, c.process.feed_mm_min,
                 c.process.power_pct);
  }
  for (const std::string& w : plan.warnings) std::fprintf(out, "  warning: %s\n", w.c_str());
  std::fprintf(out,
               "cut %.3f mm, lead-ins %.3f mm, rapids %.3f mm; estimated time %.1f s (feeds, "
               "pierces, rapids at %.0f m/min)\n",
               plan.cut_mm, plan.lead_mm, plan.rapid_mm, plan.time_s, cut::kEstimateRapidMmS * 0.06);
}

}  // namespace

int cut_main(int argc, char** argv) {
  std::string part, out_path, svg_path, process_path;
  cut::CutOptions opt;
  cut::Process defaults;
  dxf::ReadOptions read_opt;
  for (int i = 1; i < argc; ++i) {
    std::string_view a, v;
    if (const auto exit = file_or_option("lasercnc cut", kCutUsage, argc, argv, i, part, a, v)) return *exit;
    if (a.empty()) continue;  // the drawing
    auto bad = [&](const char* expected) {
      return cut_usage_error(std::string(a) + " " + std::string(v) + ": expected " + expected);
    };
    // NaN when not a number: every range check below then fails
    const double x = parse_number(v).value_or(std::nan(""));
    if (a == "-o" || a == "--output") {
      out_path = std::string(v);
    } else if (a == "--svg") {
      svg_path = std::string(v);
    } else if (a == "--process") {
      process_path = std::string(v);
    } else if (a == "--feed") {
      if (!(x > 0.0 && std::isfinite(x))) return bad("a feed in mm/min, more than 0");
      defaults.feed_mm_min = x;
    } else if (a == "--power") {
      if (!(x >= 0.0 && x <= 100.0)) return bad("a power in % of rated, 0 to 100");
      defaults.power_pct = x;
    } else if (a == "--pierce") {
      if (!(x >= 0.0 && x <= 3600.0)) return bad("a pierce time in s, 0 to 3600");
      defaults.pierce_s = x;
    } else if (a == "--kerf") {
      if (!(x >= 0.0 && x <= 10.0)) return bad("a kerf width in mm, 0 to 10");
      defaults.kerf_mm = x;
    } else if (a == "--lead-in" || a == "--lead-out") {
      if (!(x >= 0.0 && x <= 100.0)) return bad("a length in mm, 0 to 100");
      (a == "--lead-in" ? opt.lead_in_mm : opt.lead_out_mm) = x;
    } else if (a == "--direction") {
      if (v == "cw")
        opt.outer = cut::Direction::Cw;
      else if (v == "ccw")
        opt.outer = cut::Direction::Ccw;
      else
        return bad("cw or ccw (the outlines' direction; holes the other way)");
    } else if (a == "--units") {
      const std::optional<double> u = parse_unit_mm(v);
      if (!u) return bad("mm, inch, cm or m");
      read_opt.unit_mm = *u;
      opt.units_given = true;
    } else if (a == "--origin") {
      const auto xy = parse_xy(v);
      if (!xy) return bad("X,Y in mm (e.g. 10,10)");
      opt.origin = cut::Vec2(xy->first, xy->second);
    } else {
      return cut_usage_error("unknown option " + std::string(a));
    }
  }
  if (part.empty()) return cut_usage_error("missing PART.dxf");
  if (out_path.empty()) return cut_usage_error("missing -o PROGRAM.ngc (- for standard output)");

  std::vector<std::string> inputs{part};
  if (!process_path.empty()) inputs.push_back(process_path);
  if (Status s = check_outputs({out_path, svg_path}, inputs); !s) {
    std::fprintf(stderr, "lasercnc cut: %s\n", s.error().to_string().c_str());
    return 2;
  }
  auto fail = [](const Diagnostic& e) {
    std::fprintf(stderr, "%s\n", e.to_string().c_str());
    return 1;
  };

  if (process_path.empty()) {
    opt.process.defaults = defaults;
  } else {
    Result<cut::ProcessTable> t = cut::read_process_table(process_path, defaults);
    if (!t) return fail(t.error());
    opt.process = std::move(t).value();
  }
  Result<dxf::ReadResult> read = dxf::read_dxf_file(part, read_opt);
  if (!read) return fail(read.error());
  if (Status s = cut::check_units(read->drawing, opt.units_given); !s) return fail(s.error());
  Result<cut::CutPlan> plan = cut::plan_cut(read->drawing, opt);
  if (!plan) {
    Diagnostic e = plan.error();
    if (e.file.empty()) e.file = part;
    return fail(e);
  }

  const bool to_stdout = out_path == "-" || out_path == "/dev/stdout";
  std::FILE* report = to_stdout ? stderr : stdout;
  print_summary(report, part, *plan, read->notes);
  OutputSet outputs(inputs);
  if (!outputs.add(out_path, [&](OutputFile& f) { f.write(cut::cut_gcode(*plan, opt, part)); })) return 1;
  if (!svg_path.empty()) {
    if (!outputs.add(svg_path,
                     [&](OutputFile& f) { f.write(cut::plan_svg(*plan, part + " — lasercnc cut")); }))
      return 1;
  }
  if (!outputs.commit_all()) return 1;
  if (!to_stdout) std::fprintf(report, "program: %s\n", out_path.c_str());
  if (!svg_path.empty()) std::fprintf(report, "picture: %s\n", svg_path.c_str());
  return 0;
}

}  // namespace lcnc::app
