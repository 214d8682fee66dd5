// fmpp_alu_addend: the block ALU's operands as its execute stage takes them, for every
// lane (bit-plane form, as in fmpp_alu_exec):
//   - word A shifted right (arithmetic) by SHR_A for ADD, SUB and RSHIFT, unshifted for
//     every other operation: a barrel shifter of log2(32) = 5 levels of 2:1 multiplexers,
//     each level moving whole planes (plane k takes plane k + 2^j, the sign plane fills);
//   - word A shifted left by one for DIVSTEP (plane k takes plane k - 1, plane 0 is 0);
//   - the addend: word B for ADD and FUNC, not B for SUB, not IMM (the same in every
//     lane) for CMP; the carry-in is 1 for SUB and CMP. DIVSTEP subtracts B where A is
//     non-negative and adds it where A is negative: per lane, not B and carry-in 1 where
//     A's sign bit is 0, B and carry-in 0 where it is 1 (so the execute stage finds A's
//     sign as not cin).
// The pipelined tile makes the same function in stage 2, after the operand read and its
// forwarding (written out in its clocked block, rtl/fmpp_tile.sv says why), and registers
// it with the operands, so that the execute stage's adder starts from registers: the
// opcode's decode and the shifter are off the carry path. fmpp_alu is this module and
// fmpp_alu_exec in one clock.
module fmpp_alu_addend #(
  parameter int unsigned Lanes = 64
) (
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,   // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::F_IMM_W-1:0]      imm_i,  // CMP: the constant compared with; ADD/SUB/RSHIFT: SHR_A
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  a_i,    // word A of every lane
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  b_i,    // word B of every lane
  output logic [fmpp_pkg::WordW*Lanes-1:0]  a_o,    // word A as the execute stage takes it
  output logic [fmpp_pkg::WordW*Lanes-1:0]  y_o,    // the addend
  output logic [Lanes-1:0]                  cin_o   // the carry-in of every lane
);
  localparam int unsigned W = fmpp_pkg::WordW;
  localparam int unsigned S = fmpp_pkg::SHR_A_W;

  logic [S-1:0] shr;
  assign shr = (op_i == fmpp_pkg::OP_ADD || op_i == fmpp_pkg::OP_SUB || op_i == fmpp_pkg::OP_RSHIFT)
             ? imm_i[fmpp_pkg::SHR_A_LSB +: S] : '0;
  for (genvar j = 0; j < S; j++) begin : g_level
    logic [W*Lanes-1:0] x, y;  // into and out of level j
    if (j == 0) begin : g_first
      assign x = a_i;
    end else begin : g_next
      assign x = g_level[j-1].y;
    end
    for (genvar k = 0; k < W; k++) begin : g_plane
      localparam int unsigned From = (k + (1 << j) < W) ? k + (1 << j) : W - 1;
      assign y[k*Lanes +: Lanes] = shr[j] ? x[From*Lanes +: Lanes] : x[k*Lanes +: Lanes];
    end
  end
  logic              divstep;
  logic [Lanes-1:0]  subs;  // DIVSTEP: the lanes that subtract (A >= 0)
  assign divstep = op_i == fmpp_pkg::OP_DIVSTEP;
  assign subs    = ~a_i[(W-1)*Lanes +: Lanes];
  assign a_o = divstep ? {a_i[(W-1)*Lanes-1:0], {Lanes{1'b0}}} : g_level[S-1].y;

  assign cin_o = (op_i == fmpp_pkg::OP_SUB || op_i == fmpp_pkg::OP_CMP) ? {Lanes{1'b1}} : divstep ? subs : '0;
  for (genvar k = 0; k < W; k++) begin : g_bit
    assign y_o[k*Lanes +: Lanes] = (op_i == fmpp_pkg::OP_CMP) ? {Lanes{~imm_i[k]}}
                                 : (op_i == fmpp_pkg::OP_SUB) ? ~b_i[k*Lanes +: Lanes]
                                 : divstep ? b_i[k*Lanes +: Lanes] ^ subs : b_i[k*Lanes +: Lanes];
  end

endmodule
