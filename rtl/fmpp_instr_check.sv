// fmpp_instr_check: is a 64-bit instruction legal on a machine with NumWords words?
//
// The AXI slave runs every QUEUE write through this check before it is queued, so an
// illegal instruction answers SLVERR at once and never reaches the array. Rules (see
// docs/isa.md), all read from the map (fmpp_pkg): the opcode exists; none of its
// reserved bits is set (fields it does not use, bits of a used field outside its
// sub-fields: OpReserved); used word fields are below NumWords; no sub-field holds a
// value the map does not name (IllegalMask/IllegalValue); a sub-field value that
// requires other fields to hold given values finds them so (ReqWhen*/ReqNeed*: REF on
// the address part names word 0).
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
  logic [63:0]                  reserved;

  assign op = instr_i[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W];
  assign d  = instr_i[fmpp_pkg::F_D_LSB  +: fmpp_pkg::F_D_W];
  assign a  = instr_i[fmpp_pkg::F_A_LSB  +: fmpp_pkg::F_A_W];
  assign b  = instr_i[fmpp_pkg::F_B_LSB  +: fmpp_pkg::F_B_W];

  // Which segments of reserved bits (fmpp_pkg::RsvSegMask) have a bit set.
  logic [fmpp_pkg::NumRsvSegs-1:0] seg_set;
  always_comb begin
    for (int s = 0; s < fmpp_pkg::NumRsvSegs; s++) seg_set[s] = |(instr_i & fmpp_pkg::RsvSegMask[s*64 +: 64]);
  end

  // The range checks as constant tables indexed by the field (a function of its few bits,
  // which LUTs make in two levels), not compares, which FPGA synthesis puts on a carry chain
  // (on the iCE40 that chain stood on the write's path from the bus to the queue's push).
  localparam logic [63:0] WordOut = {64{1'b1}} << NumWords;   // bit w: w >= NumWords
  localparam logic [31:0] OpKnown = ~({32{1'b1}} << fmpp_pkg::NumOpcodes);  // bit o: o < NumOpcodes

  always_comb begin
    logic known;
    int unsigned row;
    known    = OpKnown[op];
    // The tables' row: an unknown opcode reads row 0 (and is illegal anyway), so no
    // part-select ever reaches past a table (the simulator would read beyond it).
    row      = known ? 32'(op) : 0;
    reserved = known ? fmpp_pkg::OpReserved[row*64 +: 64] : '1;
    legal_o  = known && ((seg_set & fmpp_pkg::RsvSegOps[row*fmpp_pkg::NumRsvSegs +: fmpp_pkg::NumRsvSegs]) == '0);
    // Used word fields (their bits are not reserved) must address a word of the block.
    if (!reserved[fmpp_pkg::F_D_LSB] && WordOut[d]) legal_o = 1'b0;
    if (!reserved[fmpp_pkg::F_A_LSB] && WordOut[a]) legal_o = 1'b0;
    if (!reserved[fmpp_pkg::F_B_LSB] && WordOut[b]) legal_o = 1'b0;
    // The map's other rules, each a compare of a few bits against constants.
    for (int k = 0; k < fmpp_pkg::NumIllegal; k++) begin
      if ((instr_i & fmpp_pkg::IllegalMask[k*64 +: 64]) == fmpp_pkg::IllegalValue[k*64 +: 64]) legal_o = 1'b0;
    end
    for (int k = 0; k < fmpp_pkg::NumRequires; k++) begin
      if ((instr_i & fmpp_pkg::ReqWhenMask[k*64 +: 64]) == fmpp_pkg::ReqWhenValue[k*64 +: 64] &&
          (instr_i & fmpp_pkg::ReqNeedMask[k*64 +: 64]) != fmpp_pkg::ReqNeedValue[k*64 +: 64]) legal_o = 1'b0;
    end
  end

endmodule
