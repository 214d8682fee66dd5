// fmpp_tile: Lanes blocks of the FMPP CAM array (a tile of at most LaneW blocks).
//
// Each block has NumWords data words of 32 bits, 8 flags and its read-only index
// (base_i + lane: the paper's ROM address part). The tile stores its words in bit-plane
// form (see fmpp_alu) so that one instruction is a handful of wide bitwise operations, and
// executes the instruction broadcast by fmpp_array in the array's pipeline: in stage 2 it
// reads words A and B into its operand registers (forwarding the word stage 3 writes in the
// same clock), in stage 3 it executes on them with the flags and word D as they are then,
// and writes back at the clock edge: masked match (REF, SETSADR) of a word or of the block
// index into a flag; masked parallel write (WRITES) and the block ALU, predicated on a
// flag; signed compare of a word with the immediate (CMP) into a flag; flag logic (SETS,
// RESETS, FLAGOP); host writes of one word or one block's flags (queued window writes).
// It also answers the host read port and reports its share of the responders.
//
// Written so that Verilator gives all full tiles one C++ body (docs/architecture.md,
// "One code for every tile"): no per-instance port expressions, no functions, and
// `case` statements with distinct constant items and a default.
module fmpp_tile #(
  parameter int unsigned Lanes    = 64,
  parameter int unsigned NumWords = 32
) (
  input  logic                         clk_i,
  // Active-low reset, sampled synchronously by every flop; only the assertions'
  // `disable iff` uses it asynchronously (hence the lint waiver).
  /* verilator lint_off SYNCASYNCNET */
  input  logic                         rst_ni,
  /* verilator lint_on SYNCASYNCNET */
  // Index of lane 0 (a multiple of LaneW). Public so that Verilator keeps it a
  // variable instead of folding each tile's constant into its own copy of the code.
  input  logic [31:0]                  base_i /*verilator public_flat_rd*/,

  // Operand read (pipeline stage 2): the entry's words A and B, and the addend made from B
  input  logic                         opr_a_en_i,  // an entry in stage 2 reads word A
  input  logic                         opr_b_en_i,  // it loads the addend (word B or CMP's IMM)
  input  logic [fmpp_pkg::F_A_W-1:0]   a_i,
  input  logic [fmpp_pkg::F_B_W-1:0]   b_i,
  input  logic [fmpp_pkg::F_OP_W-1:0]  opr_op_i,    // the stage-2 entry's opcode
  input  logic [fmpp_pkg::F_IMM_W-1:0] opr_imm_i,   // and its immediate (CMP's constant)
  input  logic [fmpp_pkg::SHR_A_W-1:0] opr_shr_i,   // its shift of A, decoded at the broadcast (fmpp_array)
  input  logic [3:0]                   opr_shc_i,   // FMPP_ONEHOT_SHIFT: the coarse shift by 0, 8, 16, 24, one-hot (fmpp_array)
  input  logic [7:0]                   opr_shf_i,   // and the fine one by 0 to 7
  input  logic                         opr_shv_i,   // and DIVSTEP's doubling
  input  logic                         fwd_a_i,     // its word A is the word the stage-3 entry writes here
  // Execute bus (stage 3): the entry that executes this cycle (state changes at the clock edge)
  input  logic                         exec_i,      // an entry executes this cycle
  input  logic [fmpp_pkg::F_OP_W-1:0]  alu_op_i,    // the ALU's opcode: op_i while an instruction but BITCOPY executes, else NOP
  // Its write of word D in this tile, decoded a clock ahead by fmpp_array (each only while
  // it executes): the adder's sum (ADD, SUB, DIVSTEP), the ALU's other result (FUNC, LSHIFT,
  // RSHIFT), WRITES, BITCOPY, a window write of one word of this tile.
  input  logic                         ws_sum_i,
  input  logic                         ws_alu_i,
  input  logic                         ws_writes_i,
  input  logic                         ws_bitcopy_i,
  input  logic                         ws_word_i,
  input  fmpp_pkg::qkind_e             kind_i,
  input  logic [fmpp_pkg::F_OP_W-1:0]  op_i,        // fmpp_pkg::opcode_e
  input  logic [fmpp_pkg::F_F_W-1:0]   f_i,
  input  logic [fmpp_pkg::F_F_W-1:0]   f_nx_i,      // F of the entry in stage 3 after the next edge
  input  logic [fmpp_pkg::F_D_W-1:0]   d_i,
  input  logic [fmpp_pkg::F_X_W-1:0]   x_i,         // sub-fields by opcode (fmpp_pkg::REF_FN_LSB, ...)
  input  logic [fmpp_pkg::F_IMM_W-1:0] imm_i,
  input  logic [31:0]                  mask_i,
  input  logic [fmpp_pkg::WordW-1:0]   wpl_i,
  input  logic [3:0]                   rk_i,
  input  logic [5:0]                   a_nx_i, b_nx_i, d_nx_i,  // FMPP_BRAM_WORDS: the words A, B, D read at the next edge
  input  logic [fmpp_pkg::BlockIdxW-1:0] hw_block_i,  // block of a window write
  input  logic [Lanes-1:0]            hw_lane_sel_i, // its lane, one-hot (the word line), decoded a clock ahead
  input  logic [3:0]                   hw_strb_i,
  input  logic [31:0]                  hw_data_i,
  input  logic                         flagop_any_i, // FLAGOP: some block in the array has v = 1 (0 while it waits)
  output logic                         flagop_any_o, // FLAGOP: some block in this tile had v = 1 a clock ago

  // Host read port (combinational, evaluated only for the addressed tile)
  input  logic                         rd_en_i,     // a window read is being requested
  input  fmpp_pkg::rkind_e             rd_kind_i,
  input  logic [fmpp_pkg::BlockIdxW-1:0] rd_block_i,  // block (WORD, FLAGS) or tile (PLANE)
  input  logic [fmpp_pkg::WordIdxW-1:0]  rd_word_i,
  input  logic [fmpp_pkg::FlagIdxW-1:0]  rd_flag_i,
  output logic [63:0]                  rd_data_o,
  // FPGA synthesis (FMPP_BRAM_WORDS_HOST): a word read is read from the RAM at the edge that
  // accepts it (rd_acc_i) and answered from the RAM's output while its R beat lasts
  // (rd_late_o; 0 without the macro, and rd_data_o answers it at once)
  input  logic                         rd_acc_i,
  output logic [31:0]                  rd_late_o,

  // Responders over SEL and the overflow summary (registered; they follow the flags while resp_en_i)
  input  logic                         resp_en_i,
  output logic                         sel_any_o,
  output logic [31:0]                  sel_count_o,
  output logic [fmpp_pkg::LaneIdxW-1:0] sel_first_o,
  output logic                         ovf_any_o
);
  /*verilator no_inline_module*/

  localparam int unsigned W  = fmpp_pkg::WordW;
  localparam int unsigned NF = fmpp_pkg::NumFlags;
  localparam int unsigned FC = fmpp_pkg::FlagC;
  localparam int unsigned FV = fmpp_pkg::FlagV;
  // Word fields are F_D_W bits; the push check guarantees they are below NumWords.
  localparam int unsigned WIdxW = (NumWords > 1) ? $clog2(NumWords) : 1;
  // REF's source flag and FLAGOP's first flag share a multiplexer when the map puts them
  // in the same bits of X (a constant: both selections below fold into one).
  localparam bit FsIsFa = fmpp_pkg::REF_FS_LSB == fmpp_pkg::FLAG_FA_LSB;
  // CMP's source flag likewise shares it when it sits where REF's does.
  localparam bit CmpFsIsFs = fmpp_pkg::CMP_FS_LSB == fmpp_pkg::REF_FS_LSB;

  typedef logic [W*Lanes-1:0]  word_t;   // one word of every lane, plane k at [k*Lanes +: Lanes]
  typedef logic [NF*Lanes-1:0] flags_t;  // flag f of every lane at [f*Lanes +: Lanes]
  typedef logic [Lanes-1:0]    lane_t;

  // State. Words have no reset (memory); flags reset to 0 (nothing selected).
`ifdef FMPP_BRAM_WORDS
  (* ram_style = "block" *)
`endif
  word_t  mem_q [NumWords] /*verilator public_flat_rd*/;
  flags_t flag_q /*verilator public_flat_rd*/;


  // Operand registers (stage 2 -> 3): A through the shifter, the ALU's addend (B, not B or
  // not IMM) and its carry-in, made in stage 2 so that stage 3's adder starts from registers.
  // Word D, the flags and the mask are read in stage 3, when every earlier entry wrote them.
  word_t opa_q, opb_q;
  lane_t cin_q;
  word_t alu_r, alu_sum;
  lane_t alu_c, alu_v, alu_ge;
  logic  alu_wr_c, alu_wr_v;

  // The ALU sees the opcode only while an instruction that uses it executes (NOP otherwise,
  // decoded a clock ahead by fmpp_array, so no gate stands between the stage registers and
  // the ALU): its results are used only then, and a simulator so does no adder work on the
  // other clocks. BITCOPY, which needs word D, is done by the next-state logic below, so the
  // ALU has no BITCOPY and its D input is not used.
  fmpp_alu_exec #(.Lanes(Lanes), .HasBitcopy(1'b0)) u_alu (
    .op_i    (alu_op_i),
    .fn_i    (x_i[fmpp_pkg::FUNC_FN_LSB +: fmpp_pkg::FUNC_FN_W]),
    .bit_i_i (imm_i[fmpp_pkg::BIT_I_LSB +: fmpp_pkg::BIT_I_W]),
    .bit_j_i (imm_i[fmpp_pkg::BIT_J_LSB +: fmpp_pkg::BIT_J_W]),
    .a_i     (opa_q),
    .y_i     (opb_q),
    .cin_i   (cin_q),
    .d_i     ('0),
    .r_o     (alu_r),
    .sum_o   (alu_sum),
    .carry_o (alu_c),
    .ovf_o   (alu_v),
    .wr_c_o  (alu_wr_c),
    .wr_v_o  (alu_wr_v),
    .ge_o    (alu_ge)
  );

  // The word reads of A, B and D (32 : 1 of a whole word of every lane). In synthesis each is
  // a one-hot select decoded once for the tile and an AND-OR per bit, so that a new word
  // number switches two select lines and the two words' gates, not a tree of multiplexers
  // whose selects reach every bit (docs/architecture.md, "Operand isolation"). Simulators
  // (and the FPGA flow, FMPP_INDEXED_READ, whose LUTs make a tree multiplexer well) index
  // the memory where the word is used, so that a clock copies only the words it needs.
`ifdef VERILATOR
`define FMPP_TILE_INDEXED
`elsif FMPP_INDEXED_READ
`define FMPP_TILE_INDEXED
`endif
`ifdef FMPP_BRAM_WORDS
  // FPGA synthesis: the words in synchronous-read RAM (the iCE40's block RAM, a copy per
  // read port), read a clock ahead (a_nx_i ...), with the write made at the edge that
  // latched the read forwarded from wd_q.
  word_t ram_a_q, ram_b_q, ram_d_q, wd_q;
  logic wfa_q, wfb_q, wfd_q;  // the RAM's read of A, B, D missed the write in wd_q
  always_ff @(posedge clk_i) begin
    ram_a_q <= mem_q[a_nx_i[WIdxW-1:0]];
    ram_b_q <= mem_q[b_nx_i[WIdxW-1:0]];
    ram_d_q <= mem_q[d_nx_i[WIdxW-1:0]];
  end
`define FMPP_RD_A (wfa_q ? wd_q : ram_a_q)
`define FMPP_RD_B (wfb_q ? wd_q : ram_b_q)
`define FMPP_RD_D (wfd_q ? wd_q : ram_d_q)
`define FMPP_RD_D_PLANE(k) (wfd_q ? wd_q[(k)*Lanes +: Lanes] : ram_d_q[(k)*Lanes +: Lanes])
`elsif FMPP_TILE_INDEXED
`define FMPP_RD_A mem_q[a_i[WIdxW-1:0]]
`define FMPP_RD_B mem_q[b_i[WIdxW-1:0]]
`define FMPP_RD_D mem_q[d_i[WIdxW-1:0]]
`define FMPP_RD_D_PLANE(k) mem_q[d_i[WIdxW-1:0]][(k)*Lanes +: Lanes]
`else
`define FMPP_RD_A rd_a
`define FMPP_RD_B rd_b
`define FMPP_RD_D rd_d
`define FMPP_RD_D_PLANE(k) rd_d[(k)*Lanes +: Lanes]
  logic [NumWords-1:0] a_oh, b_oh, d_oh;
  word_t rd_a, rd_b, rd_d;
  assign a_oh = NumWords'(1) << a_i[WIdxW-1:0];
  assign b_oh = NumWords'(1) << b_i[WIdxW-1:0];
  assign d_oh = NumWords'(1) << d_i[WIdxW-1:0];
  always_comb begin
    rd_a = '0;
    rd_b = '0;
    rd_d = '0;
    for (int w = 0; w < NumWords; w++) begin
      rd_a = rd_a | ({W*Lanes{a_oh[w]}} & mem_q[w]);
      rd_b = rd_b | ({W*Lanes{b_oh[w]}} & mem_q[w]);
      rd_d = rd_d | ({W*Lanes{d_oh[w]}} & mem_q[w]);
    end
  end
`endif

  // Selections every instruction needs, once per clock (loops, not functions: see the top).
  lane_t pred;         // flag F: the predicate (in synthesis a register: pred_q)
  lane_t flag_a;       // REF: flag REF_FS; CMP: flag CMP_FS; FLAGOP: flag FLAG_FA
  lane_t flag_b;       // FLAGOP: flag FLAG_FB
  lane_t hw_lane_sel;  // one-hot lane of a window write (the word line)
  logic  hw_sel;       // the window write is for this tile
  logic  rd_sel;       // the window read is for this tile
  logic [fmpp_pkg::LaneIdxW-1:0] rd_lane;
  assign hw_sel  = hw_block_i[15:6] == base_i[15:6];
  assign hw_lane_sel = hw_lane_sel_i;
  logic unused_hw_lane;
  assign unused_hw_lane = ^hw_block_i[fmpp_pkg::LaneIdxW-1:0];
  // Simulators read only for an enabled read (a tile not addressed does no work); synthesis
  // reads by the address alone and fmpp_array applies rd_en_i to the tiles' OR, so that the
  // address checks behind rd_en_i run beside the read.
`ifdef VERILATOR
  assign rd_sel  = rd_en_i && (rd_kind_i == fmpp_pkg::RK_PLANE ? rd_block_i[9:0] == base_i[15:6]
                                                              : rd_block_i[15:6] == base_i[15:6]);
`else
  assign rd_sel  = rd_kind_i == fmpp_pkg::RK_PLANE ? rd_block_i[9:0] == base_i[15:6]
                                                   : rd_block_i[15:6] == base_i[15:6];
  logic unused_rd_en;
  assign unused_rd_en = rd_en_i;
`endif
  assign rd_lane = rd_block_i[fmpp_pkg::LaneIdxW-1:0];
  logic [fmpp_pkg::REF_FS_W-1:0]  fa_idx;
  logic [fmpp_pkg::FLAG_FB_W-1:0] fb_idx;
  always_comb begin
    fa_idx = x_i[fmpp_pkg::REF_FS_LSB +: fmpp_pkg::REF_FS_W];
    if (!FsIsFa && op_i == fmpp_pkg::OP_FLAGOP) fa_idx = x_i[fmpp_pkg::FLAG_FA_LSB +: fmpp_pkg::FLAG_FA_W];
    if (!CmpFsIsFs && op_i == fmpp_pkg::OP_CMP) fa_idx = x_i[fmpp_pkg::CMP_FS_LSB +: fmpp_pkg::CMP_FS_W];
  end
  assign fb_idx = x_i[fmpp_pkg::FLAG_FB_LSB +: fmpp_pkg::FLAG_FB_W];
  // Each an indexed part-select (NF = 8 planes, every index in range): a balanced tree of
  // 2:1 multiplexers in synthesis (3 levels), not a priority chain of compares.
  // The predicate is selected a clock ahead, from the flags as this clock's stage 3 leaves
  // them and the F of the entry that executes next (f_nx_i), so that stage 3's write
  // multiplexers take it from a register: pred_q is always flag_q's plane f_i.
  // Simulators select it where it is used (the same plane: the lockstep tests compare the two).
`ifdef VERILATOR
  assign pred   = flag_q[f_i*Lanes +: Lanes];
  logic unused_f_nx;
  assign unused_f_nx = ^{alu_sum, f_nx_i, wpl_i, rk_i, a_nx_i, b_nx_i, d_nx_i, opr_shc_i, opr_shf_i, opr_shv_i, opr_shr_i, a_i, b_i};
`else
  lane_t pred_q;
  assign pred   = pred_q;
`endif
  assign flag_a = flag_q[fa_idx*Lanes +: Lanes];
  assign flag_b = flag_q[fb_idx*Lanes +: Lanes];

  // Bit k of every lane's block index (the ROM address part): low bits from the lane
  // number, high bits from base_i. Constant for a given tile.
  word_t index;
  always_comb begin
    for (int k = 0; k < W; k++) begin
      for (int l = 0; l < Lanes; l++) begin
        index[k*Lanes + l] = (k < 6) ? ((l >> k) & 1) == 1 : base_i[k];
      end
    end
  end

  // FLAGOP value: lut[2 fa + fb] in every lane (lut = FLAG_LUT).
  lane_t flagop_v;
  logic [fmpp_pkg::FLAG_LUT_W-1:0] lut;
  assign lut = imm_i[fmpp_pkg::FLAG_LUT_LSB +: fmpp_pkg::FLAG_LUT_W];
  always_comb begin
    flagop_v = '0;
    if (exec_i && kind_i == fmpp_pkg::QE_INSTR && op_i == fmpp_pkg::OP_FLAGOP) begin
      flagop_v = ({Lanes{lut[0]}} & ~flag_a & ~flag_b) | ({Lanes{lut[1]}} & ~flag_a & flag_b) |
                 ({Lanes{lut[2]}} &  flag_a & ~flag_b) | ({Lanes{lut[3]}} &  flag_a & flag_b);
    end
  end
  // The tile's "if any", registered: the first stage of the array's any tree (a FLAGOP with
  // FLAG_ANY waits fmpp_pkg::AnyLatency clocks in stage 3 for the tree's answer).
  always_ff @(posedge clk_i) flagop_any_o <= |flagop_v;

  // The locals of the clocked and read-port blocks are left out of waveform traces: a traced
  // temporary is one Verilator must keep in the model's memory instead of a C++ local (a
  // third of the simulation's time). The state, the operand registers and the module's
  // nets stay traced.
  /* verilator tracing_off */
  // Stages 3 and 2 in one clocked block, stage 3 first: its next state is computed only for
  // an entry that executes (a simulator does nothing on the other clocks), and stage 2 takes
  // the word stage 3 writes at this edge from its write data (forwarding), so that an entry
  // may use its predecessor's result. The shifted A and the addend are fmpp_alu_addend's
  // function; an operand that needs neither goes straight into its register (for a
  // simulator, one copy of the word instead of three). At most one flag plane (fl_dst) and
  // one word (D) change per clock, besides the C and V updates of the ALU. Every local is
  // assigned before it is read on every path, so synthesis makes no flops of them (formal
  // job pipe_1x4 checks the whole against the single-cycle tile).
  always_ff @(posedge clk_i) begin
    word_t  wr_data;                // stage 3: word D as written
`ifndef VERILATOR
    logic [2*W*Lanes-1:0] mg;       // word D and word A as read, with the new bits (not the sum)
    lane_t  wr_lanes;               // the lanes written
    word_t  alu_rs;
`endif
`ifdef FMPP_ONEHOT_SHIFT
    word_t  sh_mid, sh_out;         // stage 2's A shifted coarsely, and shifted
`endif
    flags_t flags_n;                // stage 3: the flags after the entry
    lane_t  match, src, fl_new;
`ifndef VERILATOR
    lane_t  pred_n;                 // the next predicate (pred_q)
`endif
    logic [31:0] key_mask;
    logic addr_part, fl_we, wr_en;
    logic [fmpp_pkg::F_F_W-1:0] fl_dst;
    word_t  opa_rd, opb_rd;         // stage 2's A and B (forwarded or read) where transformed
    lane_t  subs;
    logic   fwd_a, fwd_b;
`ifndef FMPP_ONEHOT_SHIFT
    logic [fmpp_pkg::SHR_A_W-1:0] shr;
`endif
    if (exec_i) begin
      flags_n  = flag_q;
      match    = '0;
      src      = '0;
      fl_new   = '0;
      fl_we    = 1'b0;
      fl_dst   = f_i;
      key_mask = mask_i;
      addr_part = 1'b0;
      case (kind_i)
        fmpp_pkg::QE_INSTR: begin
          case (op_i)
            fmpp_pkg::OP_REF, fmpp_pkg::OP_SETSADR: begin
              // Masked match: every unmasked bit of the source equals the key bit.
              addr_part = (op_i == fmpp_pkg::OP_SETSADR) ||
                          x_i[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_ADDR;
              if (op_i == fmpp_pkg::OP_SETSADR) key_mask = '0;
              match = '1;
              for (int k = 0; k < W; k++) begin
                if (!key_mask[k]) begin
                  src = addr_part ? index[k*Lanes +: Lanes] : opa_q[k*Lanes +: Lanes];
                  match = match & ~(src ^ {Lanes{imm_i[k]}});
                end
              end
              fl_we = 1'b1;
              if (op_i == fmpp_pkg::OP_SETSADR) begin
                fl_dst = 3'(fmpp_pkg::FlagSEL);
                fl_new = match;
              end else begin
                case (x_i[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W])
                  fmpp_pkg::REF_FN_AND: fl_new = flag_a & match;
                  fmpp_pkg::REF_FN_OR:  fl_new = flag_a | match;
                  default:              fl_new = match;  // THROUGH
                endcase
              end
            end
            fmpp_pkg::OP_CMP: begin
              // Signed compare with IMM on the ALU's subtracter; CMP_LT turns >= into <.
              match = alu_ge ^ {Lanes{x_i[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT}};
              fl_we = 1'b1;
              case (x_i[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W])
                fmpp_pkg::CMP_FN_AND: fl_new = flag_a & match;
                fmpp_pkg::CMP_FN_OR:  fl_new = flag_a | match;
                default:              fl_new = match;  // THROUGH
              endcase
            end
            fmpp_pkg::OP_SETS, fmpp_pkg::OP_RESETS: begin
              fl_we  = 1'b1;
              fl_dst = 3'(fmpp_pkg::FlagSEL);
              fl_new = (op_i == fmpp_pkg::OP_SETS) ? '1 : '0;
            end
            fmpp_pkg::OP_FLAGOP: begin
              fl_we  = imm_i[fmpp_pkg::FLAG_ANY_LSB +: fmpp_pkg::FLAG_ANY_W] == '0 || flagop_any_i;
              fl_new = flagop_v;
            end
            fmpp_pkg::OP_FUNC, fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_DIVSTEP,
            fmpp_pkg::OP_LSHIFT, fmpp_pkg::OP_RSHIFT: begin
              // The ALU's flags (word D below).
              if (alu_wr_c) flags_n[FC*Lanes +: Lanes] = (alu_c & pred) | (flag_q[FC*Lanes +: Lanes] & ~pred);
              if (alu_wr_v) flags_n[FV*Lanes +: Lanes] = flag_q[FV*Lanes +: Lanes] | (alu_v & pred);
            end
            default: ;  // NOP, MASKSET; WRITES and BITCOPY write word D only (below)
          endcase
        end
        fmpp_pkg::QE_FLAGS: begin
          if (hw_sel) begin
            for (int f = 0; f < NF; f++) begin
              flags_n[f*Lanes +: Lanes] = (flag_q[f*Lanes +: Lanes] & ~hw_lane_sel) | ({Lanes{hw_data_i[f]}} & hw_lane_sel);
            end
          end
        end
        default: ;
      endcase
      // The next predicate: plane f_nx_i of the flags after this edge, fl_new (the latest of
      // them) entering last, through one multiplexer of its own.
`ifndef VERILATOR
      pred_n = flags_n[f_nx_i*Lanes +: Lanes];
      if (fl_we && fl_dst == f_nx_i) pred_n = fl_new;
`endif
      if (fl_we) begin
        for (int f = 0; f < NF; f++) begin
          if (fl_dst == 3'(f)) flags_n[f*Lanes +: Lanes] = fl_new;
        end
      end
      if (!rst_ni) flag_q <= '0;
      else flag_q <= flags_n;
    end else begin
`ifndef VERILATOR
      pred_n = flag_q[f_nx_i*Lanes +: Lanes];
`endif
      if (!rst_ni) flag_q <= '0;
    end
`ifndef VERILATOR
    pred_q <= rst_ni ? pred_n : '0;
`endif
    // Word D as the executing entry writes it, by the write the array decoded (ws_*_i, at
    // most one set): in the lanes written (the predicate's, or a window write's word line)
    // the planes that change take their new bits. ADD, SUB, DIVSTEP: the adder's sum; FUNC,
    // LSHIFT, RSHIFT: the ALU's other result; WRITES: IMM in the unmasked planes; BITCOPY:
    // A's plane BIT_I (which stage 2's shifter moved to plane 0, opr_shr_i being BIT_I) into
    // plane BIT_J; a window write: its data in the planes of its byte strobes. A forwarded
    // into stage 2 is word D as written. The function is one; its text is two:
    // - simulators take the one branch of the write made and forward word D (word A is word
    //   D), so that a clock does the work of its write alone (the lockstep tests check it);
    // - synthesis builds for the clock: the sum enters last, through a multiplexer of its own
    //   behind every other choice (it is stage 3's latest signal), and the new bits are merged
    //   into word A as read as well (mg's second word), which a forward takes, so that the
    //   read of word D stands on no path into A (the formal jobs check it).
    wr_en = ws_sum_i || ws_alu_i || ws_writes_i || ws_bitcopy_i || ws_word_i;
`ifdef VERILATOR
    wr_data = '0;
    if (wr_en) begin
      if (ws_sum_i || ws_alu_i) begin
        // The ALU's result: r_o holds the sum too in this text (fmpp_alu_exec's ripple adder).
        for (int k = 0; k < W; k++) begin
          wr_data[k*Lanes +: Lanes] = (alu_r[k*Lanes +: Lanes] & pred) | (`FMPP_RD_D_PLANE(k) & ~pred);
        end
      end else begin
        wr_data = `FMPP_RD_D;
      end
      if (ws_writes_i) begin
        for (int k = 0; k < W; k++) begin
          if (!mask_i[k]) wr_data[k*Lanes +: Lanes] = ({Lanes{imm_i[k]}} & pred) | (wr_data[k*Lanes +: Lanes] & ~pred);
        end
      end else if (ws_bitcopy_i) begin
        wr_data[imm_i[fmpp_pkg::BIT_J_LSB +: fmpp_pkg::BIT_J_W]*Lanes +: Lanes] =
            (opa_q[0 +: Lanes] & pred) | (wr_data[imm_i[fmpp_pkg::BIT_J_LSB +: fmpp_pkg::BIT_J_W]*Lanes +: Lanes] & ~pred);
      end else if (ws_word_i) begin
        for (int k = 0; k < W; k++) begin
          if (hw_strb_i[k / 8]) begin
            wr_data[k*Lanes +: Lanes] = ({Lanes{hw_data_i[k]}} & hw_lane_sel) | (wr_data[k*Lanes +: Lanes] & ~hw_lane_sel);
          end
        end
      end
      // No write while rst_ni is low: the entry in stage 3 is dropped by the reset.
      if (rst_ni) mem_q[d_i[WIdxW-1:0]] <= wr_data;
    end
`else
    for (int k = 0; k < W; k++) begin
      alu_rs[k*Lanes +: Lanes] =
          (rk_i[1:0] == 2'd1 ? opa_q[k*Lanes +: Lanes] & opb_q[k*Lanes +: Lanes] :
           rk_i[1:0] == 2'd2 ? opa_q[k*Lanes +: Lanes] | opb_q[k*Lanes +: Lanes] :
           rk_i[1:0] == 2'd3 ? opa_q[k*Lanes +: Lanes] ^ opb_q[k*Lanes +: Lanes] : '0) |
          (k > 0 && rk_i[2] ? opa_q[(k > 0 ? k - 1 : 0)*Lanes +: Lanes] : '0) |
          (rk_i[3] ? opa_q[(k < W - 1 ? k + 1 : W - 1)*Lanes +: Lanes] : '0);
    end
    wr_lanes = ws_word_i ? hw_lane_sel : pred;
    mg = {`FMPP_RD_A, `FMPP_RD_D};
    for (int s = 0; s < 2; s++) begin
      for (int k = 0; k < W; k++) begin
        if (wpl_i[k]) begin
          mg[(s*W + k)*Lanes +: Lanes] =
              (wr_lanes & (ws_alu_i ? alu_rs[k*Lanes +: Lanes] :
                           ws_bitcopy_i ? opa_q[0 +: Lanes] :
                           {Lanes{ws_writes_i ? imm_i[k] : hw_data_i[k]}})) |
              (mg[(s*W + k)*Lanes +: Lanes] & ~wr_lanes);
        end
      end
    end
    wr_data = mg[0 +: W*Lanes];
    if (ws_sum_i) begin
      for (int k = 0; k < W; k++) begin
        wr_data[k*Lanes +: Lanes] = (alu_sum[k*Lanes +: Lanes] & pred) | (wr_data[k*Lanes +: Lanes] & ~pred);
      end
    end
    if (wr_en && rst_ni) mem_q[d_i[WIdxW-1:0]] <= wr_data;
`endif
`ifdef FMPP_BRAM_WORDS
    // The word written at this edge, for the reads the RAM latches at the same edge.
    if (wr_en) wd_q <= wr_data;
    wfa_q <= wr_en && rst_ni && d_i[WIdxW-1:0] == a_nx_i[WIdxW-1:0];
    wfb_q <= wr_en && rst_ni && d_i[WIdxW-1:0] == b_nx_i[WIdxW-1:0];
    wfd_q <= wr_en && rst_ni && d_i[WIdxW-1:0] == d_nx_i[WIdxW-1:0];
`endif
    // Each operand register loads only for an entry that uses it (operand isolation: the
    // array holds the word fields of the others), so the reads and the ALU stay still.
    subs = '0;
    if (opr_a_en_i) begin
      fwd_a = exec_i && fwd_a_i;  // wr_en && a_i == d_i, decoded a clock ahead
`ifdef VERILATOR
      // Simulators take A where it is used: an unshifted A is loaded from its source with
      // no copy (the shifter's path below makes one).
`define FMPP_OPA (fwd_a ? wr_data : `FMPP_RD_A)
`else
      opa_rd = fwd_a ? mg[W*Lanes +: W*Lanes] : `FMPP_RD_A;
      if (fwd_a && ws_sum_i) begin
        for (int k = 0; k < W; k++) begin
          opa_rd[k*Lanes +: Lanes] = (alu_sum[k*Lanes +: Lanes] & pred) | (opa_rd[k*Lanes +: Lanes] & ~pred);
        end
      end
`define FMPP_OPA opa_rd
`endif
`ifdef FMPP_ONEHOT_SHIFT
`ifdef VERILATOR
      opa_rd = `FMPP_OPA;
`endif
      subs = ~opa_rd[(W-1)*Lanes +: Lanes];  // DIVSTEP (which does not shift): the lanes whose A >= 0 subtract
      // FPGA synthesis: the shifter and DIVSTEP's doubling as two one-hot AND-OR stages, each
      // behind selects decoded a clock ahead (fmpp_array): plane k takes plane
      // min(k + 8c, 31) (or k - 1 to double), then min(k + f, 31). Clamping the plane is the
      // arithmetic shift's sign fill. Two levels of LUTs a stage, and each plane feeds 5 + 8
      // taps, not the 33 of a one-stage one-hot.
      for (int k = 0; k < W; k++) begin
        lane_t t0, t1, t2, t3, dbl;
        t0  = {Lanes{opr_shc_i[0]}} & opa_rd[k*Lanes +: Lanes];
        t1  = {Lanes{opr_shc_i[1]}} & opa_rd[(k + 8  < W ? k + 8  : W - 1)*Lanes +: Lanes];
        t2  = {Lanes{opr_shc_i[2]}} & opa_rd[(k + 16 < W ? k + 16 : W - 1)*Lanes +: Lanes];
        t3  = {Lanes{opr_shc_i[3]}} & opa_rd[(k + 24 < W ? k + 24 : W - 1)*Lanes +: Lanes];
        dbl = (k > 0) ? {Lanes{opr_shv_i}} & opa_rd[(k > 0 ? k - 1 : 0)*Lanes +: Lanes] : '0;
        sh_mid[k*Lanes +: Lanes] = ((t0 | t1) | (t2 | t3)) | dbl;
      end
      for (int k = 0; k < W; k++) begin
        logic [8*Lanes-1:0] f;  // tap j: plane min(k + j, 31)
        for (int j = 0; j < 8; j++) f[j*Lanes +: Lanes] = {Lanes{opr_shf_i[j]}} & sh_mid[(k + j < W ? k + j : W - 1)*Lanes +: Lanes];
        sh_out[k*Lanes +: Lanes] = ((f[0 +: Lanes] | f[Lanes +: Lanes]) | (f[2*Lanes +: Lanes] | f[3*Lanes +: Lanes])) |
                                   ((f[4*Lanes +: Lanes] | f[5*Lanes +: Lanes]) | (f[6*Lanes +: Lanes] | f[7*Lanes +: Lanes]));
      end
      opa_q <= sh_out;
`else
      shr = opr_shr_i;
      if (shr == '0 && opr_op_i != fmpp_pkg::OP_DIVSTEP) begin
        opa_q <= `FMPP_OPA;  // A as read: no copy to shift
      end else begin
        opa_rd = `FMPP_OPA;
        subs = ~opa_rd[(W-1)*Lanes +: Lanes];  // DIVSTEP (which does not shift): the lanes whose A >= 0 subtract
        // The shifter: a level per bit of SHR_A, plane k taking plane k + 2^j and the sign
        // plane filling. Each level's condition stands outside its plane loop, so that a
        // simulator tests it once (the same multiplexers).
        for (int j = 0; j < fmpp_pkg::SHR_A_W; j++) begin
          if (shr[j]) begin
            for (int k = 0; k < W; k++) begin
              opa_rd[k*Lanes +: Lanes] = opa_rd[(k + (1 << j) < W ? k + (1 << j) : W - 1)*Lanes +: Lanes];
            end
          end
        end
        if (opr_op_i == fmpp_pkg::OP_DIVSTEP) opa_rd = {opa_rd[(W-1)*Lanes-1:0], {Lanes{1'b0}}};  // A << 1
        opa_q <= opa_rd;
      end
`endif
`undef FMPP_OPA
    end
    if (opr_b_en_i) begin
      fwd_b = wr_en && b_i[WIdxW-1:0] == d_i[WIdxW-1:0];
      // The addend, the opcode tested once for all planes (DIVSTEP's subs from A above).
      if (opr_op_i == fmpp_pkg::OP_CMP) begin
        for (int k = 0; k < W; k++) opb_q[k*Lanes +: Lanes] <= {Lanes{~opr_imm_i[k]}};
      end else if (opr_op_i == fmpp_pkg::OP_SUB) begin
        opb_q <= ~(fwd_b ? wr_data : `FMPP_RD_B);
      end else if (opr_op_i == fmpp_pkg::OP_DIVSTEP) begin
        opb_rd = fwd_b ? wr_data : `FMPP_RD_B;
        for (int k = 0; k < W; k++) opb_q[k*Lanes +: Lanes] <= opb_rd[k*Lanes +: Lanes] ^ subs;
      end else begin
        opb_q <= fwd_b ? wr_data : `FMPP_RD_B;
      end
      if (opr_op_i == fmpp_pkg::OP_SUB || opr_op_i == fmpp_pkg::OP_CMP) cin_q <= '1;
      else if (opr_op_i == fmpp_pkg::OP_DIVSTEP) cin_q <= subs;
      else cin_q <= '0;
    end
  end
  /* verilator tracing_on */

  if (WIdxW < 6) begin : g_unused_hi
    logic unused_hi;
    assign unused_hi = ^{a_i[fmpp_pkg::F_A_W-1:WIdxW], b_i[fmpp_pkg::F_B_W-1:WIdxW],
                         d_i[fmpp_pkg::F_D_W-1:WIdxW], rd_word_i[5:WIdxW]};
  end

`ifdef FMPP_BRAM_WORDS_HOST
  // The host's word read: a read port of its own, enabled at the accept only, so that its
  // output holds through the R beat (the pipeline is drained when a read is accepted: no
  // write lands at that edge). hlane_q: the lane read, one-hot, 0 where the read is not a
  // word of this tile.
  word_t ram_h_q;
  lane_t hlane_q;
  always_ff @(posedge clk_i) begin
    if (rd_acc_i) ram_h_q <= mem_q[rd_word_i[WIdxW-1:0]];
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni) hlane_q <= '0;
    else if (rd_acc_i) hlane_q <= (rd_en_i && rd_kind_i == fmpp_pkg::RK_WORD && rd_sel) ? {{(Lanes-1){1'b0}}, 1'b1} << rd_lane : '0;
  end
  always_comb begin
    for (int k = 0; k < W; k++) rd_late_o[k] = |(ram_h_q[k*Lanes +: Lanes] & hlane_q);
  end
`else
  assign rd_late_o = '0;
  logic unused_rd_acc;
  assign unused_rd_acc = rd_acc_i;
`endif

  /* verilator tracing_off */
  // Host read port: the addressed lane's word (or flags) through a one-hot lane select, or a
  // whole flag plane; all inside the tile select, so a tile not addressed does no work.
  always_comb begin
    lane_t rd_lane_sel;
    rd_data_o = '0;
    rd_lane_sel = '0;
    if (rd_sel) begin
      rd_lane_sel = {{(Lanes-1){1'b0}}, 1'b1} << rd_lane;
      case (rd_kind_i)
        fmpp_pkg::RK_WORD: begin
`ifndef FMPP_BRAM_WORDS_HOST  // else rd_late_o answers, a clock later
          for (int k = 0; k < W; k++) rd_data_o[k] = |(mem_q[rd_word_i[WIdxW-1:0]][k*Lanes +: Lanes] & rd_lane_sel);
`endif
        end
        fmpp_pkg::RK_FLAGS: begin
          for (int f = 0; f < NF; f++) rd_data_o[f] = |(flag_q[f*Lanes +: Lanes] & rd_lane_sel);
        end
        default: begin  // RK_PLANE
          rd_data_o[Lanes-1:0] = flag_q[rd_flag_i*Lanes +: Lanes];  // a tree multiplexer
        end
      endcase
    end
  end

  // Responders: any, count and the lowest selected lane (isolate the lowest set bit,
  // then encode it), and whether any lane has V, into the first registers of the array's
  // responder tree. They follow the flags while a RESP or STATUS read waits (resp_en_i: the
  // read is accepted fmpp_pkg::RespLatency clocks after the queue drained) and hold otherwise.
  always_ff @(posedge clk_i) begin
    lane_t sel, lowest;
    if (resp_en_i) begin
      sel          = flag_q[fmpp_pkg::FlagSEL*Lanes +: Lanes];
      lowest       = sel & (~sel + 1'b1);
      sel_any_o   <= |sel;
      sel_count_o <= $countones(sel);
      for (int k = 0; k < 6; k++) sel_first_o[k] <= |(lowest & index[k*Lanes +: Lanes]);
      ovf_any_o   <= |flag_q[FV*Lanes +: Lanes];
    end
  end

  // Coverage (make coverage only: named cover points would give each tile its own code)
`ifdef FMPP_COVERAGE
  // Some lane's adder carries out and overflows (Verilator 5.006 merges the loop's
  // iterations into one point per tile; every lane: tests/rtl_units/alu_unit_test.cpp).
  for (genvar l = 0; l < Lanes; l++) begin : g_cov_lane
    c_carry: cover property (@(posedge clk_i) exec_i && kind_i == fmpp_pkg::QE_INSTR && alu_wr_c && pred[l] && alu_c[l]);
    c_ovf: cover property (@(posedge clk_i) exec_i && kind_i == fmpp_pkg::QE_INSTR && alu_wr_v && pred[l] && alu_v[l]);
  end
`endif

  // Elaboration check (run-time properties of the tile's inputs: fmpp_array).
`ifndef SYNTHESIS
  if (Lanes < 1 || Lanes > fmpp_pkg::LaneW) begin : g_bad_lanes
    $error("fmpp_tile: Lanes = %0d outside [1, %0d]", Lanes, fmpp_pkg::LaneW);
  end
`endif

  /* verilator tracing_on */

`undef FMPP_RD_A
`undef FMPP_RD_B
`undef FMPP_RD_D
`undef FMPP_RD_D_PLANE
`undef FMPP_TILE_INDEXED

endmodule
