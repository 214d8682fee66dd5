// Formal harness: fmpp_instr_check accepts exactly the legal encodings. The reference
// fmpp_instr_ref is generated from rtl/fmpp_map.json by formal/gen_instr_ref.py; both
// are combinational, so one solver step covers all 2^64 instruction words and the
// equivalence is a proof for the given NumWords (tools/formal.sh runs several).
module fmpp_instr_check_formal #(
  parameter int unsigned NumWords = 32
) (
  input logic        clk_i,  // unused: the check is combinational
  input logic [63:0] instr_i
);
  logic legal, ref_legal;
  fmpp_instr_check #(.NumWords(NumWords)) u_dut (.instr_i, .legal_o (legal));
  fmpp_instr_ref   #(.NumWords(NumWords)) u_ref (.instr_i, .legal_o (ref_legal));

  always @(*) begin
    // p_equiv: the RTL check and the map's reference agree on every instruction word.
    p_equiv: assert (legal == ref_legal);
  end
  always @(*) begin
    // Non-vacuity: both answers occur.
    c_legal: cover (legal);
    c_illegal: cover (!legal);
  end
endmodule
