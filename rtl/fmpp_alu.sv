// fmpp_alu: the block ALU of the FMPP in one clock, for the Lanes blocks of a tile:
// fmpp_alu_addend (the operands as the execute stage takes them: A through the shifter,
// the addend) feeding fmpp_alu_exec (the operations). The pipelined tile uses the two parts in consecutive stages; this
// composition is the ALU's unit under test (tests/rtl_units) and the single-cycle
// reference's (formal/fmpp_array_sc.sv). Operands and results are in bit-plane form: bit k
// of the word of lane l is bit l of plane k, a[k*Lanes +: Lanes].
// Nothing in the FMPP instantiates it, so a lint of the whole file list sees it as a
// second top: expected.
/* verilator lint_off MULTITOP */
module fmpp_alu #(
  parameter int unsigned Lanes = 64
) (
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,      // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::FUNC_FN_W-1:0]    fn_i,      // FUNC: AND / OR / XOR
  input  logic [fmpp_pkg::BIT_I_W-1:0]      bit_i_i,   // BITCOPY source bit
  input  logic [fmpp_pkg::BIT_J_W-1:0]      bit_j_i,   // BITCOPY destination bit
  input  logic [fmpp_pkg::F_IMM_W-1:0]      imm_i,     // CMP: the constant compared with; ADD/SUB/RSHIFT: SHR_A
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  a_i,       // word A of every lane
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  b_i,       // word B of every lane
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  d_i,       // old value of word D (BITCOPY keeps its other bits)
  output logic [fmpp_pkg::WordW*Lanes-1:0]  r_o,       // value for word D
  output logic [Lanes-1:0]                  carry_o,   // new C flag
  output logic [Lanes-1:0]                  ovf_o,     // signed overflow (ORed into V)
  output logic                              wr_c_o,    // this op writes C
  output logic                              wr_v_o,    // this op may set V
  output logic [Lanes-1:0]                  ge_o       // CMP: word A >= IMM (signed)
);
  logic [fmpp_pkg::WordW*Lanes-1:0] a, y;
  logic [Lanes-1:0] cin;
  logic [fmpp_pkg::WordW*Lanes-1:0] r, sum;

  fmpp_alu_addend #(.Lanes(Lanes)) u_addend (
    .op_i(op_i), .imm_i(imm_i), .a_i(a_i), .b_i(b_i), .a_o(a), .y_o(y), .cin_o(cin)
  );
  fmpp_alu_exec #(.Lanes(Lanes)) u_exec (
    .op_i(op_i), .fn_i(fn_i), .bit_i_i(bit_i_i), .bit_j_i(bit_j_i), .a_i(a), .y_i(y), .cin_i(cin),
    .d_i(d_i), .r_o(r), .sum_o(sum), .carry_o(carry_o), .ovf_o(ovf_o), .wr_c_o(wr_c_o), .wr_v_o(wr_v_o), .ge_o(ge_o)
  );
  // Word D: the adder's sum for its operations (CMP's difference, which nothing writes), else
  // the result of the others.
  assign r_o = (op_i == fmpp_pkg::OP_ADD || op_i == fmpp_pkg::OP_SUB || op_i == fmpp_pkg::OP_CMP ||
                op_i == fmpp_pkg::OP_DIVSTEP) ? sum : r;

endmodule
/* verilator lint_on MULTITOP */
