-- Testbench support: a seeded random source (ieee.math_real.uniform, so
-- every run with the same seed is the same run) and the checks that report
-- expected vs actual and stop the simulation (severity failure).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use ieee.math_real.all;

package sim_support_pkg is

  type random_t is protected
    procedure init(seed : positive);
    impure function int(lo, hi : integer) return integer;   -- uniform in lo .. hi
    impure function chance(percent : natural) return boolean;
    impure function bit1 return std_ulogic;
  end protected random_t;

  type int_array is array (natural range <>) of integer;

  -- A growable array of integers, shared between a stimulus and a checker
  -- (a shared variable of this type).
  type int_store_t is protected
    procedure set(i : natural; v : integer);
    impure function get(i : natural) return integer;  -- 0 where never set
  end protected int_store_t;

  -- Stops with "<what>: expected <e>, actual <a>" when they differ.
  procedure check_equal(actual, expected : integer; what : string);
  procedure check_equal(actual, expected : std_ulogic; what : string);

  function sl(b : boolean) return std_ulogic;
  function bool_int(b : boolean) return integer;  -- 1 or 0

end package sim_support_pkg;

package body sim_support_pkg is

  type random_t is protected body
    variable s1 : positive := 1;
    variable s2 : positive := 1;

    procedure init(seed : positive) is
    begin
      s1 := seed;
      s2 := 7919 + (seed mod 100000);
    end procedure;

    impure function int(lo, hi : integer) return integer is
      variable x : real;
    begin
      uniform(s1, s2, x);
      return lo + integer(floor(x * real(hi - lo + 1)));
    end function;

    impure function chance(percent : natural) return boolean is
    begin
      return int(0, 99) < percent;
    end function;

    impure function bit1 return std_ulogic is
    begin
      if int(0, 1) = 1 then
        return '1';
      end if;
      return '0';
    end function;
  end protected body random_t;

  type int_store_t is protected body
    type int_array_ptr is access int_array;
    variable data : int_array_ptr := new int_array'(0 to 1023 => 0);

    procedure set(i : natural; v : integer) is
      variable bigger : int_array_ptr;
    begin
      if i > data'high then
        bigger := new int_array'(0 to 2 * i + 1 => 0);
        bigger(data'range) := data.all;
        deallocate(data);
        data := bigger;
      end if;
      data(i) := v;
    end procedure;

    impure function get(i : natural) return integer is
    begin
      if i > data'high then
        return 0;
      end if;
      return data(i);
    end function;
  end protected body int_store_t;

  procedure check_equal(actual, expected : integer; what : string) is
  begin
    assert actual = expected
      report what & ": expected " & integer'image(expected) & ", actual " & integer'image(actual)
      severity failure;
  end procedure;

  procedure check_equal(actual, expected : std_ulogic; what : string) is
  begin
    assert actual = expected
      report what & ": expected " & std_ulogic'image(expected) & ", actual " & std_ulogic'image(actual)
      severity failure;
  end procedure;

  function sl(b : boolean) return std_ulogic is
  begin
    if b then
      return '1';
    end if;
    return '0';
  end function;

  function bool_int(b : boolean) return integer is
  begin
    if b then
      return 1;
    end if;
    return 0;
  end function;

end package body sim_support_pkg;
