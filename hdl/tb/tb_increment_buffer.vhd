-- Self-checking testbench of increment_buffer. Random SEL latches and period
-- takes, same-cycle collisions included. The check process models EN and the
-- buffered increment and checks every cycle what the DDA would read, the
-- missed and overrun strobes; and, as a stream invariant, that every
-- accepted increment is taken exactly once, in order: the sum of accepted
-- magnitudes equals the sum taken plus what still waits in the buffer.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

use work.sim_support_pkg.all;

entity tb_increment_buffer is
  generic (
    mag_width : positive := 4;
    seed      : positive := 1;
    cycles    : positive := 50000;
    latch_pct : natural  := 30;   -- chance of SEL in a cycle, percent
    take_pct  : natural  := 30    -- chance of a period boundary in a cycle, percent
  );
end entity tb_increment_buffer;

architecture sim of tb_increment_buffer is
  constant clk_period : time := 20 ns;

  signal clk     : std_ulogic := '0';
  signal rst     : std_ulogic := '1';
  signal latch   : std_ulogic := '0';
  signal in_mag  : unsigned(mag_width - 1 downto 0) := (others => '0');
  signal in_dir  : std_ulogic := '0';
  signal take    : std_ulogic := '0';
  signal out_mag : unsigned(mag_width - 1 downto 0);
  signal out_dir : std_ulogic;
  signal full    : std_ulogic;
  signal missed  : std_ulogic;
  signal overrun : std_ulogic;
  signal done    : boolean := false;
begin

  clk <= not clk after clk_period / 2;

  dut : entity work.increment_buffer
    generic map (mag_width => mag_width)
    port map (clk => clk, rst => rst, latch => latch, in_mag => in_mag, in_dir => in_dir,
              take => take, out_mag => out_mag, out_dir => out_dir, full => full,
              missed => missed, overrun => overrun);

  stimulus : process
    variable rnd : random_t;
  begin
    rnd.init(seed);
    wait until rising_edge(clk);
    wait until rising_edge(clk);
    rst <= '0';
    for c in 1 to cycles loop
      latch  <= sl(rnd.chance(latch_pct));
      in_mag <= to_unsigned(rnd.int(0, 2 ** mag_width - 1), mag_width);
      in_dir <= rnd.bit1;
      take   <= sl(rnd.chance(take_pct));
      wait until rising_edge(clk);
    end loop;
    latch <= '0';
    take  <= '0';
    wait until rising_edge(clk);
    done <= true;
    wait;
  end process stimulus;

  check : process
    variable en        : boolean := false;
    variable mag_m     : natural := 0;
    variable dir_m     : std_ulogic := '0';
    variable exp_miss  : boolean := false;
    variable exp_over  : boolean := false;
    variable accepted  : natural := 0;   -- sum of accepted magnitudes
    variable taken     : natural := 0;   -- sum of magnitudes the DDA read
    variable n_miss    : natural := 0;
    variable n_over    : natural := 0;
    variable n_take    : natural := 0;
  begin
    wait until rising_edge(clk);
    while not done loop
      if rst = '0' then
        check_equal(full, sl(en), "cycle " & integer'image(now / clk_period) & " EN");
        if en then
          check_equal(to_integer(out_mag), mag_m, "buffered magnitude");
          check_equal(out_dir, dir_m, "buffered direction");
        else
          check_equal(to_integer(out_mag), 0, "magnitude read with EN low (no repeat)");
        end if;
        check_equal(missed, sl(exp_miss), "missed strobe");
        check_equal(overrun, sl(exp_over), "overrun strobe");
        -- the edge
        exp_miss := false;
        exp_over := false;
        if take = '1' then
          n_take := n_take + 1;
          if en then
            taken := taken + mag_m;
          else
            exp_miss := true;
            n_miss   := n_miss + 1;
          end if;
          en := false;
        end if;
        if latch = '1' then
          if en then
            exp_over := true;
            n_over   := n_over + 1;
          else
            en       := true;
            mag_m    := to_integer(in_mag);
            dir_m    := in_dir;
            accepted := accepted + mag_m;
          end if;
        end if;
      end if;
      wait until rising_edge(clk);
    end loop;
    if en then
      taken := taken + mag_m;
    end if;
    check_equal(taken, accepted, "sum of increments taken (plus the one still buffered)");
    assert n_miss > 10 and n_over > 10 and n_take > 100
      report "tb_increment_buffer: too little exercised" severity failure;
    report "tb_increment_buffer: " & integer'image(n_take) & " periods, " & integer'image(n_miss) &
           " missed, " & integer'image(n_over) & " overruns: ok";
    std.env.finish;
  end process check;

  watchdog : process
  begin
    wait for clk_period * (cycles + 100);
    assert false report "tb_increment_buffer: watchdog: simulation did not finish" severity failure;
    wait;
  end process watchdog;

end architecture sim;
