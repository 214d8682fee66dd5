// fmpp_alu: the block ALU of the FMPP (logic unit, ripple-carry adder/subtracter,
// one-bit shifter, bit copy, signed compare with the immediate), written once and
// applied to the Lanes blocks of a tile.
//
// Layout: every operand is a word in bit-plane form. Bit k of the word of block
// (tile base + l) is bit l of plane k, and plane k is a[k*Lanes +: Lanes]. Each
// expression below therefore reads as the logic of one block's ALU (for Lanes = 1
// it is exactly that), while computing all Lanes blocks at once. No signal ever
// crosses lanes: blocks are independent, as in the paper's BPBP organisation.
//
// Purely combinational; the tile applies the predicate and writes the result.
// CMP reuses the subtracter: A + not IMM + 1 on the same carry chain (IMM is broadcast,
// so operand B's bit k is one shared constant per instruction; a 2:1 multiplexer per bit
// selects it), and ge_o is the sign of A - IMM corrected by its overflow: A >= IMM signed.
// CMP writes no word and neither C nor V: wr_c_o and wr_v_o stay 0, and the tile takes
// only ge_o.
// Plain `case` (distinct constant items, with default) for the reason given in
// fmpp_tile.sv: every tile must compile to the same C++ body.
module fmpp_alu #(
  parameter int unsigned Lanes = 64
) (
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,      // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::FUNC_FN_W-1:0]    fn_i,      // FUNC: AND / OR / XOR
  input  logic [fmpp_pkg::BIT_I_W-1:0]      bit_i_i,   // BITCOPY source bit
  input  logic [fmpp_pkg::BIT_J_W-1:0]      bit_j_i,   // BITCOPY destination bit
  input  logic [fmpp_pkg::F_IMM_W-1:0]      imm_i,     // CMP: the constant compared with
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
  localparam int unsigned W = fmpp_pkg::WordW;

  always_comb begin
    logic [Lanes-1:0] c;        // carry into the current bit
    logic [Lanes-1:0] x, y;     // current bit of the two addends
    r_o     = '0;
    carry_o = '0;
    ovf_o   = '0;
    wr_c_o  = 1'b0;
    wr_v_o  = 1'b0;
    ge_o    = '0;
    c = '0;
    x = '0;
    y = '0;
    case (op_i)
      fmpp_pkg::OP_FUNC: begin
        case (fn_i)
          fmpp_pkg::FUNC_FN_AND: r_o = a_i & b_i;
          fmpp_pkg::FUNC_FN_OR:  r_o = a_i | b_i;
          default:               r_o = a_i ^ b_i;  // FUNC_FN_XOR; undefined codes never get here (ILLEGAL at push)
        endcase
      end
      fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_CMP: begin
        // Ripple carry, one full adder per bit. SUB adds the complement of B with carry-in 1;
        // CMP the complement of IMM (the same in every lane) with carry-in 1.
        c = (op_i != fmpp_pkg::OP_ADD) ? {Lanes{1'b1}} : '0;
        for (int k = 0; k < W; k++) begin
          x = a_i[k*Lanes +: Lanes];
          if (op_i == fmpp_pkg::OP_CMP) y = {Lanes{~imm_i[k]}};
          else y = (op_i == fmpp_pkg::OP_SUB) ? ~b_i[k*Lanes +: Lanes] : b_i[k*Lanes +: Lanes];
          r_o[k*Lanes +: Lanes] = x ^ y ^ c;
          if (k == W - 1) ovf_o = c;  // carry into the sign bit ...
          c = (x & y) | (c & (x ^ y));
        end
        ovf_o   = ovf_o ^ c;          // ... differs from the carry out: signed overflow
        carry_o = c;                  // SUB: 1 = no borrow (A >= B unsigned)
        if (op_i == fmpp_pkg::OP_CMP) begin
          // A - IMM >= 0 unless its sign is set without overflow or clear with it.
          // (r_o, carry_o and ovf_o then hold A - IMM and its carries; nothing writes them.)
          ge_o    = ~(r_o[(W-1)*Lanes +: Lanes] ^ ovf_o);
        end else begin
          wr_c_o  = 1'b1;
          wr_v_o  = 1'b1;
        end
      end
      fmpp_pkg::OP_BITCOPY: begin
        // Select plane i of A, then replace plane j of D (a 32:1 mux and a decoder).
        for (int k = 0; k < W; k++) begin
          if (bit_i_i == 5'(k)) x = a_i[k*Lanes +: Lanes];
        end
        for (int k = 0; k < W; k++) begin
          r_o[k*Lanes +: Lanes] = (bit_j_i == 5'(k)) ? x : d_i[k*Lanes +: Lanes];
        end
      end
      fmpp_pkg::OP_LSHIFT: begin
        r_o     = {a_i[(W-1)*Lanes-1:0], {Lanes{1'b0}}};
        carry_o = a_i[(W-1)*Lanes +: Lanes];
        ovf_o   = a_i[(W-1)*Lanes +: Lanes] ^ a_i[(W-2)*Lanes +: Lanes];
        wr_c_o  = 1'b1;
        wr_v_o  = 1'b1;
      end
      fmpp_pkg::OP_RSHIFT: begin
        r_o     = {a_i[(W-1)*Lanes +: Lanes], a_i[W*Lanes-1:Lanes]};
        carry_o = a_i[0 +: Lanes];
        wr_c_o  = 1'b1;
      end
      default: ;  // not an ALU operation
    endcase
  end

endmodule
