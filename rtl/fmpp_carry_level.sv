// fmpp_carry_level: one level of the Sklansky carry network of the block ALU
// (rtl/fmpp_alu.sv), for every lane at once (planes of Lanes bits, as in fmpp_alu).
// At level l every bit k whose bit l is set takes in the group that ends at j, the top
// bit of the 2^l-aligned group just below its own: g_o = g | p & g[j], p_o = p & p[j];
// the other bits pass through. One AND-OR per bit and level: a single LUT on the iCE40,
// an AOI/OAI pair in standard cells.
//
// keep_hierarchy: synthesis maps each level on its own, so that logic optimisation cannot
// fold the network back into a near-ripple (smaller, and three times deeper); the flows
// flatten the levels after mapping (tools/fpga.sh, tools/asic.sh, tools/synth.sh).
// Under Verilator nothing instantiates it (simulators read the ripple text of fmpp_alu_exec),
// so a lint of the whole file list sees it as a second top: expected.
/* verilator lint_off MULTITOP */
(* keep_hierarchy *)
module fmpp_carry_level #(
  parameter int unsigned Lanes = 64,
  parameter int unsigned W     = 32,
  parameter int unsigned Level = 0
) (
  input  logic [W*Lanes-1:0] g_i,
  input  logic [W*Lanes-1:0] p_i,
  output logic [W*Lanes-1:0] g_o,
  output logic [W*Lanes-1:0] p_o  // unused after the last level
);
  for (genvar k = 0; k < W; k++) begin : g_bit
    if (((k >> Level) & 1) != 0) begin : g_join
      localparam int unsigned J = ((k >> (Level + 1)) << (Level + 1)) + (1 << Level) - 1;
      assign g_o[k*Lanes +: Lanes] = g_i[k*Lanes +: Lanes] | (p_i[k*Lanes +: Lanes] & g_i[J*Lanes +: Lanes]);
      assign p_o[k*Lanes +: Lanes] = p_i[k*Lanes +: Lanes] & p_i[J*Lanes +: Lanes];
    end else begin : g_pass
      assign g_o[k*Lanes +: Lanes] = g_i[k*Lanes +: Lanes];
      assign p_o[k*Lanes +: Lanes] = p_i[k*Lanes +: Lanes];
    end
  end
endmodule
/* verilator lint_on MULTITOP */
