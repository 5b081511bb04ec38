-- Self-checking testbench of clock_divider. Random divider writes at random
-- times (values below min_divider included: they must be clamped), reloads on
-- a tick (a period boundary, as the sequencer does) and at random while idle,
-- enable dropped at random. The check process predicts every cycle from a
-- different formulation than the counter: after a reload taking D, the tick
-- is high on the enabled cycles whose count of enabled cycles since the
-- reload is a multiple of D. So a new D never cuts a tick short: the first
-- tick after a boundary comes D_new cycles after the last one.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.sim_support_pkg.all;

entity tb_clock_divider is
  generic (
    div_width     : positive := 8;
    min_divider   : positive := 2;
    reset_divider : positive := 5;
    seed          : positive := 1;
    cycles        : positive := 40000
  );
end entity tb_clock_divider;

architecture sim of tb_clock_divider is
  constant clk_period : time := 20 ns;
  constant d_top      : natural := 2 ** div_width - 1;

  signal clk       : std_ulogic := '0';
  signal rst       : std_ulogic := '1';
  signal div_wr    : std_ulogic := '0';
  signal div_value : unsigned(div_width - 1 downto 0) := (others => '0');
  signal reload    : std_ulogic := '0';
  signal enable    : std_ulogic := '0';
  signal tick      : std_ulogic;
  signal div_buf   : unsigned(div_width - 1 downto 0);
  signal divider   : unsigned(div_width - 1 downto 0);
  signal done      : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.clock_divider
    generic map (div_width => div_width, min_divider => min_divider, reset_divider => reset_divider)
    port map (
      clk => clk, rst => rst, div_wr => div_wr, div_value => div_value, reload => reload,
      enable => enable, tick => tick, div_buf => div_buf, divider => divider);

  -- Drives the inputs in the style of the period sequencer: a "period" is a
  -- random number of ticks; its last tick reloads. Sometimes the period ends
  -- in a stop (enable low for a while), then a reload restarts.
  stimulus : process
    variable rnd        : random_t;
    variable ticks_left : natural := 0;
    variable hi         : natural;
  begin
    rnd.init(seed);
    hi := d_top;
    if hi > 4 * (reset_divider + min_divider) then
      hi := 4 * (reset_divider + min_divider);  -- keep periods short enough to see many
    end if;
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    for c in 1 to cycles loop
      wait until rising_edge(clk);
      wait for clk_period / 4;  -- this cycle's tick, after the edge's register updates
      -- divider write: any value, clamped ones included
      div_wr <= '0';
      if rnd.chance(3) then
        div_wr    <= '1';
        div_value <= to_unsigned(rnd.int(0, hi), div_width);
      end if;
      reload <= '0';
      if reload = '1' and enable = '0' then
        enable <= '1';           -- running from the cycle after the start's reload
      elsif enable = '0' then
        if rnd.chance(20) then   -- start: reload while idle, as the sequencer does
          reload     <= '1';
          ticks_left := rnd.int(1, 6);
        end if;
      elsif tick = '1' then
        ticks_left := ticks_left - 1;
        if ticks_left = 0 then
          if rnd.chance(15) then
            enable <= '0';       -- stop after the last tick
          else
            reload     <= '1';   -- period boundary
            ticks_left := rnd.int(1, 6);
          end if;
        end if;
      end if;
    end loop;
    wait until rising_edge(clk);
    done <= true;
    wait;
  end process stimulus;

  check : process
    variable buf_m   : natural := reset_divider;
    variable d_m     : natural := reset_divider;
    variable enabled : natural := 0;  -- enabled cycles since the last reload
    variable exp     : std_ulogic;
    variable ticks   : natural := 0;
    variable reloads : natural := 0;
  begin
    wait until rising_edge(clk);
    while not done loop
      if rst = '0' then
        -- this cycle
        if enable = '1' then
          enabled := enabled + 1;
        end if;
        exp := sl(enable = '1' and enabled mod d_m = 0);
        check_equal(tick, exp, "cycle " & integer'image(now / clk_period) & " tick (D = " &
                    integer'image(d_m) & ", enabled cycles since reload " & integer'image(enabled) & ")");
        check_equal(to_integer(divider), d_m, "divider");
        check_equal(to_integer(div_buf), buf_m, "divider buffer");
        if exp = '1' then
          ticks := ticks + 1;
        end if;
        -- the edge
        if reload = '1' then
          d_m := buf_m;
          if d_m < min_divider then
            d_m := min_divider;
          end if;
          enabled := 0;
          reloads := reloads + 1;
        end if;
        if div_wr = '1' then
          buf_m := to_integer(div_value);
        end if;
      end if;
      wait until rising_edge(clk);
    end loop;
    assert reloads > 10 and ticks > 100
      report "tb_clock_divider: too little exercised: " & integer'image(reloads) & " reloads, " &
             integer'image(ticks) & " ticks"
      severity failure;
    report "tb_clock_divider: " & integer'image(cycles) & " cycles, " & integer'image(reloads) &
           " reloads, " & integer'image(ticks) & " ticks: ok";
    std.env.finish;
  end process check;

  watchdog : process
  begin
    wait for clk_period * (cycles + 100);
    assert false report "tb_clock_divider: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
