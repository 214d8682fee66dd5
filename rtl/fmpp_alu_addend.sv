// fmpp_alu_addend: the block ALU's second operand as its adder takes it, for every lane
// (bit-plane form, as in fmpp_alu_exec): word B for ADD and FUNC, not B for SUB, not IMM
// (the same in every lane) for CMP; the carry-in is 1 for SUB and CMP. The pipelined tile
// makes the same function in stage 2, after the operand read and its forwarding (written
// out in its clocked block, rtl/fmpp_tile.sv says why), and registers it with the operand,
// so that the execute stage's adder starts from registers: the opcode's decode is off the
// carry path. fmpp_alu is this module and fmpp_alu_exec in one clock.
module fmpp_alu_addend #(
  parameter int unsigned Lanes = 64
) (
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,   // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::F_IMM_W-1:0]      imm_i,  // CMP: the constant compared with
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  b_i,    // word B of every lane
  output logic [fmpp_pkg::WordW*Lanes-1:0]  y_o,    // the addend
  output logic                              cin_o   // the carry-in
);
  localparam int unsigned W = fmpp_pkg::WordW;

  assign cin_o = op_i == fmpp_pkg::OP_SUB || op_i == fmpp_pkg::OP_CMP;
  for (genvar k = 0; k < W; k++) begin : g_bit
    assign y_o[k*Lanes +: Lanes] = (op_i == fmpp_pkg::OP_CMP) ? {Lanes{~imm_i[k]}}
                                 : (op_i == fmpp_pkg::OP_SUB) ? ~b_i[k*Lanes +: Lanes] : b_i[k*Lanes +: Lanes];
  end

endmodule
