-- Clock divider with a divider buffer (Chi, Wu and Cui 2020 §3.1 "时钟分频单元" and §5,
-- docs/design.md §5.5): makes the DDA tick, a one-cycle clock enable every D system
-- clocks. Feed override K is a new D = round(D_100% / K) written into the
-- divider buffer at any time; the divider takes it only on `reload`, which the
-- period sequencer raises at a period boundary. So a period runs at one tick
-- rate from its first tick to its last, and a change never shortens or
-- stretches a tick half-way (glitch-free by construction: the tick is a
-- clock enable in the one system clock domain, never a derived clock).
--
--   divider buffer: div_buf := div_value           on div_wr
--   on reload:      D := max(div_buf, min_divider); count := D - 1
--   otherwise:      count := D - 1 when count = 0 else count - 1
--   tick = enable and count = 0
--
-- After a reload at cycle L the ticks fall on cycles L + D, L + 2D, ... .
-- min_divider is the shortest tick the pulse outputs can follow (pulse
-- width, direction setup and hold; see microstep_interpolator).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;

entity clock_divider is
  generic (
    div_width     : positive := 16;   -- width of D
    min_divider   : positive := 2;    -- D is never below this
    reset_divider : positive := 125   -- D after reset (seed: 50 MHz / 125 = 400 kHz)
  );
  port (
    clk       : in  std_ulogic;
    rst       : in  std_ulogic;
    div_wr    : in  std_ulogic;
    div_value : in  unsigned(div_width - 1 downto 0);
    reload    : in  std_ulogic;
    enable    : in  std_ulogic;
    tick      : out std_ulogic;
    div_buf   : out unsigned(div_width - 1 downto 0);  -- the buffer, for read-back
    divider   : out unsigned(div_width - 1 downto 0)   -- D of the running period
  );
end entity clock_divider;

architecture rtl of clock_divider is
  constant c_ok_min : boolean := require(min_divider < 2 ** div_width,
    "clock_divider: min_divider = " & integer'image(min_divider) & " does not fit div_width = " &
    integer'image(div_width));
  constant c_ok_reset : boolean := require(reset_divider >= min_divider and reset_divider < 2 ** div_width,
    "clock_divider: reset_divider = " & integer'image(reset_divider) & " outside min_divider = " &
    integer'image(min_divider) & " .. 2^div_width - 1");

  constant d_top : positive := 2 ** div_width - 1;

  -- integer ranges (registers of div_width bits): fast to simulate
  signal buf   : natural range 0 to d_top := reset_divider;
  signal d     : natural range 1 to d_top := reset_divider;
  signal count : natural range 0 to d_top := 0;
begin

  divide : process (clk)
    variable d_new : natural range 1 to d_top;
  begin
    if rising_edge(clk) then
      if reload = '1' then
        d_new := max_of(buf, min_divider);
        d     <= d_new;
        count <= d_new - 1;
      elsif enable = '1' then
        if count = 0 then
          count <= d - 1;
        else
          count <= count - 1;
        end if;
      end if;
      if div_wr = '1' then
        buf <= to_integer(div_value);
      end if;
      if rst = '1' then
        buf   <= reset_divider;
        d     <= reset_divider;
        count <= 0;
      end if;
    end if;
  end process divide;

  tick    <= '1' when enable = '1' and count = 0 else '0';
  div_buf <= to_unsigned(buf, div_width);
  divider <= to_unsigned(d, div_width);

end architecture rtl;
