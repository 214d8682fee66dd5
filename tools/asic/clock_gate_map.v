// tools/asic_chip_flow.py: a word's storage clocked only when the word is written.
// Applied to the word storage cells (the `storage` pattern of rtl/fmpp.f), each an enabled
// flip-flop after `synth`. The enable is caught by a latch that is open while the clock is
// low (a LATCH on the inverted clock), and the flip-flop is clocked by the AND of the clock
// and that latch: the gate passes a clock pulse only after a cycle whose enable was 1, and
// the closed latch holds the enable steady while the clock is high (no glitch). Every bit of
// a word has the same enable, so `opt_merge -share_all` leaves one gate (INVX1, LATCH,
// AND2X2) per word. The flip-flop's hold multiplexer disappears with the enable.
// OpenSTA times the gate like any path: the enable into the latch (a latch check), and the
// latch into the AND (a clock gating check, setup and hold).
module \$_DFFE_PP_ (input D, input C, input E, output Q);
  wire clk_n, en_q, gclk;
  INVX1 inv (.A(C), .Y(clk_n));
  LATCH hold (.CLK(clk_n), .D(E), .Q(en_q));
  AND2X2 gate (.A(C), .B(en_q), .Y(gclk));
  \$_DFF_P_ store (.D(D), .C(gclk), .Q(Q));
endmodule
