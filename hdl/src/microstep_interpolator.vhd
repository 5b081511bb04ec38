-- The micro-step hardware interpolator (docs/design.md §9, Chi, Wu and Cui (2020) §3.1, Fig. 4):
-- bus decoder, clock divider with a divider buffer, period sequencer (Com),
-- and per axis a single-stage increment buffer, a DDA and a pulse output.
--
--                          per axis:
--   bus ─► bus_decoder ─┬─ increments, SEL ─► increment_buffer ─► dda_axis ─► pulse_output ─► drive
--                       ├─ DIV ─► clock_divider ─── tick ────────────┤
--                       └─ run ─► period_sequencer ─ load ───────────┘
--                                        └─ Com ─► the PC's interrupt
--
-- Every period is N DDA ticks; the tick is a clock enable every D system
-- clocks, so the period is N·D/f_clk (seed: N = 30, D = 125 at 50 MHz:
-- 400 kHz, 75 µs). Feed override K writes D = round(D_100% / K) into the
-- divider buffer; it takes effect at the next period boundary (docs/design.md §5.5).
--
-- Cycle timing, a period starting in cycle c0 with divider D:
--   Com = '0' in cycles c0 .. c0 + D - 1 (one tick of N: duty (N-1)/N)
--   tick t (0 .. N-1) in cycle c0 + D - 1 + t·D
--   its output pulse rises in cycle c0 + (t+1)·D + 1 + dir_setup
--   the next period's increments must be latched (SEL strobe) by cycle
--   c0 + N·D - 2, i.e. the SEL bus write by cycle c0 + N·D - 3; otherwise that
--   period outputs no pulses, `missed` strobes in its first cycle and the late
--   increments are output one period later (position stays exact, the
--   software sees the flag and the MISSED counter).
-- Pulse tick positions per period equal rt::Dda's (rt/dda.h) tick for tick.
--
-- The minimum divider must leave room for the output pulse: every tick is at
-- least pulse_width + dir_setup + dir_hold cycles (and pulse_width + 1), so
-- the fastest step rate is f_clk / min_divider per axis, reached when n = N
-- (possible when N = 2^mag_width - 1).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;

entity microstep_interpolator is
  generic (
    axes          : positive := 4;    -- seed: 4 axes simulated, 5 on the board
    mag_width     : positive := 4;    -- seed: 4-bit increments, 0 .. 15 pulses per period
    capacity      : positive := 30;   -- N, ticks per period (seed: 30)
    bus_width     : positive := 16;
    addr_width    : positive := 4;
    div_width     : positive := 16;
    reset_divider : positive := 125;  -- D after reset: 50 MHz / 125 = 400 kHz
    min_divider   : positive := 2;
    pulse_width   : positive := 1;    -- output pulse high time, cycles
    dir_setup     : natural  := 0;    -- DIR before STEP, cycles
    dir_hold      : natural  := 0     -- DIR after STEP, cycles
  );
  port (
    clk           : in  std_ulogic;
    rst           : in  std_ulogic;
    bus_addr      : in  unsigned(addr_width - 1 downto 0);
    bus_wdata     : in  std_ulogic_vector(bus_width - 1 downto 0);
    bus_we        : in  std_ulogic;
    bus_re        : in  std_ulogic;
    bus_rdata     : out std_ulogic_vector(bus_width - 1 downto 0);
    com           : out std_ulogic;  -- period sync and the PC's interrupt, low one tick
    tick          : out std_ulogic;  -- the DDA clock enable (for observation)
    missed        : out std_ulogic;  -- one cycle: this period started without increments
    pul_step      : out std_ulogic_vector(axes - 1 downto 0);  -- PUL or STEP
    sig_dir       : out std_ulogic_vector(axes - 1 downto 0)   -- SIG or DIR
  );
end entity microstep_interpolator;

architecture rtl of microstep_interpolator is
  constant c_ok_divider : boolean := require(
    min_divider >= max_of(pulse_width + dir_setup + dir_hold, pulse_width + 1),
    "microstep_interpolator: min_divider = " & integer'image(min_divider) &
    " < pulse_width + dir_setup + dir_hold = " & integer'image(pulse_width + dir_setup + dir_hold) &
    " (or pulse_width + 1): a tick could not hold one output pulse");

  signal staged_mag : std_ulogic_vector(axes * mag_width - 1 downto 0);
  signal staged_dir : std_ulogic_vector(axes - 1 downto 0);
  signal sel        : std_ulogic;
  signal div_wr     : std_ulogic;
  signal div_value  : unsigned(div_width - 1 downto 0);
  signal run        : std_ulogic;
  signal mode       : std_ulogic;
  signal tick_i     : std_ulogic;
  signal load       : std_ulogic;
  signal active     : std_ulogic;
  signal full_v     : std_ulogic_vector(axes - 1 downto 0);
  signal missed_v   : std_ulogic_vector(axes - 1 downto 0);
  signal overrun_v  : std_ulogic_vector(axes - 1 downto 0);
  signal missed_i   : std_ulogic;
  signal overrun_i  : std_ulogic;
  signal period_start : std_ulogic := '0';
begin

  decoder : entity work.bus_decoder
    generic map (
      axes => axes, mag_width => mag_width, bus_width => bus_width, addr_width => addr_width,
      div_width => div_width, reset_divider => reset_divider)
    port map (
      clk => clk, rst => rst,
      bus_addr => bus_addr, bus_wdata => bus_wdata, bus_we => bus_we, bus_re => bus_re,
      bus_rdata => bus_rdata,
      staged_mag => staged_mag, staged_dir => staged_dir, sel => sel,
      div_wr => div_wr, div_value => div_value,
      run => run, step_dir_mode => mode,
      buf_full => full_v(0), active => active, missed => missed_i, overrun => overrun_i,
      period_start => period_start);

  divider : entity work.clock_divider
    generic map (div_width => div_width, min_divider => min_divider, reset_divider => reset_divider)
    port map (
      clk => clk, rst => rst, div_wr => div_wr, div_value => div_value,
      reload => load, enable => active, tick => tick_i, div_buf => open, divider => open);

  sequencer : entity work.period_sequencer
    generic map (capacity => capacity)
    port map (
      clk => clk, rst => rst, run => run, tick => tick_i,
      load => load, active => active, com => com, tick_index => open);

  axis : for i in 0 to axes - 1 generate
    signal mag       : unsigned(mag_width - 1 downto 0);
    signal dir       : std_ulogic;
    signal pulse     : std_ulogic;
    signal pulse_dir : std_ulogic;
  begin
    buf : entity work.increment_buffer
      generic map (mag_width => mag_width)
      port map (
        clk => clk, rst => rst, latch => sel,
        in_mag => unsigned(staged_mag((i + 1) * mag_width - 1 downto i * mag_width)),
        in_dir => staged_dir(i), take => load,
        out_mag => mag, out_dir => dir, full => full_v(i),
        missed => missed_v(i), overrun => overrun_v(i));

    dda : entity work.dda_axis
      generic map (mag_width => mag_width, capacity => capacity)
      port map (
        clk => clk, rst => rst, load => load, load_mag => mag, load_dir => dir, tick => tick_i,
        pulse => pulse, pulse_dir => pulse_dir, accumulator => open);

    output : entity work.pulse_output
      generic map (pulse_width => pulse_width, dir_setup => dir_setup, dir_hold => dir_hold)
      port map (
        clk => clk, rst => rst, step_dir_mode => mode, pulse => pulse, pulse_dir => pulse_dir,
        pul_step => pul_step(i), sig_dir => sig_dir(i));
  end generate axis;

  -- All buffers latch and are taken together, so their flags agree; axis 0's
  -- stand for all.
  missed_i  <= missed_v(0);
  overrun_i <= overrun_v(0);

  starts : process (clk)
  begin
    if rising_edge(clk) then
      period_start <= load and not rst;
    end if;
  end process starts;

  tick   <= tick_i;
  missed <= missed_i;

end architecture rtl;
