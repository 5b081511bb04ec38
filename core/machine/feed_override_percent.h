// The feed override as people give it (%, 100 = as programmed) and as the
// controller holds it (a fraction, 1 = 100 %), checked by one rule wherever
// it comes in: `lasercnc run --feed-override`, and `lasercnc send override`, the
// HMI's slider and the CNC's Modbus register through the daemon's command
// check (rt/shm_command.h).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include "common/result.h"

namespace lcnc {

// The lowest override each use takes, %. A live controller: 0, a feed hold.
// A run from start to end: 1 %. A whole run at 1 % already takes 100 × its
// time; below, a period would last so long that the run never ends
// (1e-300 % is 10^297 s a period).
inline constexpr double kMinLiveOverridePct = 0.0;
inline constexpr double kMinRunOverridePct = 1.0;

// The override E, a fraction (1 = 100 %) as the controller holds it and as
// it travels (the shm command, the kernel), when min_pct/100 ≤ E ≤ max_e
// (NaN never is); else an error of `code` that names the range in percent,
// as people give it: "WHAT 200 refused: allowed 1 <= PCT <= 150 (%,
// max_feed_override = 1.5)".
[[nodiscard]] inline Result<double> check_override(double e, double min_pct, double max_e, ErrorCode code,
                                                   std::string_view what) {
  if (e >= min_pct / 100.0 && e <= max_e) return e;
  char msg[200];
  std::snprintf(msg, sizeof msg, "%.*s %g refused: allowed %g <= PCT <= %g (%%, max_feed_override = %g)",
                static_cast<int>(what.size()), what.data(), e * 100.0, min_pct, 100.0 * max_e, max_e);
  return make_error(code, msg);
}

// The same rule for an override a person gives in percent (`lasercnc run
// --feed-override PCT`): E = pct / 100.
[[nodiscard]] inline Result<double> override_from_percent(double pct, double min_pct, double max_e,
                                                          ErrorCode code, std::string_view what) {
  return check_override(pct / 100.0, min_pct, max_e, code, what);
}

}  // namespace lcnc
