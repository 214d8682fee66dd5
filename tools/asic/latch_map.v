// tools/asic.sh, storage variant: a word bit held in a latch instead of a flip-flop.
// Applied only to the word storage cells (the `storage` pattern of rtl/fmpp.f),
// each an enabled flip-flop after `synth`. The latch is open while its word is written and
// the clock is low; the AND of the enable and the inverted clock is the same for every bit
// of a word, so opt_merge leaves one clock gate per word. The flip-flop's hold multiplexer
// (its enable) disappears: a closed latch keeps its value.
module \$_DFFE_PP_ (input D, input C, input E, output Q);
  wire open_q;
  \$_ANDNOT_ gate (.A(E), .B(C), .Y(open_q));
  \$_DLATCH_P_ store (.E(open_q), .D(D), .Q(Q));
endmodule
