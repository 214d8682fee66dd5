// tools/asic.sh: yosys's positive latch onto the OSU018 LATCH cell (transparent while CLK is 1).
module \$_DLATCH_P_ (input E, input D, output Q);
  LATCH _TECHMAP_REPLACE_ (.CLK(E), .D(D), .Q(Q));
endmodule
