// `lasercnc drill HOLES.csv ...` — runs the rows of a hole table (the process
// database's CSV, holes/hole_table.h) as one drilling job on the simulated
// machine (holes/drill_job.h): checked whole before anything moves, planned
// and executed by the same planner and RT thread as `lasercnc run`. With
// --devices the four-beam scanning head, the laser source and the power
// meter are simulated Modbus devices: each hole's head parameter block
// (fields 12–18) is written while the machine stands at the hole's clearance
// point, the head scans during the hole and stops after it; the laser's
// setpoint follows the job (app/laser_link.h).
//
// Exit codes as `lasercnc run`: 0 done, 1 bad input (table, machine, a hole
// beyond the travel, a device that refuses), 2 bad command line, 3 the run
// failed its own checks.
#pragma once

namespace lcnc::app {

// argv[0] is "drill", argv[1…] the table and options.
int drill_main(int argc, char** argv);

}  // namespace lcnc::app
