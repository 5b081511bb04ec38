-- Self-checking testbench of dda_axis. Random increments (0, the maximum and
-- everything between, random directions) over many periods, with random idle
-- cycles between ticks (the DDA must not depend on the tick spacing). The
-- check process models the DDA clock by clock — the tick loop of
-- rt::Dda::reference_period — and compares pulse, direction and accumulator
-- every cycle; it also holds every pulse to the closed form rt::Dda::run_period
-- uses: the j-th pulse of a period falls on tick ceil(((j+1)·N - acc0)/n) - 1.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.sim_support_pkg.all;

entity tb_dda_axis is
  generic (
    mag_width : positive := 4;
    capacity  : positive := 30;
    seed      : positive := 1;
    periods   : positive := 400;
    max_gap   : natural  := 3     -- idle cycles between ticks: 0 .. max_gap
  );
end entity tb_dda_axis;

architecture sim of tb_dda_axis is
  constant clk_period : time := 20 ns;
  constant n_max      : natural := 2 ** mag_width - 1;

  signal clk      : std_ulogic := '0';
  signal rst      : std_ulogic := '1';
  signal load     : std_ulogic := '0';
  signal load_mag : unsigned(mag_width - 1 downto 0) := (others => '0');
  signal load_dir : std_ulogic := '0';
  signal tick     : std_ulogic := '0';
  signal pulse    : std_ulogic;
  signal pdir     : std_ulogic;
  signal acc      : natural range 0 to 2 * capacity - 1;
  signal done     : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.dda_axis
    generic map (mag_width => mag_width, capacity => capacity)
    port map (
      clk => clk, rst => rst, load => load, load_mag => load_mag, load_dir => load_dir,
      tick => tick, pulse => pulse, pulse_dir => pdir, accumulator => acc);

  stimulus : process
    variable rnd : random_t;
    variable n   : natural;

    procedure next_increment is
    begin
      case rnd.int(0, 9) is
        when 0 | 1  => n := 0;
        when 2 | 3  => n := n_max;
        when others => n := rnd.int(0, n_max);
      end case;
      load_mag <= to_unsigned(n, mag_width);
      load_dir <= rnd.bit1;
    end procedure;
  begin
    rnd.init(seed);
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    -- the first period's increment, loaded without a tick
    next_increment;
    load <= '1';
    wait until rising_edge(clk);
    load <= '0';
    for p in 0 to periods - 1 loop
      for t in 0 to capacity - 1 loop
        for g in 1 to rnd.int(0, max_gap) loop
          tick <= '0';
          wait until rising_edge(clk);
        end loop;
        tick <= '1';
        if t = capacity - 1 then
          next_increment;  -- loaded with the period's last tick, as the sequencer does
          load <= '1';
        end if;
        wait until rising_edge(clk);
        load <= '0';
      end loop;
    end loop;
    tick <= '0';
    for i in 1 to 3 loop
      wait until rising_edge(clk);
    end loop;
    done <= true;
    wait;
  end process stimulus;

  check : process
    variable ref_acc     : natural := capacity / 2;
    variable ref_n       : natural := 0;
    variable ref_dir     : std_ulogic := '0';
    variable exp_pulse   : std_ulogic := '0';
    variable exp_dir     : std_ulogic := '0';
    variable acc0        : natural := capacity / 2;  -- acc at the period's start
    variable tick_idx    : natural := 0;
    variable pulses      : natural := 0;   -- this period
    variable period      : natural := 0;
    variable total       : natural := 0;
    variable closed_form : natural;
  begin
    wait until rising_edge(clk);
    while not done loop
      if rst = '0' then
        -- this cycle's outputs against the model
        check_equal(pulse, exp_pulse, "period " & integer'image(period) & " pulse");
        if exp_pulse = '1' then
          check_equal(pdir, exp_dir, "period " & integer'image(period) & " pulse direction");
        end if;
        check_equal(acc, ref_acc, "period " & integer'image(period) & " accumulator");

        -- the edge at the end of this cycle
        exp_pulse := '0';
        if tick = '1' then
          ref_acc := ref_acc + ref_n;
          if ref_acc >= capacity then
            ref_acc   := ref_acc - capacity;
            exp_pulse := '1';
            exp_dir   := ref_dir;
            pulses    := pulses + 1;
            total     := total + 1;
            -- the closed form of rt::Dda::run_period, j = pulses - 1
            closed_form := (pulses * capacity - acc0 + ref_n - 1) / ref_n - 1;
            check_equal(tick_idx, closed_form, "period " & integer'image(period) & " pulse " &
                        integer'image(pulses - 1) & " of n = " & integer'image(ref_n) &
                        ": tick by the closed form");
          end if;
          tick_idx := tick_idx + 1;
        end if;
        if load = '1' then
          if tick = '1' then  -- a period ends: exactly n pulses, acc back where it began
            check_equal(tick_idx, capacity, "period " & integer'image(period) & " ticks");
            check_equal(pulses, ref_n, "period " & integer'image(period) & " pulse count");
            check_equal(ref_acc, acc0, "period " & integer'image(period) & " accumulator at its end");
            period := period + 1;
          end if;
          ref_n    := to_integer(load_mag);
          ref_dir  := load_dir;
          acc0     := ref_acc;
          tick_idx := 0;
          pulses   := 0;
        end if;
      end if;
      wait until rising_edge(clk);
    end loop;
    check_equal(period, periods, "periods completed");
    report "tb_dda_axis: " & integer'image(periods) & " periods, " & integer'image(total) &
           " pulses, N = " & integer'image(capacity) & ", " & integer'image(mag_width) & " bits: ok";
    std.env.finish;
  end process check;

  watchdog : process
  begin
    wait for clk_period * (periods + 2) * capacity * (max_gap + 1) + clk_period * 100;
    assert false report "tb_dda_axis: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
