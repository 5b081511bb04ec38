-- Period sequencer: counts the DDA ticks of a period and makes Com, the
-- interpolation sync that starts every period and interrupts the PC (seed
-- 001 §3.1: "插补同步信号 Com", low one tick per period, 29/30 duty at N = 30).
--
-- A period is N ticks, index 0 .. N-1. `load` is the cycle whose edge starts
-- a period: the first cycle with run = '1' while stopped, or the cycle of the
-- last tick (index N-1) of a running period while run stays '1'. On that
-- edge the DDA takes the buffered increments and the divider its buffered D.
-- If run is '0' at the last tick the sequencer stops after it: a period is
-- never cut short.
--
--   Com = '0' while active and the tick index is 0, i.e. from the period's
--   first cycle c0 through its first tick at c0 + D - 1: D cycles of N·D.
--   Com is a register (the PC's interrupt line must not glitch).
library ieee;
use ieee.std_logic_1164.all;

use work.lcnc_hdl_pkg.all;

entity period_sequencer is
  generic (
    capacity : positive := 30  -- N, ticks per period
  );
  port (
    clk        : in  std_ulogic;
    rst        : in  std_ulogic;
    run        : in  std_ulogic;
    tick       : in  std_ulogic;
    load       : out std_ulogic;
    active     : out std_ulogic;
    com        : out std_ulogic;
    tick_index : out natural range 0 to capacity - 1  -- for observation
  );
end entity period_sequencer;

architecture rtl of period_sequencer is
  constant c_ok : boolean := require(capacity >= 2,
    "period_sequencer: capacity N = " & integer'image(capacity) & " < 2 (Com could not toggle)");

  signal active_r : std_ulogic := '0';
  signal idx      : natural range 0 to capacity - 1 := 0;
  signal com_r    : std_ulogic := '1';
  signal at_end   : std_ulogic;
  signal load_i   : std_ulogic;
begin

  at_end <= '1' when active_r = '1' and tick = '1' and idx = capacity - 1 else '0';
  load_i <= '1' when run = '1' and (active_r = '0' or at_end = '1') else '0';

  count : process (clk)
    variable active_n : std_ulogic;
    variable idx_n    : natural range 0 to capacity - 1;
  begin
    if rising_edge(clk) then
      active_n := active_r;
      idx_n    := idx;
      if load_i = '1' then
        active_n := '1';
        idx_n    := 0;
      elsif at_end = '1' then      -- run = '0': stop after the last tick
        active_n := '0';
        idx_n    := 0;
      elsif active_r = '1' and tick = '1' then
        idx_n := idx + 1;
      end if;
      if rst = '1' then
        active_n := '0';
        idx_n    := 0;
      end if;
      active_r <= active_n;
      idx      <= idx_n;
      if active_n = '1' and idx_n = 0 then
        com_r <= '0';
      else
        com_r <= '1';
      end if;
    end if;
  end process count;

  load       <= load_i;
  active     <= active_r;
  com        <= com_r;
  tick_index <= idx;

end architecture rtl;
