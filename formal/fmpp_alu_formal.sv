// Formal harness: the block ALU's adder, subtracter, right shift, compare and division step (fmpp_alu: the
// stage-2 shifter and addend and the stage-3 parallel-prefix carry network) against the
// arithmetic of `>>>`, `+` and `-` on whole words, in every lane, for every SHR_A. Combinational: one step of yosys's SAT solver
// covers every operand and immediate, so the check is a proof for the given Lanes (z3
// does not get through the bit-plane definitions in reasonable time).
module fmpp_alu_formal #(
  parameter int unsigned Lanes = 2
) (
  input logic                              clk_i,  // unused: the ALU is combinational
  input logic [fmpp_pkg::F_OP_W-1:0]       op_i,
  input logic [fmpp_pkg::F_IMM_W-1:0]      imm_i,
  input logic [fmpp_pkg::WordW*Lanes-1:0]  a_i,
  input logic [fmpp_pkg::WordW*Lanes-1:0]  b_i,
  input logic [fmpp_pkg::WordW*Lanes-1:0]  d_i
);
  localparam int unsigned W = fmpp_pkg::WordW;
  logic [W*Lanes-1:0] r;
  logic [Lanes-1:0]   c, v, ge;
  logic               wr_c, wr_v;
  logic [Lanes-1:0]   ok_add, ok_sub, ok_rsh, ok_cmp, ok_div, carried;
  logic [fmpp_pkg::SHR_A_W-1:0] shr;
  assign shr = imm_i[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W];
  fmpp_alu #(.Lanes(Lanes)) u_dut (
    .op_i, .fn_i('0), .bit_i_i('0), .bit_j_i('0), .imm_i, .a_i, .b_i, .d_i,
    .r_o(r), .carry_o(c), .ovf_o(v), .wr_c_o(wr_c), .wr_v_o(wr_v), .ge_o(ge)
  );

  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    logic [W-1:0] a, sa, b, rr, sum, dif, rsh, a2, dst;
    logic         co, bo, dco;
    for (genvar k = 0; k < W; k++) begin : g_bit
      assign a[k]  = a_i[k*Lanes + l];
      assign b[k]  = b_i[k*Lanes + l];
      assign rr[k] = r[k*Lanes + l];
    end
    assign sa = $signed(a) >>> shr;
    assign rsh = $signed(sa) >>> 1;
    assign {co, sum} = {1'b0, sa} + {1'b0, b};
    assign {bo, dif} = {1'b0, sa} - {1'b0, b};
    // DIVSTEP: 2A - B where A >= 0 (C = no borrow), 2A + B where A < 0 (C = carry out); V
    // = signed overflow of that sum or of the doubling.
    assign a2 = a << 1;
    assign {dco, dst} = a[W-1] ? {1'b0, a2} + {1'b0, b} : {1'b1, a2} - {1'b0, b};
    // With A' = A >>> SHR_A: ADD writes A' + B, C = the carry out, V = signed overflow; SUB
    // writes A' - B, C = no borrow (A' >= B unsigned), V = signed overflow; RSHIFT writes
    // A' >>> 1, C = the last bit out (bit 0 of A'); CMP answers A >= IMM, both signed.
    assign ok_add[l] = rr == sum && c[l] == co && v[l] == ((sa[W-1] == b[W-1]) && (sum[W-1] != sa[W-1]));
    assign ok_sub[l] = rr == dif && c[l] == !bo && v[l] == ((sa[W-1] != b[W-1]) && (dif[W-1] != sa[W-1]));
    assign ok_rsh[l] = rr == rsh && c[l] == sa[0];
    assign ok_cmp[l] = ge[l] == ($signed(a) >= $signed(imm_i));
    assign ok_div[l] = rr == dst && c[l] == dco &&
                       v[l] == ((a[W-1] != a[W-2]) ||
                                (a[W-1] ? ((a2[W-1] == b[W-1]) && (dst[W-1] != a2[W-1]))
                                        : ((a2[W-1] != b[W-1]) && (dst[W-1] != a2[W-1]))));
    assign carried[l] = co;
  end
  always @(*) begin
    if (op_i == fmpp_pkg::OP_ADD) p_add: assert (&ok_add && wr_c && wr_v);
    if (op_i == fmpp_pkg::OP_SUB) p_sub: assert (&ok_sub && wr_c && wr_v);
    if (op_i == fmpp_pkg::OP_RSHIFT) p_rsh: assert (&ok_rsh && wr_c && !wr_v);
    if (op_i == fmpp_pkg::OP_CMP) p_cmp: assert (&ok_cmp && !wr_c && !wr_v);
    if (op_i == fmpp_pkg::OP_DIVSTEP) p_div: assert (&ok_div && wr_c && wr_v);
  end
  // Non-vacuity: a carry out of every lane at once, an overflow, both compare answers, an
  // overflow after the longest shift.
  // (Checked by yosys's SAT solver: with SAT_COVER each point is an assertion of its
  // negation, which must fail.)
  logic f_cov_carry, f_cov_ovf, f_cov_ge, f_cov_shift;
  assign f_cov_carry = op_i == fmpp_pkg::OP_ADD && &carried;
  assign f_cov_ovf   = op_i == fmpp_pkg::OP_SUB && |v;
  assign f_cov_ge    = op_i == fmpp_pkg::OP_CMP && ge[0] && !ge[Lanes-1];
  assign f_cov_shift = op_i == fmpp_pkg::OP_SUB && &shr && |v;  // overflow after the longest shift
  always @(*) begin
`ifdef SAT_COVER
    c_carry: assert (!f_cov_carry);
    c_ovf: assert (!f_cov_ovf);
    c_ge: assert (!f_cov_ge);
    c_shift: assert (!f_cov_shift);
`else
    c_carry: cover (f_cov_carry);
    c_ovf: cover (f_cov_ovf);
    c_ge: cover (f_cov_ge);
    c_shift: cover (f_cov_shift);
`endif
  end
endmodule
