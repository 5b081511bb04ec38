-- Self-checking testbench of bus_decoder. Random bus writes and reads to
-- every address (unmapped ones included), random status inputs (missed,
-- overrun and period strobes, buffer-full and active levels), clears that
-- collide with events. The check process keeps its own register file and
-- compares every output every cycle: the staged increments, the SEL, DIV and
-- clear effects one cycle after the write, the mode frozen while active,
-- the sticky flags, the saturating MISSED and wrapping PERIODS counters, and
-- the read data one cycle after each read.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;
use work.sim_support_pkg.all;

entity tb_bus_decoder is
  generic (
    axes       : positive := 4;
    mag_width  : positive := 4;
    bus_width  : positive := 8;    -- small, so the counters saturate and wrap
    addr_width : positive := 4;
    div_width  : positive := 8;
    seed       : positive := 1;
    cycles     : positive := 60000
  );
end entity tb_bus_decoder;

architecture sim of tb_bus_decoder is
  constant clk_period : time := 20 ns;
  constant count_top  : natural := 2 ** bus_width - 1;

  signal clk          : std_ulogic := '0';
  signal rst          : std_ulogic := '1';
  signal bus_addr     : unsigned(addr_width - 1 downto 0) := (others => '0');
  signal bus_wdata    : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
  signal bus_we       : std_ulogic := '0';
  signal bus_re       : std_ulogic := '0';
  signal bus_rdata    : std_ulogic_vector(bus_width - 1 downto 0);
  signal staged_mag   : std_ulogic_vector(axes * mag_width - 1 downto 0);
  signal staged_dir   : std_ulogic_vector(axes - 1 downto 0);
  signal sel          : std_ulogic;
  signal div_wr       : std_ulogic;
  signal div_value    : unsigned(div_width - 1 downto 0);
  signal run          : std_ulogic;
  signal mode         : std_ulogic;
  signal buf_full     : std_ulogic := '0';
  signal active       : std_ulogic := '0';
  signal missed       : std_ulogic := '0';
  signal overrun      : std_ulogic := '0';
  signal period_start : std_ulogic := '0';
  signal done         : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.bus_decoder
    generic map (axes => axes, mag_width => mag_width, bus_width => bus_width,
                 addr_width => addr_width, div_width => div_width, reset_divider => 3)
    port map (
      clk => clk, rst => rst, bus_addr => bus_addr, bus_wdata => bus_wdata, bus_we => bus_we,
      bus_re => bus_re, bus_rdata => bus_rdata, staged_mag => staged_mag, staged_dir => staged_dir,
      sel => sel, div_wr => div_wr, div_value => div_value, run => run, step_dir_mode => mode,
      buf_full => buf_full, active => active, missed => missed, overrun => overrun,
      period_start => period_start);

  stimulus : process
    variable rnd : random_t;
    variable wd  : std_ulogic_vector(bus_width - 1 downto 0);
  begin
    rnd.init(seed);
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    for c in 1 to cycles loop
      for b in wd'range loop
        wd(b) := rnd.bit1;
      end loop;
      if rnd.chance(2) then  -- clears are rarer than other CTRL writes
        wd(ctrl_clear_bit) := '1';
      else
        wd(ctrl_clear_bit) := '0';
      end if;
      bus_wdata <= wd;
      bus_addr  <= to_unsigned(rnd.int(0, 2 ** addr_width - 1), addr_width);
      bus_we    <= sl(rnd.chance(40));
      bus_re    <= sl(rnd.chance(40));
      missed    <= sl(rnd.chance(10));
      overrun   <= sl(rnd.chance(3));
      period_start <= sl(rnd.chance(30));
      if rnd.chance(5) then
        active <= not active;
      end if;
      buf_full  <= rnd.bit1;
      wait until rising_edge(clk);
    end loop;
    bus_we <= '0';
    bus_re <= '0';
    wait until rising_edge(clk);
    done <= true;
    wait;
  end process stimulus;

  check : process
    variable mag_m     : std_ulogic_vector(axes * mag_width - 1 downto 0) := (others => '0');
    variable dir_m     : std_ulogic_vector(axes - 1 downto 0) := (others => '0');
    variable sel_m     : std_ulogic := '0';
    variable divwr_m   : std_ulogic := '0';
    variable div_m     : natural := 3;
    variable run_m     : std_ulogic := '0';
    variable mode_m    : std_ulogic := '0';
    variable missed_s  : std_ulogic := '0';
    variable overrun_s : std_ulogic := '0';
    variable missed_n  : natural := 0;
    variable periods_n : natural := 0;
    variable rdata_m   : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
    variable a         : natural;
    variable clear     : boolean;
    variable reads     : natural := 0;
    variable saturated : boolean := false;
  begin
    wait until rising_edge(clk);
    while not done loop
      if rst = '0' then
        for i in 0 to axes - 1 loop
          check_equal(to_integer(unsigned(staged_mag((i + 1) * mag_width - 1 downto i * mag_width))),
                      to_integer(unsigned(mag_m((i + 1) * mag_width - 1 downto i * mag_width))),
                      "axis " & integer'image(i) & " staged magnitude");
          check_equal(staged_dir(i), dir_m(i), "axis " & integer'image(i) & " staged direction");
        end loop;
        check_equal(sel, sel_m, "SEL strobe");
        check_equal(div_wr, divwr_m, "divider write strobe");
        check_equal(to_integer(div_value), div_m, "divider value");
        check_equal(run, run_m, "run");
        check_equal(mode, mode_m, "output mode");
        check_equal(to_integer(unsigned(bus_rdata)), to_integer(unsigned(rdata_m)), "read data");

        -- the edge; a read sees the registers as they were before it
        a       := to_integer(bus_addr);
        rdata_m := (others => '0');
        if bus_re = '1' then
          reads := reads + 1;
          if a = addr_div(axes) then
            rdata_m(div_width - 1 downto 0) := std_ulogic_vector(to_unsigned(div_m, div_width));
          elsif a = addr_ctrl(axes) then
            rdata_m(ctrl_run_bit)      := run_m;
            rdata_m(ctrl_step_dir_bit) := mode_m;
          elsif a = addr_status(axes) then
            rdata_m(status_full_bit)    := buf_full;
            rdata_m(status_missed_bit)  := missed_s;
            rdata_m(status_overrun_bit) := overrun_s;
            rdata_m(status_active_bit)  := active;
          elsif a = addr_missed(axes) then
            rdata_m := std_ulogic_vector(to_unsigned(missed_n, bus_width));
          elsif a = addr_periods(axes) then
            rdata_m := std_ulogic_vector(to_unsigned(periods_n, bus_width));
          end if;
        end if;
        clear   := false;
        sel_m   := '0';
        divwr_m := '0';
        if bus_we = '1' then
          if a < axes then
            mag_m((a + 1) * mag_width - 1 downto a * mag_width) := bus_wdata(mag_width - 1 downto 0);
            dir_m(a) := bus_wdata(bus_width - 1);
          elsif a = addr_sel(axes) then
            sel_m := '1';
          elsif a = addr_div(axes) then
            div_m   := to_integer(unsigned(bus_wdata(div_width - 1 downto 0)));
            divwr_m := '1';
          elsif a = addr_ctrl(axes) then
            run_m := bus_wdata(ctrl_run_bit);
            if active = '0' then
              mode_m := bus_wdata(ctrl_step_dir_bit);
            end if;
            clear := bus_wdata(ctrl_clear_bit) = '1';
          end if;
        end if;
        -- status: a clear and an event on the same edge leave the event counted
        if clear then
          missed_s  := '0';
          overrun_s := '0';
          missed_n  := 0;
          periods_n := 0;
        end if;
        if missed = '1' then
          missed_s := '1';
          if missed_n < count_top then
            missed_n := missed_n + 1;
          else
            saturated := true;
          end if;
        end if;
        if overrun = '1' then
          overrun_s := '1';
        end if;
        if period_start = '1' then
          periods_n := (periods_n + 1) mod (count_top + 1);
        end if;
      end if;
      wait until rising_edge(clk);
    end loop;
    assert reads > 1000 and (saturated or count_top > cycles / 20)
      report "tb_bus_decoder: too little exercised (reads " & integer'image(reads) &
             ", MISSED saturated " & boolean'image(saturated) & ")" severity failure;
    report "tb_bus_decoder: " & integer'image(axes) & " axes, " & integer'image(cycles) &
           " cycles, " & integer'image(reads) & " reads: ok";
    std.env.finish;
  end process check;

  watchdog : process
  begin
    wait for clk_period * (cycles + 100);
    assert false report "tb_bus_decoder: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
