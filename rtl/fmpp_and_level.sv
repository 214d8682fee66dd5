// fmpp_and_level: one level of a Sklansky prefix AND over W bits (fmpp_incr): at level l
// every bit k whose bit l is set ANDs in the prefix of the top bit of the 2^l-aligned group
// just below its own; the other bits pass through. After log2(W) levels bit k is the AND
// of bits 0..k. The propagate half of fmpp_carry_level, for counters.
//
// keep_hierarchy, for the reason given in fmpp_carry_level.sv: mapped as one netlist with
// its neighbours, the network is folded back into a chain of ANDs (a 64-bit counter's
// increment became the longest path of the 16 x 32 machine in standard cells). A
// simulator never instantiates it (fmpp_incr's simulation text is `+ 1`), so a lint of
// the whole file list sees it as a second top: expected.
/* verilator lint_off MULTITOP */
(* keep_hierarchy *)
module fmpp_and_level #(
  parameter int unsigned W     = 64,
  parameter int unsigned Level = 0
) (
  input  logic [W-1:0] p_i,
  output logic [W-1:0] p_o
);
  for (genvar k = 0; k < W; k++) begin : g_bit
    if (((k >> Level) & 1) != 0) begin : g_join
      localparam int unsigned J = ((k >> (Level + 1)) << (Level + 1)) + (1 << Level) - 1;
      assign p_o[k] = p_i[k] & p_i[J];
    end else begin : g_pass
      assign p_o[k] = p_i[k];
    end
  end
endmodule
/* verilator lint_on MULTITOP */
