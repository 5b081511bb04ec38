-- Single-stage increment buffer of one axis (Chi, Wu and Cui 2020 §3.1, Fig. 6:
-- "插补缓存单元" with the data-valid flag EN).
--
-- The software writes the next period's increment while the current one is
-- being output; SEL (`latch`) moves it from the decoder's staging register
-- into this buffer and sets EN (`full`). At the period boundary (`take`, the
-- period sequencer's load) the DDA reads the buffer and EN is cleared, so an
-- increment is used exactly once:
--
--   take with EN = '1':  out = the buffered increment; EN := '0'
--   take with EN = '0':  out = 0 pulses, and `missed` flags the period —
--                        the last increment is never repeated
--   latch with EN = '0': buffer := in; EN := '1'
--   latch with EN = '1': `overrun` flags it and the buffer keeps the older,
--                        not yet used increment (a second SEL in one period
--                        is a software fault; nothing is silently replaced)
--
-- take and latch on the same edge: the DDA gets the old content, the new
-- increment stays for the next period (EN stays '1').
-- missed and overrun are one-cycle strobes in the cycle after the edge.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity increment_buffer is
  generic (
    mag_width : positive := 4
  );
  port (
    clk     : in  std_ulogic;
    rst     : in  std_ulogic;
    latch   : in  std_ulogic;
    in_mag  : in  unsigned(mag_width - 1 downto 0);
    in_dir  : in  std_ulogic;
    take    : in  std_ulogic;
    out_mag : out unsigned(mag_width - 1 downto 0);  -- valid while take = '1'
    out_dir : out std_ulogic;
    full    : out std_ulogic;
    missed  : out std_ulogic;
    overrun : out std_ulogic
  );
end entity increment_buffer;

architecture rtl of increment_buffer is
  signal mag       : unsigned(mag_width - 1 downto 0) := (others => '0');
  signal dir       : std_ulogic := '0';
  signal en        : std_ulogic := '0';
  signal missed_r  : std_ulogic := '0';
  signal overrun_r : std_ulogic := '0';
begin

  buffer_stage : process (clk)
    variable en_n : std_ulogic;
  begin
    if rising_edge(clk) then
      en_n      := en;
      missed_r  <= '0';
      overrun_r <= '0';
      if take = '1' then
        missed_r <= not en;
        en_n     := '0';
      end if;
      if latch = '1' then
        if en_n = '1' then
          overrun_r <= '1';
        else
          mag  <= in_mag;
          dir  <= in_dir;
          en_n := '1';
        end if;
      end if;
      en <= en_n;
      if rst = '1' then
        mag       <= (others => '0');
        dir       <= '0';
        en        <= '0';
        missed_r  <= '0';
        overrun_r <= '0';
      end if;
    end if;
  end process buffer_stage;

  out_mag <= mag when en = '1' else (others => '0');
  out_dir <= dir when en = '1' else '0';
  full    <= en;
  missed  <= missed_r;
  overrun <= overrun_r;

end architecture rtl;
