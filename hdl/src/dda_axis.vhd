-- One axis of the DDA fine interpolator (docs/design.md §5.4, Chi, Wu and Cui (2020) §3.1 Fig. 5),
-- bit-exact with rt::Dda (rt/dda.h).
--
-- An accumulator of capacity N is preset to N/2 (rounded down) at reset and
-- carried across periods. On every tick:
--
--     acc := acc + n;  if acc >= N then pulse on this tick; acc := acc - N
--
-- Since acc stays in [0, N) and n <= N, a period of N ticks emits exactly n
-- pulses, evenly spread, and leaves acc where it started.
--
-- Timing: `load` and `tick` are clock enables. On the edge where load = '1'
-- the increment register takes load_mag / load_dir for the ticks that follow
-- (the period sequencer raises load together with the period's last tick,
-- which still adds the old n: VHDL signal semantics). The pulse of a tick at
-- cycle k is pulse = '1' in cycle k+1 with its direction in pulse_dir.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;

entity dda_axis is
  generic (
    mag_width : positive := 4;   -- n in 0 .. 2^mag_width - 1 (seed: 4 bits)
    capacity  : positive := 30   -- N, ticks per period (seed: 30)
  );
  port (
    clk         : in  std_ulogic;
    rst         : in  std_ulogic;  -- synchronous; presets acc to N/2
    load        : in  std_ulogic;
    load_mag    : in  unsigned(mag_width - 1 downto 0);
    load_dir    : in  std_ulogic;  -- '1' = negative
    tick        : in  std_ulogic;
    pulse       : out std_ulogic;
    pulse_dir   : out std_ulogic;
    accumulator : out natural range 0 to 2 * capacity - 1  -- for observation
  );
end entity dda_axis;

architecture rtl of dda_axis is
  constant c_ok_capacity : boolean := require(capacity >= 2 ** mag_width - 1,
    "dda_axis: capacity N = " & integer'image(capacity) & " < 2^mag_width - 1 = " &
    integer'image(2 ** mag_width - 1) & " (a period could not emit its largest increment)");
  constant c_ok_period : boolean := require(capacity >= 2,
    "dda_axis: capacity N = " & integer'image(capacity) & " < 2");

  -- Integer ranges, not vectors: the same registers once synthesized
  -- (acc + n < 2N needs bits_for(2N - 1) bits), and several times faster to
  -- simulate, which the long replays need.
  signal acc     : natural range 0 to 2 * capacity - 1 := capacity / 2;
  signal n       : natural range 0 to 2 ** mag_width - 1 := 0;
  signal dir     : std_ulogic := '0';
  signal pulse_r : std_ulogic := '0';
  signal pdir_r  : std_ulogic := '0';
begin

  step : process (clk)
    variable sum : natural range 0 to 2 * capacity - 1;
  begin
    if rising_edge(clk) then
      if tick = '1' then
        sum := acc + n;
        if sum >= capacity then
          acc     <= sum - capacity;
          pulse_r <= '1';
          pdir_r  <= dir;
        else
          acc     <= sum;
          pulse_r <= '0';
        end if;
      elsif pulse_r = '1' then
        pulse_r <= '0';
      end if;
      if load = '1' then
        n   <= to_integer(load_mag);
        dir <= load_dir;
      end if;
      if rst = '1' then
        acc     <= capacity / 2;
        n       <= 0;
        dir     <= '0';
        pulse_r <= '0';
        pdir_r  <= '0';
      end if;
    end if;
  end process step;

  pulse       <= pulse_r;
  pulse_dir   <= pdir_r;
  accumulator <= acc;

end architecture rtl;
