#include "decompose/part_decomposition.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "decompose/seed_decomposition.h"
#include "decompose/sync_decomposition.h"
#include "dxf/contour_chain.h"
#include "dxf/contour_check.h"
#include "dxf/dxf_tolerances.h"

namespace lcnc::decompose {
namespace {

std::string over(const char* what, double value, double limit, const char* unit) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s %.3f %s > %.3f %s", what, value, unit, limit, unit);
  return buf;
}

}  // namespace

Status check_part_size(const dxf::Drawing& d, const std::vector<dxf::Contour>& contours, double step_mm) {
  if (!(step_mm > 0.0)) return {};  // discretize_all names a bad step
  double length_mm = 0.0, points = 0.0;
  for (const dxf::Contour& c : contours) {
    const double l = c.length();
    length_mm += l;
    points += std::max(static_cast<double>(dxf::kMinContourPoints), std::ceil(l / step_mm));
  }
  if (points <= static_cast<double>(kMaxPartPoints)) return {};
  char buf[480];
  std::snprintf(buf, sizeof buf,
                "the part's %zu contours are %.1f mm long at step %g mm: %.1f M points, more "
                "than the %.1f M allowed; the drawing is read in %s (%g mm per unit): check "
                "$INSUNITS (or --units) and --step",
                contours.size(), length_mm, step_mm, points * 1e-6,
                static_cast<double>(kMaxPartPoints) * 1e-6, d.units.c_str(), d.unit_mm);
  return make_error(ErrorCode::DecomposeTooLarge, buf, d.file);
}

Status check_options(const Options& opt) {
  auto positive = [](double v, const char* what, const char* unit) -> Status {
    if (std::isfinite(v) && v > 0.0) return {};
    return make_error(ErrorCode::DecomposeBadOption, std::string(what) + " " + std::to_string(v) + " " +
                                                         unit + "; expected a positive number");
  };
  if (Status s = positive(opt.speed_mm_s, "contour speed", "mm/s"); !s) return s;
  if (Status s = positive(opt.main_accel_mm_s2, "main-axis acceleration limit", "mm/s^2"); !s) return s;
  if (Status s = positive(opt.main_speed_mm_s, "main-axis speed limit", "mm/s"); !s) return s;
  if (Status s = positive(opt.aux_speed_mm_s, "auxiliary speed limit", "mm/s"); !s) return s;
  if (Status s = positive(opt.aux_half_field_mm, "auxiliary half field", "mm"); !s) return s;
  // The beam is the sum of the two groups (S = S1 + S2), so in sync mode,
  // which keeps every limit, it cannot run faster than their speed limits
  // added: refused before any work (the search for the highest feasible
  // speed from far above it would take minutes).
  if (opt.mode == Mode::Sync && opt.speed_mm_s > opt.main_speed_mm_s + opt.aux_speed_mm_s) {
    const double sum = opt.main_speed_mm_s + opt.aux_speed_mm_s;
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "contour speed %.1f mm/s (%.2f m/min) is more than the main and auxiliary "
                  "axes reach together: %.1f + %.1f = %.1f mm/s (%.2f m/min); expected a contour "
                  "speed at most that",
                  opt.speed_mm_s, opt.speed_mm_s * 0.06, opt.main_speed_mm_s, opt.aux_speed_mm_s, sum,
                  sum * 0.06);
    return make_error(ErrorCode::DecomposeInfeasible, buf);
  }
  if (!(opt.critical_angle_deg > 0.0 && opt.critical_angle_deg < 180.0)) {
    return make_error(
        ErrorCode::DecomposeBadOption,
        "critical angle " + std::to_string(opt.critical_angle_deg) + " deg; expected 0 < angle < 180");
  }
  return {};
}

Result<PreparedPart> prepare_part(const dxf::Drawing& d, double step_mm) {
  Result<std::vector<dxf::Contour>> cs = dxf::chain_contours(d);
  if (!cs) return cs.error();
  if (cs->empty()) {
    return make_error(ErrorCode::DxfOpenContour,
                      "the drawing has no contours; expected at least one closed contour", d.file);
  }
  if (Status s = check_part_size(d, *cs, step_mm); !s) return s.error();
  Result<std::vector<dxf::Polyline>> pl = dxf::discretize_all(*cs, step_mm, d.file);
  if (!pl) return pl.error();
  if (Status s = dxf::check_crossings(*cs, *pl, d.file); !s) return s.error();
  return PreparedPart{std::move(*cs), std::move(*pl)};
}

Result<PartResult> decompose_prepared(const PreparedPart& p, const Options& opt) {
  if (Status s = check_options(opt); !s) return s.error();
  PartResult out;
  out.contours.reserve(p.contours.size());
  for (std::size_t i = 0; i < p.contours.size(); ++i) {
    ContourResult r;
    r.contour = p.contours[i];
    r.polyline = p.polylines[i];
    if (opt.mode == Mode::Seed) {
      Result<KinematicsTable> t = seed_decompose(r.polyline, opt);
      if (!t) {
        Diagnostic e = t.error();
        e.message = r.contour.name() + ": " + e.message;
        return e;
      }
      r.table = std::move(*t);
    } else {
      Result<SyncResult> t = sync_decompose(r.polyline, opt, r.contour.name());
      if (!t) return t.error();
      r.table = std::move(t->table);
      r.tau_s = t->tau_s;
    }
    r.peaks = peaks(r.table);
    if (r.peaks.a_main > opt.main_accel_mm_s2) {
      r.exceeded.push_back(over("main acceleration", r.peaks.a_main, opt.main_accel_mm_s2, "mm/s^2"));
    }
    if (r.peaks.v_main > opt.main_speed_mm_s) {
      r.exceeded.push_back(over("main speed", r.peaks.v_main, opt.main_speed_mm_s, "mm/s"));
    }
    if (r.peaks.v_aux > opt.aux_speed_mm_s) {
      r.exceeded.push_back(over("auxiliary speed", r.peaks.v_aux, opt.aux_speed_mm_s, "mm/s"));
    }
    if (r.peaks.aux_excursion > opt.aux_half_field_mm) {
      r.exceeded.push_back(over("auxiliary excursion", r.peaks.aux_excursion, opt.aux_half_field_mm, "mm"));
    }
    out.points += r.polyline.size();
    out.contours.push_back(std::move(r));
  }
  return out;
}

Result<PartResult> decompose_part(const dxf::Drawing& d, double step_mm, const Options& opt) {
  if (Status s = check_options(opt); !s) return s.error();
  Result<PreparedPart> p = prepare_part(d, step_mm);
  if (!p) return p.error();
  return decompose_prepared(*p, opt);
}

}  // namespace lcnc::decompose
