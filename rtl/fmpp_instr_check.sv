// fmpp_instr_check: is a 64-bit instruction legal on a machine with NumWords words?
//
// The AXI slave runs every QUEUE write through this check before it is queued, so an
// illegal instruction answers SLVERR at once and never reaches the array. Rules (see
// docs/isa.md), all read from the map (fmpp_pkg): the opcode exists; none of its
// reserved bits is set (fields it does not use, bits of a used field outside its
// sub-fields: OpReserved); used word fields are below NumWords; REF_FN, FUNC_FN and
// CMP_FN hold a value the map names (<SUB>_LEGAL); REF on the address part names word 0.
module fmpp_instr_check #(
  parameter int unsigned NumWords = 32
) (
  input  logic [63:0] instr_i,
  output logic        legal_o
);
  logic [fmpp_pkg::F_OP_W-1:0]  op;
  logic [fmpp_pkg::F_D_W-1:0]   d;
  logic [fmpp_pkg::F_A_W-1:0]   a;
  logic [fmpp_pkg::F_B_W-1:0]   b;
  // Only X's sub-fields with named values are read here; which bits those are is the map's choice.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [fmpp_pkg::F_X_W-1:0]   x;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [63:0]                  reserved;

  assign op = instr_i[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W];
  assign d  = instr_i[fmpp_pkg::F_D_LSB  +: fmpp_pkg::F_D_W];
  assign a  = instr_i[fmpp_pkg::F_A_LSB  +: fmpp_pkg::F_A_W];
  assign b  = instr_i[fmpp_pkg::F_B_LSB  +: fmpp_pkg::F_B_W];
  assign x  = instr_i[fmpp_pkg::F_X_LSB  +: fmpp_pkg::F_X_W];

  // Which segments of reserved bits (fmpp_pkg::RsvSegMask) have a bit set.
  logic [fmpp_pkg::NumRsvSegs-1:0] seg_set;
  always_comb begin
    for (int s = 0; s < fmpp_pkg::NumRsvSegs; s++) seg_set[s] = |(instr_i & fmpp_pkg::RsvSegMask[s*64 +: 64]);
  end

  always_comb begin
    logic known;
    int unsigned row;
    known    = 32'(op) < fmpp_pkg::NumOpcodes;
    // The tables' row: an unknown opcode reads row 0 (and is illegal anyway), so no
    // part-select ever reaches past a table (the simulator would read beyond it).
    row      = known ? 32'(op) : 0;
    reserved = known ? fmpp_pkg::OpReserved[row*64 +: 64] : '1;
    legal_o  = known && ((seg_set & fmpp_pkg::RsvSegOps[row*fmpp_pkg::NumRsvSegs +: fmpp_pkg::NumRsvSegs]) == '0);
    // Used word fields (their bits are not reserved) must address a word of the block.
    if (!reserved[fmpp_pkg::F_D_LSB] && 32'(d) >= NumWords) legal_o = 1'b0;
    if (!reserved[fmpp_pkg::F_A_LSB] && 32'(a) >= NumWords) legal_o = 1'b0;
    if (!reserved[fmpp_pkg::F_B_LSB] && 32'(b) >= NumWords) legal_o = 1'b0;
    unique case (op)
      fmpp_pkg::OP_REF: begin
        if (!fmpp_pkg::REF_FN_LEGAL[x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W]]) legal_o = 1'b0;
        if (!fmpp_pkg::REF_PART_LEGAL[x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W]]) legal_o = 1'b0;
        if (x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_ADDR && a != '0) legal_o = 1'b0;
      end
      fmpp_pkg::OP_FUNC: begin
        if (!fmpp_pkg::FUNC_FN_LEGAL[x[fmpp_pkg::FUNC_FN_LSB +: fmpp_pkg::FUNC_FN_W]]) legal_o = 1'b0;
      end
      fmpp_pkg::OP_CMP: begin
        if (!fmpp_pkg::CMP_FN_LEGAL[x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W]]) legal_o = 1'b0;
        if (!fmpp_pkg::CMP_LT_LEGAL[x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W]]) legal_o = 1'b0;
      end
      default: ;
    endcase
  end

endmodule
