-- Pulse output stage of one axis: turns the DDA's one-cycle pulse events into
-- what the drive takes, selectable at run time:
--
--   step_dir_mode = '0': positive/negative pulse pairs, the paper's PUL / SIG
--                        (Chi, Wu and Cui 2020 Fig. 7): pul_step pulses for a positive
--                        step, sig_dir for a negative one.
--   step_dir_mode = '1': STEP on pul_step, DIR on sig_dir ('1' = negative),
--                        which most drives take.
--
-- Timing, for an event (pulse = '1') in cycle e (all outputs are registers):
--
--   DIR  (step/dir)  takes the event's direction from cycle e + 1
--   STEP / PUL / SIG high in cycles e + 1 + dir_setup .. e + dir_setup + pulse_width
--
-- so DIR leads STEP's rising edge by dir_setup cycles, STEP is pulse_width
-- cycles wide, and every pulse has the same latency (the pulse train keeps
-- the DDA's spacing exactly). DIR changes only with a pulse of the other
-- direction, so a period of zero pulses leaves it alone. Events must be at
-- least dir_setup + pulse_width + dir_hold cycles apart (and pulse_width + 1,
-- so STEP has a low phase); then DIR holds dir_hold cycles after STEP falls.
-- The interpolator guarantees it by its minimum divider; simulation asserts it
-- (`since` has no load in synthesis and goes away).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;

entity pulse_output is
  generic (
    pulse_width : positive := 1;  -- STEP/PUL/SIG high time, cycles
    dir_setup   : natural  := 0;  -- DIR valid before STEP rises, cycles
    dir_hold    : natural  := 0   -- DIR kept after STEP falls, cycles
  );
  port (
    clk           : in  std_ulogic;
    rst           : in  std_ulogic;
    step_dir_mode : in  std_ulogic;
    pulse         : in  std_ulogic;
    pulse_dir     : in  std_ulogic;
    pul_step      : out std_ulogic;
    sig_dir       : out std_ulogic
  );
end entity pulse_output;

architecture rtl of pulse_output is
  constant span      : positive := dir_setup + pulse_width;  -- cycles from event to STEP falling
  constant min_space : positive := max_of(span + dir_hold, pulse_width + 1);

  signal remaining : natural range 0 to span := 0;  -- cycles of the pulse in flight
  signal cur_dir   : std_ulogic := '0';             -- direction of the pulse in flight
  signal dir_r     : std_ulogic := '0';             -- DIR level (step/dir mode)
  signal a_r       : std_ulogic := '0';
  signal b_r       : std_ulogic := '0';
begin

  shape : process (clk)
    variable rem_n : natural range 0 to span;
    variable cdir  : std_ulogic;
    variable ddir  : std_ulogic;
    variable high  : boolean;
    variable since : natural := min_space;  -- cycles since the last event: the simulation check only
  begin
    if rising_edge(clk) then
      rem_n := remaining;
      cdir  := cur_dir;
      ddir  := dir_r;
      if pulse = '1' then
        assert since >= min_space
          report "pulse_output: events " & integer'image(since) & " cycles apart, need >= " &
                 integer'image(min_space) & " (pulse_width + dir_setup + dir_hold)"
          severity failure;
        since := 0;
        rem_n := span;
        cdir  := pulse_dir;
        ddir  := pulse_dir;
      elsif rem_n > 0 then
        rem_n := rem_n - 1;
      end if;
      if since < min_space then
        since := since + 1;
      end if;
      high := rem_n >= 1 and rem_n <= pulse_width;
      if step_dir_mode = '1' then
        a_r <= '1' when high else '0';
        b_r <= ddir;
      else
        a_r <= '1' when high and cdir = '0' else '0';
        b_r <= '1' when high and cdir = '1' else '0';
      end if;
      remaining <= rem_n;
      cur_dir   <= cdir;
      dir_r     <= ddir;
      if rst = '1' then
        remaining <= 0;
        cur_dir   <= '0';
        dir_r     <= '0';
        a_r       <= '0';
        b_r       <= '0';
        since     := min_space;
      end if;
    end if;
  end process shape;

  pul_step <= a_r;
  sig_dir  <= b_r;

end architecture rtl;
