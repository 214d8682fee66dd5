// fmpp_tile: Lanes blocks of the FMPP CAM array (a tile of at most LaneW blocks).
//
// Each block has NumWords data words of 32 bits, 8 flags and its read-only index
// (base_i + lane: the paper's ROM address part). The tile stores its words in
// bit-plane form (see fmpp_alu) so that one instruction is a handful of wide
// bitwise operations, and executes the instruction broadcast by fmpp_array:
//   - masked match (REF, SETSADR) of a word or of the block index into a flag,
//   - masked parallel write (WRITES) and the block ALU, predicated on a flag,
//   - flag logic (SETS, RESETS, FLAGOP),
//   - host writes of one word or one block's flags (queued window writes).
// It also answers the host read port and reports its share of the responders.
//
// The tile is deliberately not inlined by Verilator: all full tiles share one
// C++ body, which keeps a 4096-block build to seconds.
module fmpp_tile #(
  parameter int unsigned Lanes    = 64,
  parameter int unsigned NumWords = 32
) (
  input  logic                         clk_i,
  // Asynchronous reset; its only synchronous use is `disable iff` in the assertions.
  /* verilator lint_off SYNCASYNCNET */
  input  logic                         rst_ni,
  /* verilator lint_on SYNCASYNCNET */
  input  logic [31:0]                  base_i,      // index of lane 0 (a multiple of LaneW)

  // Execute bus: the queue entry popped this cycle (state changes at the clock edge)
  input  logic                         exec_i,      // an entry executes this cycle
  input  fmpp_pkg::qkind_e             kind_i,
  input  logic [4:0]                   op_i,        // fmpp_pkg::opcode_e
  input  logic [2:0]                   f_i,
  input  logic [5:0]                   d_i,
  input  logic [5:0]                   a_i,
  input  logic [5:0]                   b_i,
  input  logic [5:0]                   x_i,
  input  logic [31:0]                  imm_i,
  input  logic [31:0]                  mask_i,
  input  logic                         hw_sel_i,    // window write targets this tile
  input  logic [5:0]                   hw_lane_i,
  input  logic [3:0]                   hw_strb_i,
  input  logic [31:0]                  hw_data_i,
  input  logic                         flagop_any_i, // FLAGOP: some block in the array has v = 1
  output logic                         flagop_any_o, // FLAGOP: some block in this tile has v = 1

  // Host read port (combinational, only evaluated when rd_sel_i)
  input  logic                         rd_sel_i,
  input  fmpp_pkg::qkind_e             rd_kind_i,   // QE_WORD: a word; QE_FLAGS: a block's flags; QE_INSTR: a flag plane
  input  logic [5:0]                   rd_lane_i,
  input  logic [5:0]                   rd_word_i,
  input  logic [2:0]                   rd_flag_i,
  output logic [63:0]                  rd_data_o,

  // Responders over SEL and the overflow summary (only evaluated when resp_en_i)
  input  logic                         resp_en_i,
  output logic                         sel_any_o,
  output logic [31:0]                  sel_count_o,
  output logic [5:0]                   sel_first_o,
  output logic                         ovf_any_o
);
  /*verilator no_inline_module*/

  localparam int unsigned W  = fmpp_pkg::WordW;
  localparam int unsigned NF = fmpp_pkg::NumFlags;
  localparam int unsigned FC = fmpp_pkg::FlagC;
  localparam int unsigned FV = fmpp_pkg::FlagV;
  // Word fields are 6 bits; the push check guarantees they are below NumWords.
  localparam int unsigned WIdxW = (NumWords > 1) ? $clog2(NumWords) : 1;

  typedef logic [W*Lanes-1:0]  word_t;   // one word of every lane, plane k at [k*Lanes +: Lanes]
  typedef logic [NF*Lanes-1:0] flags_t;  // flag f of every lane at [f*Lanes +: Lanes]
  typedef logic [Lanes-1:0]    lane_t;

  // State. Words have no reset (memory); flags reset to 0 (nothing selected).
  word_t  mem_q [NumWords] /*verilator public_flat_rd*/;
  flags_t flag_q /*verilator public_flat_rd*/;
  flags_t flag_d;

  word_t opa, opb, opd;
  word_t alu_r;
  lane_t alu_c, alu_v;
  logic  alu_wr_c, alu_wr_v;
  word_t wr_data;
  logic  wr_en;
  logic [5:0] wr_word;

  assign opa = mem_q[a_i[WIdxW-1:0]];
  assign opb = mem_q[b_i[WIdxW-1:0]];
  assign opd = mem_q[d_i[WIdxW-1:0]];
  if (WIdxW < 6) begin : g_unused_hi
    logic unused_hi;
    assign unused_hi = ^{a_i[5:WIdxW], b_i[5:WIdxW], d_i[5:WIdxW], rd_word_i[5:WIdxW]};
  end

  fmpp_alu #(.Lanes(Lanes)) u_alu (
    .op_i    (op_i),
    .fn_i    (x_i[1:0]),
    .bit_i_i (imm_i[4:0]),
    .bit_j_i (imm_i[12:8]),
    .a_i     (opa),
    .b_i     (opb),
    .d_i     (opd),
    .r_o     (alu_r),
    .carry_o (alu_c),
    .ovf_o   (alu_v),
    .wr_c_o  (alu_wr_c),
    .wr_v_o  (alu_wr_v)
  );

  // Bit k of every lane's block index: low bits from the lane number, high bits from base_i.
  function automatic lane_t index_plane(input logic [31:0] base, input int k);
    lane_t p;
    p = '0;
    for (int l = 0; l < Lanes; l++) begin
      p[l] = (k < 6) ? ((l >> k) & 1) == 1 : base[k];
    end
    index_plane = p;
  endfunction

  // FLAGOP value: lut[{fa, fb}] in every lane.
  lane_t flagop_v;
  always_comb begin
    lane_t fa, fb;
    fa = flag_q[x_i[5:3]*Lanes +: Lanes];
    fb = flag_q[x_i[2:0]*Lanes +: Lanes];
    flagop_v = '0;
    if (exec_i && kind_i == fmpp_pkg::QE_INSTR && op_i == fmpp_pkg::OP_FLAGOP) begin
      flagop_v = ({Lanes{imm_i[0]}} & ~fa & ~fb) | ({Lanes{imm_i[1]}} & ~fa & fb) |
                 ({Lanes{imm_i[2]}} &  fa & ~fb) | ({Lanes{imm_i[3]}} &  fa & fb);
    end
  end
  assign flagop_any_o = |flagop_v;

  // Next state.
  always_comb begin
    lane_t pred, match, old, src;
    logic [31:0] key_mask;
    logic addr_part;
    flag_d   = flag_q;
    wr_en    = 1'b0;
    wr_word  = d_i;
    wr_data  = opd;
    pred     = flag_q[f_i*Lanes +: Lanes];
    match    = '0;
    old      = '0;
    src      = '0;
    key_mask = mask_i;
    addr_part = 1'b0;
    if (exec_i) begin
      unique case (kind_i)
        fmpp_pkg::QE_INSTR: begin
          unique case (op_i)
            fmpp_pkg::OP_REF, fmpp_pkg::OP_SETSADR: begin
              // Masked match: every unmasked bit of the source equals the key bit.
              addr_part = (op_i == fmpp_pkg::OP_SETSADR) || x_i[2] == fmpp_pkg::REF_PART_ADDR;
              if (op_i == fmpp_pkg::OP_SETSADR) key_mask = '0;
              match = '1;
              for (int k = 0; k < W; k++) begin
                if (!key_mask[k]) begin
                  src = addr_part ? index_plane(base_i, k) : opa[k*Lanes +: Lanes];
                  match = match & ~(src ^ {Lanes{imm_i[k]}});
                end
              end
              if (op_i == fmpp_pkg::OP_SETSADR) begin
                flag_d[fmpp_pkg::FlagSEL*Lanes +: Lanes] = match;
              end else begin
                old = flag_q[x_i[5:3]*Lanes +: Lanes];
                unique case (x_i[1:0])
                  fmpp_pkg::REF_FN_AND: flag_d[f_i*Lanes +: Lanes] = old & match;
                  fmpp_pkg::REF_FN_OR:  flag_d[f_i*Lanes +: Lanes] = old | match;
                  default:              flag_d[f_i*Lanes +: Lanes] = match;  // THROUGH
                endcase
              end
            end
            fmpp_pkg::OP_SETS:   flag_d[fmpp_pkg::FlagSEL*Lanes +: Lanes] = '1;
            fmpp_pkg::OP_RESETS: flag_d[fmpp_pkg::FlagSEL*Lanes +: Lanes] = '0;
            fmpp_pkg::OP_FLAGOP: begin
              if (!imm_i[8] || flagop_any_i) flag_d[f_i*Lanes +: Lanes] = flagop_v;
            end
            fmpp_pkg::OP_WRITES: begin
              // Masked parallel write: masked bits and unselected blocks keep their value.
              wr_en = 1'b1;
              for (int k = 0; k < W; k++) begin
                if (!mask_i[k]) begin
                  wr_data[k*Lanes +: Lanes] = ({Lanes{imm_i[k]}} & pred) | (opd[k*Lanes +: Lanes] & ~pred);
                end
              end
            end
            fmpp_pkg::OP_FUNC, fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_BITCOPY,
            fmpp_pkg::OP_LSHIFT, fmpp_pkg::OP_RSHIFT: begin
              wr_en = 1'b1;
              for (int k = 0; k < W; k++) begin
                wr_data[k*Lanes +: Lanes] = (alu_r[k*Lanes +: Lanes] & pred) | (opd[k*Lanes +: Lanes] & ~pred);
              end
              if (alu_wr_c) flag_d[FC*Lanes +: Lanes] = (alu_c & pred) | (flag_q[FC*Lanes +: Lanes] & ~pred);
              if (alu_wr_v) flag_d[FV*Lanes +: Lanes] = flag_q[FV*Lanes +: Lanes] | (alu_v & pred);
            end
            default: ;  // NOP and MASKSET do not touch the tile
          endcase
        end
        fmpp_pkg::QE_WORD: begin
          if (hw_sel_i) begin
            wr_en   = 1'b1;
            wr_word = d_i;
            for (int k = 0; k < W; k++) begin
              if (hw_strb_i[k / 8]) wr_data[k*Lanes + {26'd0, hw_lane_i}] = hw_data_i[k];
            end
          end
        end
        fmpp_pkg::QE_FLAGS: begin
          if (hw_sel_i) begin
            for (int f = 0; f < NF; f++) flag_d[f*Lanes + {26'd0, hw_lane_i}] = hw_data_i[f];
          end
        end
        default: ;
      endcase
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      flag_q <= '0;
    end else begin
      flag_q <= flag_d;
    end
  end

  always_ff @(posedge clk_i) begin
    if (wr_en) mem_q[wr_word[WIdxW-1:0]] <= wr_data;
  end

  // Host read port.
  always_comb begin
    word_t w;
    rd_data_o = '0;
    w = '0;
    if (rd_sel_i) begin
      unique case (rd_kind_i)
        fmpp_pkg::QE_WORD: begin
          w = mem_q[rd_word_i[WIdxW-1:0]];
          for (int k = 0; k < W; k++) rd_data_o[k] = w[k*Lanes + {26'd0, rd_lane_i}];
        end
        fmpp_pkg::QE_FLAGS: begin
          for (int f = 0; f < NF; f++) rd_data_o[f] = flag_q[f*Lanes + {26'd0, rd_lane_i}];
        end
        default: rd_data_o[Lanes-1:0] = flag_q[rd_flag_i*Lanes +: Lanes];  // a flag plane
      endcase
    end
  end

  // Responders: any, count and the lowest selected lane (isolate the lowest set bit,
  // then encode it), and whether any lane has V.
  always_comb begin
    lane_t sel, lowest;
    sel         = flag_q[fmpp_pkg::FlagSEL*Lanes +: Lanes];
    lowest      = '0;
    sel_any_o   = 1'b0;
    sel_count_o = '0;
    sel_first_o = '0;
    ovf_any_o   = 1'b0;
    if (resp_en_i) begin
      sel_any_o   = |sel;
      sel_count_o = $countones(sel);
      lowest      = sel & (~sel + 1'b1);
      for (int k = 0; k < 6; k++) sel_first_o[k] = |(lowest & index_plane('0, k));
      ovf_any_o   = |flag_q[FV*Lanes +: Lanes];
    end
  end

  // Assertions
`ifndef SYNTHESIS
  initial begin
    assert (Lanes >= 1 && Lanes <= fmpp_pkg::LaneW)
      else $fatal(1, "fmpp_tile: Lanes = %0d outside [1, %0d]", Lanes, fmpp_pkg::LaneW);
  end
  a_base_aligned: assert property (@(posedge clk_i) base_i[5:0] == 6'd0)
    else $error("fmpp_tile: base_i = %0d is not a multiple of 64", base_i);
  a_hw_lane: assert property (@(posedge clk_i) disable iff (!rst_ni)
                              (exec_i && hw_sel_i && kind_i != fmpp_pkg::QE_INSTR) |-> 32'(hw_lane_i) < Lanes)
    else $error("fmpp_tile: window write to lane %0d of a %0d-lane tile", hw_lane_i, Lanes);
  a_words: assert property (@(posedge clk_i) disable iff (!rst_ni)
                            (exec_i && wr_en) |-> 32'(wr_word) < NumWords)
    else $error("fmpp_tile: write to word %0d of %0d", wr_word, NumWords);
`endif

endmodule
