-- Self-checking testbench of period_sequencer. Random ticks (also while
-- stopped, where they must be ignored), run dropped and raised at random.
-- The check process keeps its own model — the list of tick counts per
-- period — and checks every cycle: Com low exactly from a period's first
-- cycle through its first tick, load on the start and on each period's last
-- tick while running, a stop only after a period's last tick, N ticks in
-- every period; at the end the measured Com duty equals (N-1)/N of the ticks.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;
use work.sim_support_pkg.all;

entity tb_period_sequencer is
  generic (
    capacity : positive := 30;
    seed     : positive := 1;
    cycles   : positive := 60000;
    tick_pct : natural  := 40     -- chance of a tick in a cycle, percent
  );
end entity tb_period_sequencer;

architecture sim of tb_period_sequencer is
  constant clk_period : time := 20 ns;

  signal clk        : std_ulogic := '0';
  signal rst        : std_ulogic := '1';
  signal run        : std_ulogic := '0';
  signal tick       : std_ulogic := '0';
  signal load       : std_ulogic;
  signal active     : std_ulogic;
  signal com        : std_ulogic;
  signal tick_index : natural range 0 to capacity - 1;
  signal done       : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.period_sequencer
    generic map (capacity => capacity)
    port map (clk => clk, rst => rst, run => run, tick => tick, load => load, active => active,
              com => com, tick_index => tick_index);

  stimulus : process
    variable rnd : random_t;
  begin
    rnd.init(seed);
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    for c in 1 to cycles loop
      tick <= sl(rnd.chance(tick_pct));
      if rnd.chance(1) then
        run <= not run;
      elsif c < 10 then
        run <= '1';
      end if;
      wait until rising_edge(clk);
    end loop;
    done <= true;
    wait;
  end process stimulus;

  check : process
    variable act       : boolean := false;
    variable idx       : natural := 0;   -- ticks done in the running period
    variable periods   : natural := 0;
    variable exp_load  : boolean;
    variable com_low   : natural := 0;   -- ticks with Com low
    variable ticks_run : natural := 0;   -- ticks while active
  begin
    wait until rising_edge(clk);
    while not done loop
      if rst = '0' then
        exp_load := run = '1' and (not act or (tick = '1' and idx = capacity - 1));
        check_equal(load, sl(exp_load), "period " & integer'image(periods) & " tick " &
                    integer'image(idx) & " load");
        check_equal(active, sl(act), "period " & integer'image(periods) & " active");
        check_equal(com, sl(not (act and idx = 0)), "period " & integer'image(periods) & " tick " &
                    integer'image(idx) & " Com");
        if act then
          check_equal(tick_index, idx, "period " & integer'image(periods) & " tick index");
          if tick = '1' then
            ticks_run := ticks_run + 1;
            if com = '0' then
              com_low := com_low + 1;
            end if;
          end if;
        end if;
        -- the edge
        if exp_load then
          if act then
            periods := periods + 1;
          end if;
          act := true;
          idx := 0;
        elsif act and tick = '1' then
          if idx = capacity - 1 then  -- run = '0': stop after the last tick
            act := false;
            idx := 0;
            periods := periods + 1;
          else
            idx := idx + 1;
          end if;
        end if;
      end if;
      wait until rising_edge(clk);
    end loop;
    assert periods > 20
      report "tb_period_sequencer: only " & integer'image(periods) & " periods" severity failure;
    -- every completed period had exactly one of its N ticks under Com low
    assert com_low * capacity <= ticks_run + capacity and ticks_run <= com_low * capacity + capacity
      report "tb_period_sequencer: Com low on " & integer'image(com_low) & " of " &
             integer'image(ticks_run) & " ticks, expected 1 in " & integer'image(capacity)
      severity failure;
    report "tb_period_sequencer: N = " & integer'image(capacity) & ", " & integer'image(periods) &
           " periods, Com low on " & integer'image(com_low) & " of " & integer'image(ticks_run) &
           " ticks: ok";
    std.env.finish;
  end process check;

  watchdog : process
  begin
    wait for clk_period * (cycles + 100);
    assert false report "tb_period_sequencer: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
