// Formal harness: fmpp_incr's synthesis text (the prefix-AND network) against `+ 1`, for
// every value of the counter. Combinational: one step of yosys's SAT solver is a proof.
module fmpp_incr_formal #(
  parameter int unsigned W = 64
) (
  input logic         clk_i,  // unused: the increment is combinational
  input logic [W-1:0] q_i
);
  logic [W-1:0] inc;
  fmpp_incr #(.W(W)) u_dut (.q_i(q_i), .inc_o(inc));
  logic f_wrap;
  assign f_wrap = &q_i;
  always @(*) begin
    p_inc: assert (inc == q_i + 1'b1);
`ifdef SAT_COVER
    c_wrap: assert (!f_wrap);
`else
    c_wrap: cover (f_wrap);
`endif
  end
  logic unused_clk;
  assign unused_clk = clk_i;
endmodule
