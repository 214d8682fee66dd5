// fmpp_instr_check: is a 64-bit instruction legal on a machine with NumWords words?
//
// The AXI slave runs every QUEUE write through this check before it is queued, so an
// illegal instruction answers SLVERR at once and never reaches the array. Rules (see
// docs/isa.md): the opcode exists; every field the opcode does not use is zero; used
// word fields are below NumWords; REF and FUNC function codes are defined; REF on the
// address part names word 0; BITCOPY and FLAGOP leave their reserved immediate bits zero.
module fmpp_instr_check #(
  parameter int unsigned NumWords = 32
) (
  input  logic [63:0] instr_i,
  output logic        legal_o
);
  localparam int unsigned NF = fmpp_pkg::NumFields;

  logic [4:0]  op;
  logic [2:0]  f;
  logic [5:0]  d, a, b, x;
  logic [31:0] imm;

  assign op  = instr_i[fmpp_pkg::F_OP_LSB  +: fmpp_pkg::F_OP_W];
  assign f   = instr_i[fmpp_pkg::F_F_LSB   +: fmpp_pkg::F_F_W];
  assign d   = instr_i[fmpp_pkg::F_D_LSB   +: fmpp_pkg::F_D_W];
  assign a   = instr_i[fmpp_pkg::F_A_LSB   +: fmpp_pkg::F_A_W];
  assign b   = instr_i[fmpp_pkg::F_B_LSB   +: fmpp_pkg::F_B_W];
  assign x   = instr_i[fmpp_pkg::F_X_LSB   +: fmpp_pkg::F_X_W];
  assign imm = instr_i[fmpp_pkg::F_IMM_LSB +: fmpp_pkg::F_IMM_W];

  always_comb begin
    logic [NF-1:0] uses;
    logic [NF-1:0] nonzero;
    logic          known;
    known   = {27'd0, op} < fmpp_pkg::NumOpcodes;
    uses    = known ? fmpp_pkg::OpUses[op*NF +: NF] : '0;
    nonzero = {imm != '0, x != '0, b != '0, a != '0, d != '0, f != '0, 1'b1};
    legal_o = known && ((nonzero & ~uses) == '0);
    // Used word fields must address a word of the block.
    if (uses[2] && {26'd0, d} >= NumWords) legal_o = 1'b0;
    if (uses[3] && {26'd0, a} >= NumWords) legal_o = 1'b0;
    if (uses[4] && {26'd0, b} >= NumWords) legal_o = 1'b0;
    unique case (op)
      fmpp_pkg::OP_REF: begin
        if (x[1:0] == 2'd3) legal_o = 1'b0;
        if (x[2] == fmpp_pkg::REF_PART_ADDR && a != '0) legal_o = 1'b0;
      end
      fmpp_pkg::OP_FUNC: begin
        if (x[1:0] == 2'd3 || x[5:2] != '0) legal_o = 1'b0;
      end
      fmpp_pkg::OP_BITCOPY: begin
        if ((imm & ~32'h0000_1F1F) != '0) legal_o = 1'b0;
      end
      fmpp_pkg::OP_FLAGOP: begin
        if ((imm & ~32'h0000_010F) != '0) legal_o = 1'b0;
      end
      default: ;
    endcase
  end

endmodule
