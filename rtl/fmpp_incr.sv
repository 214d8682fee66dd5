// fmpp_incr: a counter's next value, q + 1 (modulo 2^W).
//
// Two texts, like the ALU's adder. Synthesis: bit k toggles when bits 0..k-1 are all 1, the
// prefix AND taken by a Sklansky network (fmpp_and_level, log2(W) levels, kept apart so that
// mapping cannot fold it into a chain), so the increment of a 64-bit counter is 6 AND levels
// and an XOR, and the counter's enable, a multiplexer after it. Simulation (Verilator) and
// the FPGA flow (FMPP_CARRY_CHAIN_ADDER, the carry chain): `+ 1`.
// The formal job incr_64 proves the two equal.
module fmpp_incr #(
  parameter int unsigned W = 64
) (
  input  logic [W-1:0] q_i,
  output logic [W-1:0] inc_o
);
`ifdef VERILATOR
  assign inc_o = q_i + 1'b1;
`elsif FMPP_CARRY_CHAIN_ADDER
  assign inc_o = q_i + 1'b1;  // the FPGA flow: `+` maps onto the carry chain (fmpp_alu_exec)
`else
  localparam int unsigned Levels = $clog2(W);
  for (genvar l = 0; l < Levels; l++) begin : g_level
    logic [W-1:0] p;
    if (l == 0) begin : g_first
      fmpp_and_level #(.W(W), .Level(l)) u_level (.p_i(q_i), .p_o(p));
    end else begin : g_next
      fmpp_and_level #(.W(W), .Level(l)) u_level (.p_i(g_level[l-1].p), .p_o(p));
    end
  end
  logic [W-1:0] ones;  // bit k: bits 0..k of q are all 1
  assign ones  = g_level[Levels-1].p;
  assign inc_o = q_i ^ {ones[W-2:0], 1'b1};
  logic unused_top;
  assign unused_top = ones[W-1];
`endif
endmodule
