-- Bus decoder and register file (Chi, Wu and Cui 2020 §3.1 "译码单元"): the PC's side of
-- the interpolator. The software writes each axis's increment for the next
-- period (magnitude + direction, the paper's PulDat and d7, one axis per bus
-- write) into a staging register while the current period is being output,
-- then SEL latches all axes at once into the increment buffers. It also
-- writes the divider buffer (feed override) and the control register, and
-- reads status and counters. Register map: lcnc_hdl_pkg.
--
-- A simple synchronous bus: a write is bus_we = '1' for one cycle with
-- bus_addr / bus_wdata; a read is bus_re = '1' for one cycle and bus_rdata
-- holds the value in the next cycle. Every output is a register, so the
-- decoder may sit in another chip than the axes (the paper splits them):
--
--   write in cycle k   -> staged values, div_value, run, mode from cycle k+1
--                      -> sel, div_wr, clear: one-cycle strobes in cycle k+1
--
-- The output mode changes only while the sequencer is stopped (a drive must
-- not see STEP/DIR turn into PUL/SIG mid-motion).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.lcnc_hdl_pkg.all;

entity bus_decoder is
  generic (
    axes       : positive := 4;
    mag_width  : positive := 4;
    bus_width  : positive := 16;
    addr_width : positive := 4;
    div_width  : positive := 16;
    reset_divider : positive := 125   -- the divider buffer's read-back after reset
  );
  port (
    clk        : in  std_ulogic;
    rst        : in  std_ulogic;
    bus_addr   : in  unsigned(addr_width - 1 downto 0);
    bus_wdata  : in  std_ulogic_vector(bus_width - 1 downto 0);
    bus_we     : in  std_ulogic;
    bus_re     : in  std_ulogic;
    bus_rdata  : out std_ulogic_vector(bus_width - 1 downto 0);
    -- to the increment buffers: axis i's magnitude in bits (i+1)*mag_width-1 .. i*mag_width
    staged_mag : out std_ulogic_vector(axes * mag_width - 1 downto 0);
    staged_dir : out std_ulogic_vector(axes - 1 downto 0);
    sel        : out std_ulogic;
    -- to the clock divider
    div_wr     : out std_ulogic;
    div_value  : out unsigned(div_width - 1 downto 0);
    -- control
    run        : out std_ulogic;
    step_dir_mode : out std_ulogic;
    -- status in: strobes and levels from the interpolator
    buf_full   : in  std_ulogic;
    active     : in  std_ulogic;
    missed     : in  std_ulogic;   -- one cycle per period started without increments
    overrun    : in  std_ulogic;   -- one cycle per SEL while the buffer was full
    period_start : in std_ulogic   -- one cycle per period started
  );
end entity bus_decoder;

architecture rtl of bus_decoder is
  constant c_ok_bus : boolean := require(bus_width >= mag_width + 1,
    "bus_decoder: bus_width = " & integer'image(bus_width) & " < mag_width + 1 = " &
    integer'image(mag_width + 1) & " (magnitude and direction bit must fit one write)");
  constant c_ok_addr : boolean := require(2 ** addr_width >= addr_count(axes),
    "bus_decoder: addr_width = " & integer'image(addr_width) & " cannot address " &
    integer'image(addr_count(axes)) & " registers for " & integer'image(axes) & " axes");
  constant c_ok_div : boolean := require(div_width <= bus_width,
    "bus_decoder: div_width = " & integer'image(div_width) & " > bus_width = " &
    integer'image(bus_width));
  constant c_ok_reset : boolean := require(reset_divider < 2 ** div_width,
    "bus_decoder: reset_divider = " & integer'image(reset_divider) & " does not fit div_width = " &
    integer'image(div_width));

  constant a_sel     : natural := addr_sel(axes);
  constant a_div     : natural := addr_div(axes);
  constant a_ctrl    : natural := addr_ctrl(axes);
  constant a_status  : natural := addr_status(axes);
  constant a_missed  : natural := addr_missed(axes);
  constant a_periods : natural := addr_periods(axes);

  signal mag_r     : std_ulogic_vector(axes * mag_width - 1 downto 0) := (others => '0');
  signal dir_r     : std_ulogic_vector(axes - 1 downto 0) := (others => '0');
  signal sel_r     : std_ulogic := '0';
  signal div_wr_r  : std_ulogic := '0';
  signal div_r     : unsigned(div_width - 1 downto 0) := to_unsigned(reset_divider, div_width);
  signal run_r     : std_ulogic := '0';
  signal mode_r    : std_ulogic := '0';
  signal missed_s  : std_ulogic := '0';  -- sticky
  signal overrun_s : std_ulogic := '0';  -- sticky
  signal missed_n  : unsigned(bus_width - 1 downto 0) := (others => '0');  -- saturating
  signal periods_n : unsigned(bus_width - 1 downto 0) := (others => '0');  -- wrapping
  signal rdata_r   : std_ulogic_vector(bus_width - 1 downto 0) := (others => '0');
begin

  regs : process (clk)
    variable a     : natural;
    variable clear : boolean;
  begin
    if rising_edge(clk) then
      a        := 0;
      if bus_we = '1' or bus_re = '1' then
        a := to_integer(bus_addr);
      end if;
      clear    := false;
      sel_r    <= '0';
      div_wr_r <= '0';
      if bus_we = '1' then
        if a < axes then
          mag_r((a + 1) * mag_width - 1 downto a * mag_width) <= bus_wdata(mag_width - 1 downto 0);
          dir_r(a) <= bus_wdata(bus_width - 1);
        elsif a = a_sel then
          sel_r <= '1';
        elsif a = a_div then
          div_r    <= unsigned(bus_wdata(div_width - 1 downto 0));
          div_wr_r <= '1';
        elsif a = a_ctrl then
          run_r <= bus_wdata(ctrl_run_bit);
          if active = '0' then
            mode_r <= bus_wdata(ctrl_step_dir_bit);
          end if;
          clear := bus_wdata(ctrl_clear_bit) = '1';
        end if;
      end if;

      -- status: a clear and an event on the same edge leave the event counted
      if clear then
        missed_s  <= '0';
        overrun_s <= '0';
        missed_n  <= (others => '0');
        periods_n <= (others => '0');
      end if;
      if missed = '1' then
        missed_s <= '1';
        if clear then
          missed_n <= to_unsigned(1, bus_width);
        elsif missed_n /= (missed_n'range => '1') then
          missed_n <= missed_n + 1;
        end if;
      end if;
      if overrun = '1' then
        overrun_s <= '1';
      end if;
      if period_start = '1' then
        if clear then
          periods_n <= to_unsigned(1, bus_width);
        else
          periods_n <= periods_n + 1;
        end if;
      end if;

      rdata_r <= (others => '0');
      if bus_re = '1' then
        if a = a_div then
          rdata_r(div_width - 1 downto 0) <= std_ulogic_vector(div_r);
        elsif a = a_ctrl then
          rdata_r(ctrl_run_bit)      <= run_r;
          rdata_r(ctrl_step_dir_bit) <= mode_r;
        elsif a = a_status then
          rdata_r(status_full_bit)    <= buf_full;
          rdata_r(status_missed_bit)  <= missed_s;
          rdata_r(status_overrun_bit) <= overrun_s;
          rdata_r(status_active_bit)  <= active;
        elsif a = a_missed then
          rdata_r <= std_ulogic_vector(missed_n);
        elsif a = a_periods then
          rdata_r <= std_ulogic_vector(periods_n);
        end if;
      end if;

      if rst = '1' then
        mag_r     <= (others => '0');
        dir_r     <= (others => '0');
        sel_r     <= '0';
        div_wr_r  <= '0';
        div_r     <= to_unsigned(reset_divider, div_width);
        run_r     <= '0';
        mode_r    <= '0';
        missed_s  <= '0';
        overrun_s <= '0';
        missed_n  <= (others => '0');
        periods_n <= (others => '0');
        rdata_r   <= (others => '0');
      end if;
    end if;
  end process regs;

  staged_mag    <= mag_r;
  staged_dir    <= dir_r;
  sel           <= sel_r;
  div_wr        <= div_wr_r;
  div_value     <= div_r;
  run           <= run_r;
  step_dir_mode <= mode_r;
  bus_rdata     <= rdata_r;

end architecture rtl;
