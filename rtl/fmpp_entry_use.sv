// fmpp_entry_use: which words a queue entry uses (operand isolation, fmpp_array).
//
// An instruction reads word A (the ALU operations, BITCOPY, CMP, REF on the data part),
// word B (FUNC, ADD, SUB, DIVSTEP) and writes word D (every word write); a window write
// (a word) writes D only; a flags write uses none. The slave decodes this at the push and
// queues it with the entry, so that the array's pop takes the three bits from the queue
// head instead of decoding them before its enables cross the die. The formal harness
// assumes the same of the entries it makes up.
module fmpp_entry_use (
  input  logic        is_instr_i,  // the entry is an instruction
  input  logic        is_word_i,   // the entry is a window write of one word
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,        // the instruction's opcode
  input  logic [fmpp_pkg::REF_PART_W-1:0]   ref_part_i,  // and its REF part (X's sub-field)
  output logic        rd_a_o,
  output logic        rd_b_o,
  output logic        wr_d_o
);
  always_comb begin
    rd_a_o = 1'b0;
    rd_b_o = 1'b0;
    wr_d_o = is_word_i;
    if (is_instr_i) begin
      case (op_i)
        fmpp_pkg::OP_FUNC, fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_DIVSTEP: {rd_a_o, rd_b_o, wr_d_o} = 3'b111;
        fmpp_pkg::OP_BITCOPY, fmpp_pkg::OP_LSHIFT, fmpp_pkg::OP_RSHIFT: {rd_a_o, wr_d_o} = 2'b11;
        fmpp_pkg::OP_CMP: rd_a_o = 1'b1;
        fmpp_pkg::OP_REF: rd_a_o = ref_part_i == fmpp_pkg::REF_PART_DATA;
        fmpp_pkg::OP_WRITES: wr_d_o = 1'b1;
        default: ;
      endcase
    end
  end
endmodule
