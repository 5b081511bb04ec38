-- Self-checking testbench of pulse_output. Random pulse events, spaced from
-- the legal minimum (pulse_width + dir_setup + dir_hold, at least
-- pulse_width + 1) upwards, random directions (many reversals), the output
-- mode switched at random while no pulse is in flight (`too_close`: one pair
-- a cycle closer than legal, which the design's own check must stop). Two checks:
--  * reference: the waveform predicted from the event list (high in cycles
--    e + 1 + dir_setup .. e + dir_setup + pulse_width, DIR from e + 1),
--    compared every cycle;
--  * protocol, measured on the pins alone: every STEP/PUL/SIG pulse exactly
--    pulse_width cycles, PUL and SIG never together, DIR stable from
--    dir_setup cycles before STEP rises until dir_hold cycles after it falls,
--    and one output pulse per event.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;
use work.sim_support_pkg.all;

entity tb_pulse_output is
  generic (
    pulse_width : positive := 2;
    dir_setup   : natural  := 1;
    dir_hold    : natural  := 1;
    seed        : positive := 1;
    events      : positive := 3000;
    too_close   : boolean  := false  -- one pair of events a cycle too close: the design must stop it
  );
end entity tb_pulse_output;

architecture sim of tb_pulse_output is
  constant clk_period : time := 20 ns;
  constant min_space  : positive := max_of(pulse_width + dir_setup + dir_hold, pulse_width + 1);

  signal clk       : std_ulogic := '0';
  signal rst       : std_ulogic := '1';
  signal mode      : std_ulogic := '0';
  signal pulse     : std_ulogic := '0';
  signal pulse_dir : std_ulogic := '0';
  signal pul_step  : std_ulogic;
  signal sig_dir   : std_ulogic;
  signal done      : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.pulse_output
    generic map (pulse_width => pulse_width, dir_setup => dir_setup, dir_hold => dir_hold)
    port map (clk => clk, rst => rst, step_dir_mode => mode, pulse => pulse, pulse_dir => pulse_dir,
              pul_step => pul_step, sig_dir => sig_dir);

  stimulus : process
    variable rnd : random_t;
  begin
    rnd.init(seed);
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    for e in 1 to events loop
      pulse     <= '1';
      pulse_dir <= rnd.bit1;
      wait until rising_edge(clk);
      pulse <= '0';
      -- the legal minimum most of the time, so back-to-back pulses are common
      if too_close and e = events / 2 then
        for g in 3 to min_space loop
          wait until rising_edge(clk);
        end loop;
      elsif rnd.chance(60) then
        for g in 2 to min_space loop
          wait until rising_edge(clk);
        end loop;
      else
        for g in 2 to min_space + rnd.int(1, 3 * min_space) loop
          wait until rising_edge(clk);
        end loop;
      end if;
      if rnd.chance(3) then  -- switch modes once the pulse has left
        for g in min_space to dir_setup + pulse_width + 1 loop
          wait until rising_edge(clk);
        end loop;
        mode <= not mode;
        wait until rising_edge(clk);
      end if;
    end loop;
    for g in 0 to min_space + 2 loop
      wait until rising_edge(clk);
    end loop;
    done <= true;
    wait;
  end process stimulus;

  reference : process
    type event_array is array (0 to 1) of integer;
    variable ev_cycle : event_array := (others => -1000);  -- the last two events
    variable ev_dir   : std_ulogic_vector(0 to 1) := "00";
    variable cyc      : integer := 0;
    variable high     : boolean;
    variable hdir     : std_ulogic;
    variable dir_lvl  : std_ulogic := '0';
    variable exp_a    : std_ulogic;
    variable exp_b    : std_ulogic;
    variable out_mode : std_ulogic := '0';  -- the mode the outputs of this cycle were made in
  begin
    wait until rising_edge(clk);
    while not done loop
      cyc := cyc + 1;
      if rst = '0' then
        high := false;
        hdir := '0';
        for i in 0 to 1 loop
          if cyc >= ev_cycle(i) + 1 + dir_setup and cyc <= ev_cycle(i) + dir_setup + pulse_width then
            high := true;
            hdir := ev_dir(i);
          end if;
          if cyc = ev_cycle(i) + 1 then
            dir_lvl := ev_dir(i);
          end if;
        end loop;
        if out_mode = '1' then
          exp_a := sl(high);
          exp_b := dir_lvl;
        else
          exp_a := sl(high and hdir = '0');
          exp_b := sl(high and hdir = '1');
        end if;
        check_equal(pul_step, exp_a, "cycle " & integer'image(cyc) & " mode " &
                    std_ulogic'image(out_mode) & " pul_step");
        check_equal(sig_dir, exp_b, "cycle " & integer'image(cyc) & " mode " &
                    std_ulogic'image(out_mode) & " sig_dir");
        if pulse = '1' then  -- event in this cycle
          ev_cycle(0) := ev_cycle(1);
          ev_dir(0)   := ev_dir(1);
          ev_cycle(1) := cyc;
          ev_dir(1)   := pulse_dir;
        end if;
      end if;
      out_mode := mode;
      wait until rising_edge(clk);
    end loop;
    wait;
  end process reference;

  protocol : process
    variable cyc        : integer := 0;
    variable prev_a     : std_ulogic := '0';
    variable prev_b     : std_ulogic := '0';
    variable rise_a     : integer := 0;
    variable rise_b     : integer := 0;
    variable fall       : integer := -1000;  -- last STEP falling edge (first low cycle)
    variable dir_change : integer := -1000;  -- last DIR change (first cycle of the new level)
    variable pulses     : natural := 0;
    variable n_events   : natural := 0;
    variable out_mode   : std_ulogic := '0';
    variable prev_mode  : std_ulogic := '0';
  begin
    wait until rising_edge(clk);
    while not done loop
      cyc := cyc + 1;
      if rst = '0' then
        if pulse = '1' then
          n_events := n_events + 1;
        end if;
        if out_mode /= prev_mode then
          prev_b := sig_dir;  -- the pins change meaning: no edge on sig_dir
        end if;
        if out_mode = '1' then
          if sig_dir /= prev_b then
            assert prev_a = '0' and (pul_step = '0' or dir_setup = 0)
              report "cycle " & integer'image(cyc) & ": DIR changed while STEP high" severity failure;
            assert cyc - fall >= dir_hold
              report "cycle " & integer'image(cyc) & ": DIR hold after STEP fall: expected >= " &
                     integer'image(dir_hold) & ", actual " & integer'image(cyc - fall) severity failure;
            dir_change := cyc;
          end if;
          if pul_step = '1' and prev_a = '0' then
            assert cyc - dir_change >= dir_setup
              report "cycle " & integer'image(cyc) & ": DIR setup before STEP: expected >= " &
                     integer'image(dir_setup) & ", actual " & integer'image(cyc - dir_change)
              severity failure;
          end if;
        else
          assert not (pul_step = '1' and sig_dir = '1')
            report "cycle " & integer'image(cyc) & ": PUL and SIG high together" severity failure;
          if sig_dir = '1' and prev_b = '0' then
            rise_b := cyc;
            pulses := pulses + 1;
          end if;
          if sig_dir = '0' and prev_b = '1' then
            check_equal(cyc - rise_b, pulse_width, "cycle " & integer'image(cyc) & " SIG width");
          end if;
        end if;
        if pul_step = '1' and prev_a = '0' then
          rise_a := cyc;
          pulses := pulses + 1;
        end if;
        if pul_step = '0' and prev_a = '1' then
          check_equal(cyc - rise_a, pulse_width, "cycle " & integer'image(cyc) & " PUL/STEP width");
          fall := cyc;
        end if;
        prev_a := pul_step;
        prev_b := sig_dir;
      end if;
      prev_mode := out_mode;
      out_mode  := mode;
      wait until rising_edge(clk);
    end loop;
    check_equal(pulses, n_events, "output pulses (one per event)");
    report "tb_pulse_output: width " & integer'image(pulse_width) & ", setup " &
           integer'image(dir_setup) & ", hold " & integer'image(dir_hold) & ": " &
           integer'image(pulses) & " pulses: ok";
    std.env.finish;
  end process protocol;

  watchdog : process
  begin
    wait for clk_period * (events * (4 * min_space + dir_setup + pulse_width + 4) + 100);
    assert false report "tb_pulse_output: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
