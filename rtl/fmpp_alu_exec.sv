// fmpp_alu_exec: the block ALU of the FMPP (logic unit, parallel-prefix adder/subtracter,
// one-bit shifter, bit copy, signed compare with the immediate), written once and
// applied to the Lanes blocks of a tile. Its addend (B, not B or not IMM, and the
// carry-in) comes prepared one pipeline stage earlier, by the tile (the function of
// fmpp_alu_addend); fmpp_alu is fmpp_alu_addend and this module in one clock.
//
// Layout: every operand is a word in bit-plane form. Bit k of the word of block
// (tile base + l) is bit l of plane k, and plane k is a[k*Lanes +: Lanes]. Each
// expression below therefore reads as the logic of one block's ALU (for Lanes = 1
// it is exactly that), while computing all Lanes blocks at once. No signal ever
// crosses lanes: blocks are independent, as in the paper's BPBP organisation.
//
// Purely combinational; the tile applies the predicate and writes the result. The adder's
// sum has an output of its own (sum_o; r_o is 0 for the adder's operations, but in the
// simulation text, which computes the sum into r_o and copies it to sum_o), so that the
// tile can let it in last, after every other choice of word D and of the forwarded A: the
// sum is the latest signal of stage 3, and no multiplexer of the others lies behind it.
// In synthesis the adder's carries come from a Sklansky parallel-prefix network
// (fmpp_carry_level.sv, one module per level: log2(32) = 5 AND-OR levels instead of a
// 32-bit ripple; simulators read a ripple, see below).
// CMP reuses the subtracter: A + not IMM + 1 on the same carries, and ge_o is the sign
// of A - IMM corrected by its overflow: A >= IMM signed.
// CMP writes no word and neither C nor V: wr_c_o and wr_v_o stay 0, and the tile takes
// only ge_o.
// DIVSTEP (a non-restoring division step) is the adder on A << 1 and, per lane, not B
// with carry-in 1 where A >= 0, or B with carry-in 0 where A < 0 (both made by
// fmpp_alu_addend): A's sign is not cin, and the shift overflows where it differs from
// the shifted A's sign (A[30]).
// Plain `case` (distinct constant items, with default) for the reason given in
// fmpp_tile.sv: every tile must compile to the same C++ body.
module fmpp_alu_exec #(
  parameter int unsigned Lanes = 64,
  // 0: BITCOPY is not an operation of this ALU (r_o 0 for it): the tile copies the bit itself
  parameter bit          HasBitcopy = 1'b1
) (
  input  logic [fmpp_pkg::F_OP_W-1:0]       op_i,      // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::FUNC_FN_W-1:0]    fn_i,      // FUNC: AND / OR / XOR
  input  logic [fmpp_pkg::BIT_I_W-1:0]      bit_i_i,   // BITCOPY source bit
  input  logic [fmpp_pkg::BIT_J_W-1:0]      bit_j_i,   // BITCOPY destination bit
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  a_i,       // word A of every lane
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  y_i,       // the addend (fmpp_alu_addend): word B for FUNC and ADD
  input  logic [Lanes-1:0]                  cin_i,     // the adder's carry-in per lane (fmpp_alu_addend)
  input  logic [fmpp_pkg::WordW*Lanes-1:0]  d_i,       // old value of word D (BITCOPY keeps its other bits)
  output logic [fmpp_pkg::WordW*Lanes-1:0]  r_o,       // value for word D (FUNC, BITCOPY, LSHIFT, RSHIFT; else 0 but in simulation)
  output logic [fmpp_pkg::WordW*Lanes-1:0]  sum_o,     // the adder's sum: word D for ADD, SUB, DIVSTEP (CMP: A - IMM)
  output logic [Lanes-1:0]                  carry_o,   // new C flag
  output logic [Lanes-1:0]                  ovf_o,     // signed overflow (ORed into V)
  output logic                              wr_c_o,    // this op writes C
  output logic                              wr_v_o,    // this op may set V
  output logic [Lanes-1:0]                  ge_o       // CMP: word A >= IMM (signed)
);
  // Not traced (the tile's ports and state are): its temporaries stay C++ locals in the
  // Verilated model.
  /* verilator tracing_off */
  localparam int unsigned W = fmpp_pkg::WordW;

  // The adder: h, half sums; g0, generate per bit with the carry-in folded into bit 0's.
  // After level l, plane k of the level's g is the carry out of bits k down to the bottom of
  // k's 2^(l+1)-aligned group; after the last level (carry) the carry out of bit k.
  //
  // The adder has three texts. For synthesis in standard cells the carries come from the
  // network, each level a module (fmpp_carry_level, kept apart so that mapping cannot fold
  // it into a ripple). For an FPGA (FMPP_CARRY_CHAIN_ADDER, set by tools/fpga.sh) each
  // lane's word is gathered from the planes and added with `+`, which synthesis maps onto
  // the FPGA's dedicated carry chain (on the iCE40 about 0.1 ns a bit, against a LUT and
  // its routing per prefix level). For
  // simulation (FMPP_RIPPLE_ADDER, set under Verilator) the ADD/SUB/CMP branch of the case
  // below computes the same sums with a ripple carry: a simulator then works on the adder
  // only for those operations, and a ripple is the cheapest text to evaluate on bit planes
  // (as continuous logic the network cost every tile every clock: with the addend also made
  // by continuous logic, the Verilated render of the README took four times as long). The
  // formal jobs alu_l2, alu_l2_chain and alu_l2_ripple prove each text equal to `+` and `-`.
`ifdef VERILATOR
`define FMPP_RIPPLE_ADDER
`endif
  logic [Lanes-1:0]   cin;
  assign cin = cin_i;
`ifdef FMPP_RIPPLE_ADDER
  // The simulation text computes the sum into r_o (one output to clear, not two).
  assign sum_o = r_o;
`elsif FMPP_CARRY_CHAIN_ADDER
  logic [W*Lanes-1:0] carry;  // only the top two planes are used: out of bits 30 and 31
  logic [W*Lanes-1:0] sum;
  for (genvar l = 0; l < Lanes; l++) begin : g_lane
    logic [W-1:0] a, y;
    logic [W+1:0] s;  // bit 0 only carries cin into bit 1: one chain, cin at its start
    for (genvar k = 0; k < W; k++) begin : g_gather
      assign a[k] = a_i[k*Lanes + l];
      assign y[k] = y_i[k*Lanes + l];
      assign sum[k*Lanes + l] = s[k+1];
    end
    assign s = {1'b0, a, 1'b1} + {1'b0, y, cin_i[l]};
    assign carry[(W-1)*Lanes + l] = s[W+1];
    assign carry[(W-2)*Lanes + l] = a[W-1] ^ y[W-1] ^ s[W];  // the carry into the sign bit
  end
  assign carry[(W-2)*Lanes-1:0] = '0;
  assign sum_o = sum;
`else
  localparam int unsigned Levels = $clog2(W);  // of the carry network
  logic [W*Lanes-1:0] h, g0, carry;
  assign h   = a_i ^ y_i;
  assign g0  = (a_i & y_i) | {{(W-1)*Lanes{1'b0}}, h[0 +: Lanes] & cin};
  for (genvar l = 0; l < Levels; l++) begin : g_level
    logic [W*Lanes-1:0] g;
    logic [W*Lanes-1:0] p;  // the last level's propagate is not needed
    if (l == 0) begin : g_first
      fmpp_carry_level #(.Lanes(Lanes), .W(W), .Level(l)) u_level (.g_i(g0), .p_i(h), .g_o(g), .p_o(p));
    end else begin : g_next
      fmpp_carry_level #(.Lanes(Lanes), .W(W), .Level(l)) u_level (
        .g_i(g_level[l-1].g), .p_i(g_level[l-1].p), .g_o(g), .p_o(p)
      );
    end
  end
  assign carry = g_level[Levels-1].g;
  // Bit k's sum is its half sum with the carry into it (the carry-in, or bit k-1's out).
  assign sum_o = h ^ {carry[(W-1)*Lanes-1:0], cin};
`endif

  // The sum as this text computes it (CMP's sign below).
`ifdef FMPP_RIPPLE_ADDER
`define FMPP_SUM r_o
`else
`define FMPP_SUM sum_o
`endif

  always_comb begin
    logic [Lanes-1:0] x;        // BITCOPY: the selected plane of A
`ifdef FMPP_RIPPLE_ADDER
    logic [Lanes-1:0] c, y;  // the simulation text's carry into the current bit, its addend bit
`endif
    r_o     = '0;
    carry_o = '0;
    ovf_o   = '0;
    wr_c_o  = 1'b0;
    wr_v_o  = 1'b0;
    ge_o    = '0;
    x = '0;
`ifdef FMPP_RIPPLE_ADDER
    c = '0;
    y = '0;
`endif
    case (op_i)
      fmpp_pkg::OP_FUNC: begin
        case (fn_i)
          fmpp_pkg::FUNC_FN_AND: r_o = a_i & y_i;
          fmpp_pkg::FUNC_FN_OR:  r_o = a_i | y_i;
          default:               r_o = a_i ^ y_i;  // FUNC_FN_XOR; undefined codes never get here (ILLEGAL at push)
        endcase
      end
      fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_CMP, fmpp_pkg::OP_DIVSTEP: begin
`ifdef FMPP_RIPPLE_ADDER
        // Simulation text: one full adder per bit.
        c = cin;
        for (int k = 0; k < W; k++) begin
          x = a_i[k*Lanes +: Lanes];
          y = y_i[k*Lanes +: Lanes];
          r_o[k*Lanes +: Lanes] = x ^ y ^ c;
          if (k == W - 1) ovf_o = c;  // carry into the sign bit ...
          c = (x & y) | (c & (x ^ y));
        end
        ovf_o   = ovf_o ^ c;          // ... differs from the carry out: signed overflow
        carry_o = c;                  // SUB: 1 = no borrow (A >= B unsigned)
`elsif FMPP_CARRY_CHAIN_ADDER
        ovf_o   = carry[(W-2)*Lanes +: Lanes] ^ carry[(W-1)*Lanes +: Lanes];  // carry into the sign bit vs out of it
        carry_o = carry[(W-1)*Lanes +: Lanes];  // SUB: 1 = no borrow (A >= B unsigned)
`else
        ovf_o   = carry[(W-2)*Lanes +: Lanes] ^ carry[(W-1)*Lanes +: Lanes];  // carry into the sign bit vs out of it
        carry_o = carry[(W-1)*Lanes +: Lanes];  // SUB: 1 = no borrow (A >= B unsigned)
`endif
        if (op_i == fmpp_pkg::OP_CMP) begin
          // A - IMM >= 0 unless its sign is set without overflow or clear with it.
          // (the sum, carry_o and ovf_o then hold A - IMM and its carries; nothing writes them.)
          ge_o    = ~(`FMPP_SUM[(W-1)*Lanes +: Lanes] ^ ovf_o);
        end else begin
          // DIVSTEP: the shift A << 1 overflows where A[31] (not cin) differs from A[30].
          if (op_i == fmpp_pkg::OP_DIVSTEP) ovf_o = ovf_o | (~cin ^ a_i[(W-1)*Lanes +: Lanes]);
          wr_c_o  = 1'b1;
          wr_v_o  = 1'b1;
        end
      end
      fmpp_pkg::OP_BITCOPY: if (HasBitcopy) begin
        // Select plane i of A, then replace plane j of D (a 32:1 mux and a decoder). The
        // plane is an indexed part-select: synthesis makes a balanced tree of 2:1 multiplexers
        // (5 levels), not a 32-deep priority chain; a simulator reads one slice.
        x = a_i[bit_i_i*Lanes +: Lanes];
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

`undef FMPP_RIPPLE_ADDER
`undef FMPP_SUM

  /* verilator tracing_on */

endmodule
