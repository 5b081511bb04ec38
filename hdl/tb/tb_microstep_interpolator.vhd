-- Self-checking testbench of microstep_interpolator, the whole interpolator
-- on its bus, as the PC's driver uses it (Chi, Wu and Cui 2020 §3.1, Fig. 6-7).
--
-- Stimulus: a software model. After reset it writes the first period's
-- increments, SEL and run; then on every Com fall (the interrupt) it waits
-- its response time, writes the next period's increments one axis per bus
-- write spread over the port time, a new divider when the feed override
-- changes, and SEL. The increments are random (0, the maximum, reversals,
-- everything between; fixed seed) or replayed from a vector file (textio,
-- `vector_in`: per line "D n0 n1 ..." — the divider and the signed
-- increment of each axis — '#' lines are comments). Random runs can also be
-- late (response jitter past the period: missed periods), SEL twice
-- (overrun), change the divider below its minimum (clamped), and stop, switch
-- the output mode and restart.
--
-- Three independent checks:
--  * reference: a clock-by-clock model of the register map, buffers, divider,
--    sequencer and the DDA tick loop of rt::Dda::reference_period, written
--    in absolute cycle arithmetic; Com, missed, and every output pin are
--    compared every cycle;
--  * observer: decodes the pins alone — the period from Com's fall, D from
--    the length of Com low, each pulse's tick from its cycle (it must sit
--    exactly on the tick grid) — and writes the pulse trains (`pulses_out`,
--    "P period D" per period, "period tick axis +|-" per pulse) and the
--    signed pulse totals per axis (`totals_out`) for the comparison with the
--    C++ DDA (tests/hdl/);
--  * clean runs (`expect_clean`): no missed period, no overrun, every
--    increment output exactly once in its own period; `check_uniform`: the
--    pulse gaps in a period are floor(N/n) or ceil(N/n) ticks;
--    `expect_period_ns`: every period lasts exactly that; `expect_peak_hz`:
--    some axis reached this step rate in some period.
-- At the end the STATUS, MISSED and PERIODS registers are read over the bus
-- and compared with the model. A watchdog fails a run whose periods stall.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

use work.lcnc_hdl_pkg.all;
use work.sim_support_pkg.all;

entity tb_microstep_interpolator is
  generic (
    -- the design (defaults: the paper's preset, 50 MHz / 125 = 400 kHz, N = 30: 75 µs)
    axes          : positive := 4;
    mag_width     : positive := 4;
    capacity      : positive := 30;
    reset_divider : positive := 125;
    min_divider   : positive := 80;
    pulse_width   : positive := 40;
    dir_setup     : natural  := 20;
    dir_hold      : natural  := 20;
    clk_hz        : positive := 50_000_000;
    -- the software model
    seed          : positive := 1;
    periods       : positive := 200;     -- random increments: periods streamed
    step_dir      : boolean  := false;   -- output mode at start
    restart_at    : natural  := 0;       -- random: stop, switch mode, restart before this period; 0 never
    response_ns   : natural  := 15_000;  -- Com fall to the first bus write
    port_ns       : natural  := 5_000;   -- first axis write to SEL
    jitter_ns     : natural  := 0;       -- extra response, uniform in 0 .. jitter_ns
    zero_pct      : natural  := 15;      -- random increments: chance of 0
    max_pct       : natural  := 15;      -- random increments: chance of the maximum
    override_pct  : natural  := 0;       -- chance per period of a new divider
    divider_max   : natural  := 0;       -- random dividers up to this; 0: 2 * reset_divider
    overrun_pct   : natural  := 0;       -- chance per period of a second SEL, and of a mode change while running
    -- what a run must show
    expect_clean     : boolean := false;
    check_uniform    : boolean := false;
    expect_period_ns : natural := 0;
    expect_peak_hz   : natural := 0;     -- the highest per-axis step rate seen must reach this
    reference_model  : boolean := true;  -- off only for long replays (the observer still checks)
    -- files
    vector_in     : string := "";
    pulses_out    : string := "";
    totals_out    : string := ""
  );
end entity tb_microstep_interpolator;

architecture sim of tb_microstep_interpolator is
  constant clk_period : time     := 1 sec / clk_hz;
  constant bus_width  : positive := 16;
  constant addr_width : positive := bits_for(addr_count(axes) - 1);
  constant div_width  : positive := 16;
  constant n_max      : natural  := 2 ** mag_width - 1;
  constant div_lim    : positive := max_of(divider_max, 2 * reset_divider);
  constant replay     : boolean  := vector_in'length > 0;

  type axis_ints is array (0 to axes - 1) of integer;

  signal clk       : std_ulogic := '0';
  signal rst       : std_ulogic := '1';
  signal bus_addr  : unsigned(addr_width - 1 downto 0) := (others => '0');
  signal bus_wdata : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
  signal bus_we    : std_ulogic := '0';
  signal bus_re    : std_ulogic := '0';
  signal bus_rdata : std_ulogic_vector(bus_width - 1 downto 0);
  signal com       : std_ulogic;
  signal missed    : std_ulogic;
  signal pul_step  : std_ulogic_vector(axes - 1 downto 0);
  signal sig_dir   : std_ulogic_vector(axes - 1 downto 0);

  -- between the processes
  signal com_falls  : natural := 0;         -- interrupts raised
  signal tb_mode    : std_ulogic := '0';    -- output mode the software set
  signal sw_stops   : natural := 0;         -- run = 0 writes
  signal sw_done    : boolean := false;
  signal sw_periods : natural := 0;         -- periods the software wrote
  signal sw_totals  : axis_ints := (others => 0);
  signal rd_status  : integer := -1;
  signal rd_missed  : integer := -1;
  signal rd_periods : integer := -1;
  signal m_done     : boolean := false;
  signal m_totals   : axis_ints := (others => 0);
  signal m_missed   : natural := 0;
  signal m_overruns : natural := 0;
  signal m_periods  : natural := 0;
  signal o_done     : boolean := false;
  signal o_totals   : axis_ints := (others => 0);
  signal o_periods  : natural := 0;
  signal o_peak_hz  : real := 0.0;
  signal o_pulses   : natural := 0;

  -- signed increment the software wrote for period p, axis i: index p * axes + i
  shared variable written : int_store_t;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.microstep_interpolator
    generic map (
      axes => axes, mag_width => mag_width, capacity => capacity, bus_width => bus_width,
      addr_width => addr_width, div_width => div_width, reset_divider => reset_divider,
      min_divider => min_divider, pulse_width => pulse_width, dir_setup => dir_setup,
      dir_hold => dir_hold)
    port map (
      clk => clk, rst => rst, bus_addr => bus_addr, bus_wdata => bus_wdata, bus_we => bus_we,
      bus_re => bus_re, bus_rdata => bus_rdata, com => com, tick => open, missed => missed,
      pul_step => pul_step, sig_dir => sig_dir);

  interrupts : process
  begin
    wait until com = '0';
    com_falls <= com_falls + 1;
  end process interrupts;

  ------------------------------------------------------------------------------
  -- The software model (the PC's interrupt handler).
  ------------------------------------------------------------------------------
  software : process
    variable rnd      : random_t;
    variable handled  : natural := 0;
    variable mode     : std_ulogic := '0';
    variable d_cur    : integer := reset_divider;  -- the divider last written
    variable d_next   : integer;
    variable inc      : axis_ints;
    variable totals   : axis_ints := (others => 0);
    variable p        : natural := 0;  -- the period being written
    variable more     : boolean;
    variable v        : integer;
    variable gap      : time;
    file vec          : text;
    variable vec_line : line;
    variable status   : file_open_status;
    variable line_no  : natural := 0;
    variable ok       : boolean;

    procedure bus_write(addr : natural; data : std_ulogic_vector(bus_width - 1 downto 0)) is
    begin
      bus_addr  <= to_unsigned(addr, addr_width);
      bus_wdata <= data;
      bus_we    <= '1';
      wait until rising_edge(clk);
      bus_we <= '0';
    end procedure;

    procedure bus_read(addr : natural; value : out integer) is
    begin
      bus_addr <= to_unsigned(addr, addr_width);
      bus_re   <= '1';
      wait until rising_edge(clk);
      bus_re <= '0';
      wait until rising_edge(clk);
      value := to_integer(unsigned(bus_rdata));
    end procedure;

    function ctrl_word(run, step_dir_mode : std_ulogic; clear : boolean) return std_ulogic_vector is
      variable w : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
    begin
      w(ctrl_run_bit)      := run;
      w(ctrl_step_dir_bit) := step_dir_mode;
      w(ctrl_clear_bit)    := sl(clear);
      return w;
    end function;

    function inc_word(n : integer) return std_ulogic_vector is
      variable w : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
    begin
      w(mag_width - 1 downto 0) := std_ulogic_vector(to_unsigned(abs n, mag_width));
      w(bus_width - 1)          := sl(n < 0);
      return w;
    end function;

    -- The next period's divider and increments: from the file or random.
    -- more = false at the end of the stream.
    procedure next_period is
      variable n : integer;
    begin
      more := true;
      if replay then
        loop
          if endfile(vec) then
            more := false;
            return;
          end if;
          readline(vec, vec_line);
          line_no := line_no + 1;
          exit when vec_line'length > 0 and vec_line(vec_line'low) /= '#';
        end loop;
        read(vec_line, d_next, ok);
        assert ok report vector_in & ":" & integer'image(line_no) & ": expected the divider"
          severity failure;
        for i in 0 to axes - 1 loop
          read(vec_line, n, ok);
          if not ok then
            n := 0;  -- fewer columns than axes: the rest stand still
          end if;
          assert abs n <= n_max
            report vector_in & ":" & integer'image(line_no) & ": increment " & integer'image(n) &
                   " of axis " & integer'image(i) & " exceeds " & integer'image(n_max)
            severity failure;
          inc(i) := n;
        end loop;
        read(vec_line, n, ok);
        assert not ok report vector_in & ":" & integer'image(line_no) & ": more than " &
          integer'image(axes) & " axes" severity failure;
      else
        if p >= periods then
          more := false;
          return;
        end if;
        d_next := d_cur;
        if rnd.chance(override_pct) then
          if min_divider > 1 and rnd.chance(25) then
            d_next := rnd.int(1, min_divider - 1);  -- below the minimum: clamped
          else
            d_next := rnd.int(min_divider, div_lim);
          end if;
        end if;
        for i in 0 to axes - 1 loop
          if rnd.chance(zero_pct) then
            n := 0;
          elsif rnd.chance(max_pct * 100 / max_of(1, 100 - zero_pct)) then
            n := n_max;
          else
            n := rnd.int(0, n_max);
          end if;
          if rnd.bit1 = '1' then
            n := -n;
          end if;
          inc(i) := n;
        end loop;
      end if;
    end procedure;

    -- Writes divider (when it changes), the increments and SEL for period p.
    procedure write_period(spread, running : boolean) is
    begin
      gap := (port_ns * 1 ns) / (axes + 1);
      for i in 0 to axes - 1 loop
        if spread and i > 0 then
          wait for gap;
        end if;
        bus_write(i, inc_word(inc(i)));
        written.set(p * axes + i, inc(i));
        totals(i) := totals(i) + inc(i);
      end loop;
      if d_next /= d_cur then
        bus_write(addr_div(axes), std_ulogic_vector(to_unsigned(d_next, bus_width)));
        d_cur := d_next;
      end if;
      if spread then
        wait for gap;
      end if;
      bus_write(addr_sel(axes), (others => '0'));
      if rnd.chance(overrun_pct) then
        bus_write(addr_sel(axes), (others => '0'));  -- a second SEL: overrun, ignored
      end if;
      if running and rnd.chance(overrun_pct) then  -- a mode change while running: ignored
        bus_write(addr_ctrl(axes), ctrl_word('1', not mode, false));
      end if;
      p := p + 1;
    end procedure;

    procedure wait_idle is
      variable s : integer;
    begin
      loop
        for c in 1 to 50 loop
          wait until rising_edge(clk);
        end loop;
        bus_read(addr_status(axes), s);
        exit when (s / 2 ** status_active_bit) mod 2 = 0;
      end loop;
      for c in 1 to dir_setup + pulse_width + 4 loop  -- the last pulse leaves the pins
        wait until rising_edge(clk);
      end loop;
    end procedure;
  begin
    rnd.init(seed);
    if replay then
      file_open(status, vec, vector_in, read_mode);
      assert status = open_ok report "cannot read vector file '" & vector_in & "'" severity failure;
    end if;
    for c in 1 to 4 loop
      wait until rising_edge(clk);
    end loop;
    rst <= '0';
    wait until rising_edge(clk);
    mode := sl(step_dir);
    tb_mode <= mode;
    bus_write(addr_ctrl(axes), ctrl_word('0', mode, true));
    next_period;
    assert more report "no increments to run" severity failure;
    write_period(false, false);
    bus_write(addr_ctrl(axes), ctrl_word('1', mode, false));
    loop
      next_period;
      exit when not more;
      -- the interrupt of the period before the one being written
      if com_falls <= handled then
        wait until com_falls > handled;
      end if;
      handled := com_falls;
      if not replay and p = restart_at then
        -- stop after this period, switch the output mode, restart with period p
        bus_write(addr_ctrl(axes), ctrl_word('0', mode, false));
        sw_stops <= sw_stops + 1;
        wait_idle;
        mode := not mode;
        tb_mode <= mode;
        bus_write(addr_ctrl(axes), ctrl_word('0', mode, false));
        write_period(false, false);
        bus_write(addr_ctrl(axes), ctrl_word('1', mode, false));
      else
        v := 0;
        if jitter_ns > 0 then
          v := rnd.int(0, jitter_ns);
        end if;
        if response_ns + v > 0 then
          wait for (response_ns + v) * 1 ns;
        end if;
        write_period(port_ns > 0, true);
      end if;
    end loop;
    -- stop after the last period: run = 0 once it has started
    if com_falls <= handled then
      wait until com_falls > handled;
    end if;
    bus_write(addr_ctrl(axes), ctrl_word('0', mode, false));
    sw_stops <= sw_stops + 1;
    wait_idle;
    bus_read(addr_status(axes), v);
    rd_status <= v;
    bus_read(addr_missed(axes), v);
    rd_missed <= v;
    bus_read(addr_periods(axes), v);
    rd_periods <= v;
    sw_periods <= p;
    sw_totals  <= totals;
    sw_done    <= true;
    wait;
  end process software;

  ------------------------------------------------------------------------------
  -- Reference: the interpolator clock by clock, in absolute cycle arithmetic.
  ------------------------------------------------------------------------------
  reference : process
    variable k        : integer := 0;   -- this cycle
    variable run_m    : boolean := false;
    variable mode_m   : std_ulogic := '0';
    variable out_mode : std_ulogic := '0';  -- the mode this cycle's output registers were made in
    variable act      : boolean := false;
    variable act_k    : boolean;
    variable c0       : integer := 0;   -- first cycle of the running period
    variable d        : integer := reset_divider;
    variable t        : integer;
    variable tick_now : boolean;
    variable last     : boolean;
    variable load     : boolean;
    variable div_reg  : natural := reset_divider;  -- the decoder's DIV register
    variable div_buf  : natural := reset_divider;  -- the clock divider's buffer
    variable div_stb  : boolean := false;          -- DIV strobe in this cycle
    variable sel_stb  : boolean := false;          -- SEL strobe in this cycle
    variable staged   : axis_ints := (others => 0);
    variable full     : boolean := false;
    variable buf      : axis_ints := (others => 0);
    variable n        : axis_ints := (others => 0);   -- signed increment being output
    variable acc      : axis_ints := (others => capacity / 2);
    variable ev_old   : axis_ints := (others => -1000);  -- the last two pulse events (cycles)
    variable ev_new   : axis_ints := (others => -1000);
    variable dir_old  : std_ulogic_vector(0 to axes - 1) := (others => '0');
    variable dir_new  : std_ulogic_vector(0 to axes - 1) := (others => '0');
    variable dir_lvl  : std_ulogic_vector(0 to axes - 1) := (others => '0');
    variable exp_miss : boolean := false;
    variable totals   : axis_ints := (others => 0);
    variable missed_n : natural := 0;
    variable overruns : natural := 0;
    variable started  : natural := 0;
    variable high     : boolean;
    variable hdir     : std_ulogic;
    variable exp_a    : std_ulogic;
    variable exp_b    : std_ulogic;
    variable a        : natural;
    variable w        : std_ulogic_vector(bus_width - 1 downto 0);
    variable run_nx   : boolean;
    variable mode_nx  : std_ulogic;

    impure function where return string is
    begin
      return "cycle " & integer'image(k) & ", period " & integer'image(started - 1);
    end function;
  begin
    if not reference_model then
      m_done <= true;
      wait;
    end if;
    wait until rising_edge(clk);
    while not sw_done loop
      k := k + 1;
      if rst = '0' then
        -- this cycle's pins against the model
        -- (messages are built only on a mismatch: this runs every cycle)
        if com /= sl(not (act and k - c0 < d)) then
          check_equal(com, sl(not (act and k - c0 < d)), where & ": Com");
        end if;
        if missed /= sl(exp_miss) then
          check_equal(missed, sl(exp_miss), where & ": missed");
        end if;
        for i in 0 to axes - 1 loop
          high := false;
          hdir := '0';
          if k >= ev_old(i) + 1 + dir_setup and k <= ev_old(i) + dir_setup + pulse_width then
            high := true;
            hdir := dir_old(i);
          end if;
          if k >= ev_new(i) + 1 + dir_setup and k <= ev_new(i) + dir_setup + pulse_width then
            high := true;
            hdir := dir_new(i);
          end if;
          if k = ev_new(i) + 1 then
            dir_lvl(i) := dir_new(i);
          end if;
          if out_mode = '1' then
            exp_a := sl(high);
            exp_b := dir_lvl(i);
          else
            exp_a := sl(high and hdir = '0');
            exp_b := sl(high and hdir = '1');
          end if;
          if pul_step(i) /= exp_a or sig_dir(i) /= exp_b then
            if out_mode = '1' then
              check_equal(pul_step(i), exp_a, where & ", axis " & integer'image(i) & ": STEP");
              check_equal(sig_dir(i), exp_b, where & ", axis " & integer'image(i) & ": DIR");
            else
              check_equal(pul_step(i), exp_a, where & ", axis " & integer'image(i) & ": PUL");
              check_equal(sig_dir(i), exp_b, where & ", axis " & integer'image(i) & ": SIG");
            end if;
          end if;
        end loop;

        -- the edge at the end of this cycle
        act_k    := act;
        tick_now := act and k >= c0 + d - 1 and (k - c0 - d + 1) mod d = 0;
        t        := (k - c0 - d + 1) / d;
        last     := tick_now and t = capacity - 1;
        if tick_now then
          for i in 0 to axes - 1 loop
            acc(i) := acc(i) + abs n(i);
            if acc(i) >= capacity then
              acc(i)     := acc(i) - capacity;
              ev_old(i)  := ev_new(i);
              dir_old(i) := dir_new(i);
              ev_new(i)  := k + 1;
              dir_new(i) := sl(n(i) < 0);
              if n(i) < 0 then
                totals(i) := totals(i) - 1;
              else
                totals(i) := totals(i) + 1;
              end if;
            end if;
          end loop;
        end if;
        load     := run_m and (not act or last);
        exp_miss := false;
        if load then
          c0 := k + 1;
          d  := max_of(div_buf, min_divider);
          act := true;
          started := started + 1;
          exp_miss := not full;
          if full then
            n := buf;
          else
            n := (others => 0);
            missed_n := missed_n + 1;
          end if;
          full := false;
        elsif last then
          act := false;  -- run = 0: stopped after the last tick
        end if;
        if sel_stb then
          if full then
            overruns := overruns + 1;
          else
            buf  := staged;
            full := true;
          end if;
        end if;
        if div_stb then
          div_buf := div_reg;
        end if;
        sel_stb := false;
        div_stb := false;
        run_nx  := run_m;
        mode_nx := mode_m;
        if bus_we = '1' then
          a := to_integer(bus_addr);
          w := bus_wdata;
          if a < axes then
            staged(a) := to_integer(unsigned(w(mag_width - 1 downto 0)));
            if w(bus_width - 1) = '1' then
              staged(a) := -staged(a);
            end if;
          elsif a = addr_sel(axes) then
            sel_stb := true;
          elsif a = addr_div(axes) then
            div_reg := to_integer(unsigned(w(div_width - 1 downto 0)));
            div_stb := true;
          elsif a = addr_ctrl(axes) then
            run_nx := w(ctrl_run_bit) = '1';
            if not act_k then
              mode_nx := w(ctrl_step_dir_bit);
            end if;
          end if;
        end if;
        out_mode := mode_m;
        run_m    := run_nx;
        mode_m   := mode_nx;
      end if;
      wait until rising_edge(clk);
    end loop;
    m_totals   <= totals;
    m_missed   <= missed_n;
    m_overruns <= overruns;
    m_periods  <= started;
    m_done     <= true;
    wait;
  end process reference;

  ------------------------------------------------------------------------------
  -- Observer: the pulse trains decoded from the pins alone.
  ------------------------------------------------------------------------------
  observer : process
    constant slots     : natural := 2;  -- the running period and the one before
    variable k         : integer := 0;
    variable prev_com  : std_ulogic := '1';
    variable prev_a    : std_ulogic_vector(axes - 1 downto 0) := (others => '0');
    variable prev_b    : std_ulogic_vector(axes - 1 downto 0) := (others => '0');
    variable p         : integer := -1;  -- period index of the running period
    variable c0        : integer := 0;
    variable d         : integer := 0;
    variable c0_prev   : integer := 0;
    variable d_prev    : integer := 0;
    variable stops_at  : natural := 0;   -- sw_stops at the last Com fall
    variable x         : integer;        -- the tick's cycle
    variable pp        : integer;
    variable pc0       : integer;
    variable pd        : integer;
    variable t         : integer;
    variable rise      : boolean;
    variable neg       : boolean;
    variable totals    : axis_ints := (others => 0);
    variable counts    : int_array(0 to slots * axes - 1) := (others => 0);
    variable ticks     : int_array(0 to slots * axes * capacity - 1) := (others => 0);
    variable peak_hz   : real := 0.0;
    variable complete  : natural := 0;
    variable pulses_n  : natural := 0;
    file pulses_f      : text;
    variable l         : line;
    variable status    : file_open_status;

    -- period q is complete: its counts against what the software wrote,
    -- the uniform spacing, the peak step rate
    procedure close_period(q : integer; q_d : integer) is
      variable s, cnt, exp, gap, lo, hi : integer;
    begin
      if q < 0 then
        return;
      end if;
      s := q mod slots;
      for i in 0 to axes - 1 loop
        cnt := counts(s * axes + i);
        if expect_clean then
          exp := written.get(q * axes + i);
          check_equal(cnt, abs exp, "period " & integer'image(q) & ", axis " & integer'image(i) &
                      ": pulses output for the increment written");
        end if;
        if check_uniform and cnt > 1 then
          lo := capacity / cnt;
          hi := (capacity + cnt - 1) / cnt;
          for j in 1 to cnt - 1 loop
            gap := ticks((s * axes + i) * capacity + j) - ticks((s * axes + i) * capacity + j - 1);
            assert gap = lo or gap = hi
              report "period " & integer'image(q) & ", axis " & integer'image(i) & ": " &
                     integer'image(cnt) & " pulses not uniform: gap " & integer'image(gap) &
                     " ticks between pulse " & integer'image(j - 1) & " and " & integer'image(j) &
                     ", expected " & integer'image(lo) & " or " & integer'image(hi)
              severity failure;
          end loop;
        end if;
        if real(cnt) * real(clk_hz) / real(capacity * q_d) > peak_hz then
          peak_hz := real(cnt) * real(clk_hz) / real(capacity * q_d);
        end if;
        counts(s * axes + i) := 0;
      end loop;
      complete := complete + 1;
    end procedure;
  begin
    if pulses_out'length > 0 then
      file_open(status, pulses_f, pulses_out, write_mode);
      assert status = open_ok report "cannot write '" & pulses_out & "'" severity failure;
    end if;
    wait until rst = '0';
    while not sw_done loop
      -- Pins are registers: they change only just after a rising edge. Wake
      -- on a change, let the edge's deltas settle, and take the pins of the
      -- cycle that began at that edge; k numbers cycles (only differences
      -- of k are used). Waking on changes only keeps long replays fast.
      wait on com, pul_step, sig_dir, sw_done;
      exit when sw_done;
      wait for clk_period / 4;
      k := (now + clk_period / 2) / clk_period;
      -- pulses first: a pulse of the period before may rise with Com's fall
      for i in 0 to axes - 1 loop
        rise := false;
        neg  := false;
        if tb_mode = '1' then
          if pul_step(i) = '1' and prev_a(i) = '0' then
            rise := true;
            neg  := sig_dir(i) = '1';
          end if;
        else
          if pul_step(i) = '1' and prev_a(i) = '0' then
            rise := true;
          end if;
          if sig_dir(i) = '1' and prev_b(i) = '0' then
            assert not rise report "cycle " & integer'image(k) & ", axis " & integer'image(i) &
              ": PUL and SIG rise together" severity failure;
            rise := true;
            neg  := true;
          end if;
        end if;
        if rise then
          x := k - dir_setup - 2;
          if x >= c0 then
            pp := p;  pc0 := c0;  pd := d;
          else
            pp := p - 1;  pc0 := c0_prev;  pd := d_prev;
          end if;
          assert pp >= 0 and pd > 0 and x >= pc0 + pd - 1 and (x - pc0 - pd + 1) mod pd = 0
            report "cycle " & integer'image(k) & ", axis " & integer'image(i) &
                   ": pulse off the tick grid (period " & integer'image(pp) & " from cycle " &
                   integer'image(pc0) & ", D = " & integer'image(pd) & ")"
            severity failure;
          t := (x - pc0 - pd + 1) / pd;
          assert t < capacity
            report "cycle " & integer'image(k) & ", axis " & integer'image(i) & ": tick " &
                   integer'image(t) & " beyond the period" severity failure;
          if neg then
            totals(i) := totals(i) - 1;
          else
            totals(i) := totals(i) + 1;
          end if;
          pulses_n := pulses_n + 1;
          ticks(((pp mod slots) * axes + i) * capacity + counts((pp mod slots) * axes + i)) := t;
          counts((pp mod slots) * axes + i) := counts((pp mod slots) * axes + i) + 1;
          if pulses_out'length > 0 then
            write(l, pp);
            write(l, character'(' '));
            write(l, t);
            write(l, character'(' '));
            write(l, i);
            write(l, character'(' '));
            if neg then
              write(l, character'('-'));
            else
              write(l, character'('+'));
            end if;
            writeline(pulses_f, l);
          end if;
        end if;
        prev_a(i) := pul_step(i);
        prev_b(i) := sig_dir(i);
      end loop;

      if com = '0' and prev_com = '1' then  -- a period starts
        if p >= 0 and sw_stops = stops_at then
          check_equal(k - c0, capacity * d, "period " & integer'image(p) &
                      ": cycles from Com fall to Com fall (N * D)");
          if expect_period_ns > 0 then
            assert (k - c0) * clk_period = expect_period_ns * 1 ns
              report "period " & integer'image(p) & ": lasted " & time'image((k - c0) * clk_period) &
                     ", expected " & integer'image(expect_period_ns) & " ns"
              severity failure;
          end if;
        end if;
        stops_at := sw_stops;
        c0_prev  := c0;
        d_prev   := d;
        c0       := k;
        d        := 0;
        p        := p + 1;
      elsif com = '1' and prev_com = '0' then  -- Com rises after one tick: D
        d := k - c0;
        close_period(p - 1, d_prev);
        if pulses_out'length > 0 then
          write(l, string'("P "));
          write(l, p);
          write(l, character'(' '));
          write(l, d);
          writeline(pulses_f, l);
        end if;
      end if;
      prev_com := com;
    end loop;
    close_period(p, d);
    if pulses_out'length > 0 then
      file_close(pulses_f);
    end if;
    o_totals  <= totals;
    o_periods <= p + 1;
    o_peak_hz <= peak_hz;
    o_pulses  <= pulses_n;
    o_done    <= true;
    wait;
  end process observer;

  ------------------------------------------------------------------------------
  -- The end: registers, model, observer and software agree.
  ------------------------------------------------------------------------------
  final : process
    file totals_f : text;
    variable l      : line;
    variable status : file_open_status;
  begin
    wait until m_done and o_done;
    check_equal(rd_periods, o_periods mod 2 ** bus_width, "PERIODS register vs periods seen on Com");
    if reference_model then
      check_equal(o_periods, m_periods, "periods seen on Com vs model");
      check_equal(rd_missed, m_missed, "MISSED register");
      check_equal((rd_status / 2 ** status_missed_bit) mod 2, bool_int(m_missed > 0), "STATUS missed flag");
      check_equal((rd_status / 2 ** status_overrun_bit) mod 2, bool_int(m_overruns > 0), "STATUS overrun flag");
      for i in 0 to axes - 1 loop
        check_equal(o_totals(i), m_totals(i), "axis " & integer'image(i) & ": signed pulses, pins vs model");
      end loop;
    end if;
    if expect_clean then
      check_equal(rd_missed, 0, "missed periods (MISSED register)");
      check_equal((rd_status / 2 ** status_overrun_bit) mod 2, 0, "overrun (STATUS)");
      check_equal(o_periods, sw_periods, "periods run vs periods written");
      for i in 0 to axes - 1 loop
        check_equal(o_totals(i), sw_totals(i), "axis " & integer'image(i) &
                    ": signed pulses vs the sum of increments written");
      end loop;
    end if;
    assert o_peak_hz >= real(expect_peak_hz)
      report "peak step rate per axis: expected >= " & integer'image(expect_peak_hz) &
             " pulses/s, actual " & integer'image(integer(o_peak_hz))
      severity failure;
    if totals_out'length > 0 then
      file_open(status, totals_f, totals_out, write_mode);
      assert status = open_ok report "cannot write '" & totals_out & "'" severity failure;
      for i in 0 to axes - 1 loop
        write(l, i);
        write(l, character'(' '));
        write(l, o_totals(i));
        writeline(totals_f, l);
      end loop;
      file_close(totals_f);
    end if;
    report "tb_microstep_interpolator: " & integer'image(axes) & " axes, N = " &
           integer'image(capacity) & ", " & integer'image(o_periods) & " periods, " &
           integer'image(rd_missed) & " missed, overrun " &
           integer'image((rd_status / 2 ** status_overrun_bit) mod 2) & ", " &
           integer'image(o_pulses) & " pulses, peak " & integer'image(integer(o_peak_hz)) &
           " pulses/s per axis, " & integer'image(now / 1 us) & " us simulated: ok";
    std.env.finish;
  end process final;

  watchdog : process
    constant stall : time := clk_period * (4 * capacity * div_lim + 20_000) + (response_ns + port_ns + jitter_ns) * 2 ns;
  begin
    loop
      wait on com_falls, sw_done for stall;
      exit when sw_done;
      assert com_falls'event
        report "tb_microstep_interpolator: watchdog: no period started for " & time'image(stall)
        severity failure;
    end loop;
    wait;
  end process watchdog;

end architecture sim;
