// Laser cutting of a DXF part (lasercnc cut): the drawing's contours made
// into a cutting program, step by step —
//   1. chain the entities into closed contours (dxf/contour_chain.h), each
//      a polygon within kChordToleranceMm of the curve (contour_polygon.h),
//      none crossing another (dxf/contour_check.h);
//   2. nest them: even depth = a part's outline, odd = a hole
//      (contour_nesting.h);
//   3. offset each by kerf/2 to the scrap side, kerf from its layer's
//      process (kerf_offset.h, process_table.h), and orient it: outlines
//      in the chosen direction, holes the other way;
//   4. order them, inner before outer, nearest first (cut_order.h), placing
//      each one's pierce, lead-in and lead-out as the beam comes to it
//      (lead_in.h);
//   5. write the G-code (cut_gcode) in the dialect of our interpreter
//      (LinuxCNC rs274ngc): G21 G90 G17 G94 G64 P<kBlendToleranceMm>; per
//      contour a comment naming it, its kind, layer and order, G0 to the
//      pierce, M3 S<power %>, G4 P<pierce s> (M3 + G4 fires at constant
//      power: the pierce), G1 lead-in and contour at F<feed>, the overcut,
//      M5. Assist gas M8 on for the job, M9 at its end.
//
// Direction: the default is an outline clockwise and holes
// counter-clockwise, as 2D laser cutters (CypCut, the default of most
// nesting software) cut: the part is then always on the right of the
// beam's travel and the scrap on its left, so a lead-in from the left is
// from the scrap, and the same lead-in and kerf side serve outlines and
// holes. --direction ccw turns it all round (part on the left).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/result.h"
#include "cut/cut_tolerances.h"
#include "cut/lead_in.h"
#include "cut/process_table.h"
#include "dxf/drawing.h"

namespace lcnc::cut {

enum class Direction : std::uint8_t { Cw, Ccw };

struct CutOptions {
  Direction outer = Direction::Cw;  // a part's outline; holes the other way
  double lead_in_mm = 2.0;
  double lead_out_mm = 0.5;
  ProcessTable process;
  Vec2 origin = Vec2::Zero();  // program coordinates = drawing + origin
  bool units_given = false;    // the user named the units (--units)
};

struct CutContour {
  std::uint32_t index = 0;  // dxf::Contour::index
  std::string name;         // "contour 2 (CIRCLE at DXF line 60, layer CUT)"
  std::string layer;
  int depth = 0;  // nesting depth: even = outline, odd = hole
  bool hole = false;
  Process process;
  std::vector<Vec2> drawing;  // the drawn contour's polygon (drawing coordinates)
  LeadIn entry;               // the cut path from its start, pierce, overcut
  double path_mm = 0.0;       // length of the closed path
};

struct CutPlan {
  std::vector<CutContour> contours;  // in cutting order
  std::vector<std::string> warnings;
  std::size_t holes = 0, parts = 0;
  double cut_mm = 0.0;    // contours and overcuts, beam on
  double lead_mm = 0.0;   // lead-ins, beam on
  double rapid_mm = 0.0;  // G0 from the origin through every pierce point
  double time_s = 0.0;    // estimate: feeds, pierces, rapids at kEstimateRapidMmS
};

// The drawing's units are usable: named by $INSUNITS (or the user), and the
// part between kMinPartMm and kMaxPartMm across — unless the user gave them.
// CutUnits naming what was found and asking for --units otherwise.
[[nodiscard]] Status check_units(const dxf::Drawing& d, bool units_given);

[[nodiscard]] Result<CutPlan> plan_cut(const dxf::Drawing& d, const CutOptions& opt);

// The program; `source` names the drawing in its header comment.
[[nodiscard]] std::string cut_gcode(const CutPlan& plan, const CutOptions& opt, const std::string& source);

}  // namespace lcnc::cut
