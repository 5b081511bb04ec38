-- Shared definitions of the micro-step interpolator (docs/design.md §9, Chi, Wu and Cui (2020)
-- §3.1): the bus register map and the elaboration-time generic checks.
--
-- Register map (word addresses on the bus, A = number of axes):
--
--   0 .. A-1  AXIS(i)  W   stage axis i's increment for the next period:
--                          bits mag_width-1..0 magnitude n, bit bus_width-1
--                          direction (1 = negative), as the paper's PulDat + d7
--   A         SEL      W   any write: latch all staged increments into the
--                          single-stage buffer (sets EN; seed "SEL")
--   A+1       DIV      RW  divider buffer: system clocks per DDA tick, taken
--                          at the next period boundary (feed override, §5.5)
--   A+2       CTRL     RW  bit 0 run, bit 1 output mode (0 PUL/SIG pulse
--                          pairs, 1 STEP/DIR; changed only while stopped),
--                          bit 2 clear the status flags and counters (W only)
--   A+3       STATUS   R   bit 0 buffer full (EN), bit 1 missed period (sticky),
--                          bit 2 overrun: SEL while full (sticky), bit 3 active
--   A+4       MISSED   R   periods that started without increments (saturates)
--   A+5       PERIODS  R   periods started since reset (wraps)
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

package lcnc_hdl_pkg is

  -- Returns cond; stops elaboration with msg when it is false. Used as
  --   constant c_ok : boolean := require(capacity >= 2, "...");
  -- in an architecture's declarations so that illegal generics never simulate.
  function require(cond : boolean; msg : string) return boolean;

  -- Bits needed to hold 0 .. n.
  function bits_for(n : natural) return positive;

  function max_of(a, b : integer) return integer;

  -- Register addresses (see above).
  function addr_sel(axes : positive) return natural;
  function addr_div(axes : positive) return natural;
  function addr_ctrl(axes : positive) return natural;
  function addr_status(axes : positive) return natural;
  function addr_missed(axes : positive) return natural;
  function addr_periods(axes : positive) return natural;
  function addr_count(axes : positive) return natural;  -- registers in the map

  constant ctrl_run_bit      : natural := 0;
  constant ctrl_step_dir_bit : natural := 1;
  constant ctrl_clear_bit    : natural := 2;

  constant status_full_bit    : natural := 0;
  constant status_missed_bit  : natural := 1;
  constant status_overrun_bit : natural := 2;
  constant status_active_bit  : natural := 3;

end package lcnc_hdl_pkg;

package body lcnc_hdl_pkg is

  function require(cond : boolean; msg : string) return boolean is
  begin
    assert cond report "illegal generics: " & msg severity failure;
    return cond;
  end function;

  function bits_for(n : natural) return positive is
    variable bits : positive := 1;
  begin
    while 2 ** bits <= n loop
      bits := bits + 1;
    end loop;
    return bits;
  end function;

  function max_of(a, b : integer) return integer is
  begin
    if a > b then
      return a;
    end if;
    return b;
  end function;

  function addr_sel(axes : positive) return natural is
  begin
    return axes;
  end function;

  function addr_div(axes : positive) return natural is
  begin
    return axes + 1;
  end function;

  function addr_ctrl(axes : positive) return natural is
  begin
    return axes + 2;
  end function;

  function addr_status(axes : positive) return natural is
  begin
    return axes + 3;
  end function;

  function addr_missed(axes : positive) return natural is
  begin
    return axes + 4;
  end function;

  function addr_periods(axes : positive) return natural is
  begin
    return axes + 5;
  end function;

  function addr_count(axes : positive) return natural is
  begin
    return axes + 6;
  end function;

end package body lcnc_hdl_pkg;
