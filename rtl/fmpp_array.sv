// fmpp_array: the FMPP processor array and its sequencer.
//
// Holds NumBlocks blocks in ceil(NumBlocks / 64) tiles (fmpp_tile), the mask
// register and the INSTRET counter. Each clock it may pop the head of the
// instruction queue (one entry per clock, then CTRL.GAP idle clocks) into a
// three-stage pipeline that every tile runs in step:
//   1. queue read and decode: the head is decoded into the stage-2 register at the pop;
//   2. operand read: each tile reads words A and B into its operand registers, taking
//      the value stage 3 writes in the same clock when it writes that word (forwarding);
//   3. execute and write back: ALU, match, compare and flag logic on the operand
//      registers, the flags and word D read as they are now; the word, the flags,
//      MASK and INSTRET change at the clock edge that ends this stage (the entry retires).
// An entry therefore retires two clocks after its pop, and entries still issue one per
// clock whatever they read: there is no stall. busy_o says that an entry is in stages
// 2-3; the slave lets reads through only when the queue is empty and busy_o is low.
// It combines the tiles' responders (ANY, COUNT, FIRST over SEL), the FLAGOP "if any"
// condition and the host read port.
module fmpp_array #(
  parameter int unsigned NumBlocks = 64,
  parameter int unsigned NumWords  = 32
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // Instruction queue head
  input  fmpp_pkg::qentry_t    head_i,
  input  logic                 head_valid_i,
  output logic                 pop_o,
  input  logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap_i,  // CTRL.GAP
  output logic                 busy_o,       // entries popped but not yet retired

  // Host read port (combinational; reads are only accepted while the queue is empty)
  input  logic                 rd_en_i,
  input  fmpp_pkg::rkind_e     rd_kind_i,
  input  logic [fmpp_pkg::BlockIdxW-1:0] rd_block_i,  // block (WORD, FLAGS) or tile (PLANE)
  input  logic [fmpp_pkg::WordIdxW-1:0]  rd_word_i,
  input  logic [fmpp_pkg::FlagIdxW-1:0]  rd_flag_i,
  output logic [63:0]          rd_data_o,
  input  logic                 rd_acc_i,    // the read is accepted at this edge (FMPP_BRAM_WORDS_HOST)
  output logic [31:0]          rd_late_o,   // the word read accepted a clock ago (FMPP_BRAM_WORDS_HOST; else 0)

  // Responders and summaries (the responder tree's top registers: valid RespLatency clocks
  // after resp_en_i rose with the flags settled)
  input  logic                 resp_en_i,
  output logic                 resp_any_o,
  output logic [fmpp_pkg::REG_RESP_COUNT_W-1:0] resp_count_o,
  output logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] resp_first_o,
  output logic                 ovf_any_o,

  output logic [fmpp_pkg::REG_MASK_VALUE_W-1:0] mask_o,
  output logic [fmpp_pkg::REG_INSTRET_VALUE_W-1:0] instret_o
);
  localparam int unsigned LaneW    = fmpp_pkg::LaneW;
  localparam int unsigned NumTiles = (NumBlocks + LaneW - 1) / LaneW;
  localparam int unsigned LastLanes = NumBlocks - (NumTiles - 1) * LaneW;

  // Sequencer: pop one entry per clock, then idle for CTRL.GAP clocks.
  logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap_q;
  // Public for the lockstep checker (tb/), which reads the state directly.
  logic [31:0] mask_q /*verilator public_flat_rd*/;
  logic [63:0] instret_q /*verilator public_flat_rd*/;
  logic        pop /*verilator public_flat_rd*/;
  logic        is_instr;
  logic [63:0] instr;

  // No entry executes while rst_ni is low: the queue's level resets at the same edge,
  // and an entry executed then would write a word (words have no reset) that the reset
  // was meant to drop (found by the soak's resets in the middle of programs). The
  // pipeline's valid bits reset with it, and the tiles gate their word write with rst_ni.
  assign pop      = rst_ni && head_valid_i && gap_q == '0 && !hold;
  assign pop_o    = pop;
  assign is_instr = head_i.kind == fmpp_pkg::QE_INSTR;
  assign instr    = head_i.data;

  // Stage 1: decode of the queue head. Window writes reuse D for the word; an entry
  // that is not an instruction carries OP_NOP, so no opcode test needs its kind.
  logic [fmpp_pkg::F_OP_W-1:0]  dc_op;
  logic [fmpp_pkg::F_D_W-1:0]   dc_d;
  logic [fmpp_pkg::F_IMM_W-1:0] dc_imm;  // IMM, or the data of a window write
  assign dc_op = is_instr ? instr[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W] : fmpp_pkg::OP_NOP;
  assign dc_d  = is_instr ? instr[fmpp_pkg::F_D_LSB +: fmpp_pkg::F_D_W] : head_i.word;
  assign dc_imm = is_instr ? instr[fmpp_pkg::F_IMM_LSB +: fmpp_pkg::F_IMM_W] : head_i.data[31:0];
  // Which words the entry reads and writes (operand isolation): the stage registers of A, B
  // and D load only with an entry that uses them, and a tile loads an operand register only
  // for an entry that uses it, so that an entry leaves the word reads it does not need (and
  // the ALU behind them) still. The slave decodes the uses at the push (queue entry fields
  // rd_a, rd_b, wr_d), so the pop's enables do not wait for a decode before the trunk to
  // the groups. dc_ld_b: the addend register (word B, or CMP's IMM).
  logic dc_rd_a, dc_rd_b, dc_ld_b, dc_wr_d;
  assign dc_rd_a = head_i.rd_a;
  assign dc_rd_b = head_i.rd_b;
  assign dc_wr_d = head_i.wr_d;
  assign dc_ld_b = dc_rd_b || dc_op == fmpp_pkg::OP_CMP;
  // The shift of word A in stage 2 (decoded here, so that the tiles' shifters take their
  // selects from registers): SHR_A for ADD, SUB and RSHIFT; BITCOPY's source bit BIT_I,
  // which brings that plane to plane 0; none for the others.
  logic [fmpp_pkg::SHR_A_W-1:0] dc_shr;
  always_comb begin
    dc_shr = '0;
    if (dc_op == fmpp_pkg::OP_ADD || dc_op == fmpp_pkg::OP_SUB || dc_op == fmpp_pkg::OP_RSHIFT) begin
      dc_shr = dc_imm[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W];
    end else if (dc_op == fmpp_pkg::OP_BITCOPY) begin
      dc_shr = dc_imm[fmpp_pkg::BIT_I_LSB +: fmpp_pkg::BIT_I_W];
    end
  end
`ifdef FMPP_ONEHOT_SHIFT
  // FPGA synthesis: the shifter's selects for the tiles (fmpp_tile.sv), one-hot: the coarse
  // shift by 8 x SHR[4:3] (dc_shc) and the fine one by SHR[2:0] (dc_shf); DIVSTEP doubles A
  // instead (dc_shv, no shift).
  logic [3:0] dc_shc;
  logic [7:0] dc_shf;
  logic       dc_shv;
  assign dc_shv = dc_op == fmpp_pkg::OP_DIVSTEP;
  assign dc_shc = dc_shv ? 4'd0 : 4'd1 << dc_shr[4:3];
  assign dc_shf = dc_shv ? 8'd1 : 8'd1 << dc_shr[2:0];
`endif
  // Likewise the instruction's write of word D, one bit a kind ({BITCOPY, WRITES, FUNC/LSHIFT/
  // RSHIFT, ADD/SUB/DIVSTEP}, none for other entries), and the ALU's opcode: the
  // instruction's where the ALU serves it (any but BITCOPY, which the tile does itself), NOP
  // for other entries.
  logic [3:0]                  dc_wk;
  logic [fmpp_pkg::F_OP_W-1:0] dc_aop;
  always_comb begin
    dc_wk  = '0;
    dc_aop = fmpp_pkg::OP_NOP;
    if (head_i.kind == fmpp_pkg::QE_INSTR) begin
      case (dc_op)
        fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_DIVSTEP:   dc_wk[0] = 1'b1;
        fmpp_pkg::OP_FUNC, fmpp_pkg::OP_LSHIFT, fmpp_pkg::OP_RSHIFT: dc_wk[1] = 1'b1;
        fmpp_pkg::OP_WRITES:                                         dc_wk[2] = 1'b1;
        fmpp_pkg::OP_BITCOPY:                                        dc_wk[3] = 1'b1;
        default: ;
      endcase
      if (dc_op != fmpp_pkg::OP_BITCOPY) dc_aop = dc_op;
    end
  end

  // Stage registers: s2_* holds the entry in operand read, s3_* the entry executing.
  // s3_valid_q is the retire signal: the entry's effects land at the next clock edge
  // (public: the lockstep checker snapshots the state after every retire).
  logic                         s2_valid_q, s3_valid_q;
  logic                         retire /*verilator public_flat_rd*/;
  // (The central copies keep only what the sequencer needs: the tiles take their fields from
  // their group's and their own copies below.)
  fmpp_pkg::qkind_e             s2_kind_q, s3_kind_q;
  logic [fmpp_pkg::F_OP_W-1:0]  s2_op_q, s3_op_q;
  logic [fmpp_pkg::F_IMM_W-1:0] s2_imm_q, s3_imm_q;

  // A FLAGOP with FLAG_ANY waits in stage 3 for the any tree (the tile, group and top registers
  // and the group's copy of the answer):
  // the pipeline holds for AnyLatency clocks (no pop, stages 2 and 3 keep their entries, the
  // tiles write nothing), and the entry executes in the clock after, with the tree's answer.
  // The centre and every group compute the hold from their own copies of stage 3's control
  // fields (alike by construction), so that no hold crosses the die.
  localparam int unsigned AnyLat = fmpp_pkg::AnyLatency;
  localparam int unsigned CntW   = $clog2(AnyLat + 1);
  logic [CntW-1:0] hold_cnt_q;
  logic hold;
  assign hold = s3_valid_q && s3_kind_q == fmpp_pkg::QE_INSTR && s3_op_q == fmpp_pkg::OP_FLAGOP &&
                s3_imm_q[fmpp_pkg::FLAG_ANY_LSB] && 32'(hold_cnt_q) != AnyLat;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s2_valid_q <= 1'b0;
      s3_valid_q <= 1'b0;
      hold_cnt_q <= '0;
    end else if (hold) begin
      hold_cnt_q <= hold_cnt_q + 1'b1;
    end else begin
      s2_valid_q <= pop;
      s3_valid_q <= s2_valid_q;
      hold_cnt_q <= '0;
    end
  end

  // The payload moves only with an entry (no reset: its valid bit says whether it counts).
  always_ff @(posedge clk_i) begin
    if (pop) begin
      s2_kind_q <= head_i.kind;
      s2_op_q   <= dc_op;
      s2_imm_q  <= dc_imm;
    end
    if (s2_valid_q && !hold) begin
      s3_kind_q <= s2_kind_q;
      s3_op_q   <= s2_op_q;
      s3_imm_q  <= s2_imm_q;
    end
  end

  assign retire = s3_valid_q && !hold;
  assign busy_o = s2_valid_q || s3_valid_q;

  logic [63:0] instret_inc;
  fmpp_incr #(.W(64)) u_instret_inc (.q_i(instret_q), .inc_o(instret_inc));

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      gap_q     <= '0;
      mask_q    <= '0;
      instret_q <= '0;
    end else begin
      if (pop) begin
        gap_q <= gap_i;
      end else if (gap_q != '0) begin
        gap_q <= gap_q - 1'b1;
      end
      if (retire && s3_kind_q == fmpp_pkg::QE_INSTR) begin
        instret_q <= instret_inc;
        if (s3_op_q == fmpp_pkg::OP_MASKSET) mask_q <= s3_imm_q;
      end
    end
  end

  assign mask_o    = mask_q;
  assign instret_o = instret_q;

  // The executing entry's opcode, for the waveforms and the cover points.
  logic [fmpp_pkg::F_OP_W-1:0]  op;
  assign op  = s3_op_q;

  // The broadcast: every group of TreeGroup tiles has its own copy of the stage-2 registers
  // and their valid bit, of stage 3's control fields and of the hold (loaded at the same
  // edges as the central ones); every tile has its own copy of stage 3 and of MASK, loaded
  // from its group's stage 2. So no register drives more than a group's tiles, and a tile's
  // stage 3 sits at the tile. (The copies' processes are kept: yosys would merge copies that
  // have the same inputs into one.)
  localparam int unsigned GroupW    = fmpp_pkg::TreeGroup;
  localparam int unsigned WIdxW     = (NumWords > 1) ? $clog2(NumWords) : 1;  // as the tile's
  localparam int unsigned BlockHiW  = fmpp_pkg::BlockIdxW - fmpp_pkg::LaneIdxW;
  localparam int unsigned NumGroups = (NumTiles + GroupW - 1) / GroupW;
  logic top_flag_q;
  for (genvar g = 0; g < NumGroups; g++) begin : g_bc
    logic                         v2_q, v3_q, any3_q, ans_q, hold_g;
    logic                         rd_a2_q, ld_b2_q;  // the entry reads word A; loads the addend
    logic [WIdxW-1:0]             a2_n;              // word A of stage 2 after the next edge
    logic [WIdxW-1:0]             b2_n;
    logic [fmpp_pkg::F_A_W-1:0]   a2_q;
    logic [fmpp_pkg::F_B_W-1:0]   b2_q;
    logic [fmpp_pkg::F_OP_W-1:0]  op2_q, op3_q;
    logic [fmpp_pkg::F_IMM_W-1:0] imm2_q;
    logic [fmpp_pkg::SHR_A_W-1:0] shr2_q;
    // FPGA synthesis (FMPP_ONEHOT_SHIFT): stage 2's shifter selects as registers: the shift
    // one-hots, coarse (shc2_q) and fine (shf2_q), and DIVSTEP's doubling (shv2_q).
    logic [3:0]                   shc2_q;
    logic [7:0]                   shf2_q;
    logic                         shv2_q;
`ifndef FMPP_ONEHOT_SHIFT
    assign {shc2_q, shf2_q, shv2_q} = '0;
`endif
    logic [3:0]                   wk2_q;   // dc_wk of the entry
    logic [fmpp_pkg::F_OP_W-1:0]  aop2_q;  // dc_aop of the entry
    fmpp_pkg::qkind_e             kind2_q, kind3_q;
    logic [fmpp_pkg::F_F_W-1:0]   f2_q;
    logic [fmpp_pkg::F_D_W-1:0]   d2_q;
    logic [fmpp_pkg::F_X_W-1:0]   x2_q;
    logic [fmpp_pkg::BlockIdxW-1:0] block2_q;
    logic [3:0]                   strb2_q;
    logic [CntW-1:0]              cnt_q;
    assign a2_n = (pop && dc_rd_a) ? instr[fmpp_pkg::F_A_LSB +: WIdxW] : a2_q[WIdxW-1:0];
    assign b2_n = (pop && dc_rd_b) ? instr[fmpp_pkg::F_B_LSB +: WIdxW] : b2_q[WIdxW-1:0];
    // The same hold as the centre's, from the group's own copies.
    assign hold_g = v3_q && kind3_q == fmpp_pkg::QE_INSTR && op3_q == fmpp_pkg::OP_FLAGOP && any3_q &&
                    32'(cnt_q) != AnyLat;
    (* keep *) always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        {v2_q, v3_q, cnt_q} <= '0;
      end else if (hold_g) begin
        cnt_q <= cnt_q + 1'b1;
      end else begin
        {v2_q, v3_q, cnt_q} <= {pop, v2_q, CntW'(0)};
      end
    end
    (* keep *) always_ff @(posedge clk_i) begin
      if (pop) begin
        {kind2_q, op2_q, f2_q, x2_q} <= {head_i.kind, dc_op, instr[fmpp_pkg::F_F_LSB +: fmpp_pkg::F_F_W],
                                         instr[fmpp_pkg::F_X_LSB +: fmpp_pkg::F_X_W]};
        {rd_a2_q, ld_b2_q}           <= {dc_rd_a, dc_ld_b};
        {imm2_q, shr2_q, block2_q, strb2_q} <= {dc_imm, dc_shr, head_i.block, head_i.strb};
`ifdef FMPP_ONEHOT_SHIFT
        {shc2_q, shf2_q, shv2_q} <= {dc_shc, dc_shf, dc_shv};
`endif
        {wk2_q, aop2_q}                     <= {dc_wk, dc_aop};
        // The word fields keep the last entry's that used them (operand isolation).
        if (dc_rd_a) a2_q <= instr[fmpp_pkg::F_A_LSB +: fmpp_pkg::F_A_W];
        if (dc_rd_b) b2_q <= instr[fmpp_pkg::F_B_LSB +: fmpp_pkg::F_B_W];
        if (dc_wr_d) d2_q <= dc_d;
      end
      if (v2_q && !hold_g) {kind3_q, op3_q, any3_q} <= {kind2_q, op2_q, imm2_q[fmpp_pkg::FLAG_ANY_LSB]};
      // The last register of the any tree: the top register's answer, near the group's tiles.
      ans_q <= top_flag_q;
    end
  end

  for (genvar t = 0; t < NumTiles; t++) begin : g_t3
    logic                         v3_q;
    fmpp_pkg::qkind_e             kind3_q;
    logic [fmpp_pkg::F_OP_W-1:0]  op3_q;
    logic [fmpp_pkg::F_F_W-1:0]   f3_q;
    logic [fmpp_pkg::F_D_W-1:0]   d3_q;
    logic [fmpp_pkg::F_X_W-1:0]   x3_q;
    logic [fmpp_pkg::F_IMM_W-1:0] imm3_q;
    logic [fmpp_pkg::BlockIdxW-1:0] block3_q;
    localparam int unsigned L3 = (t == NumTiles - 1) ? LastLanes : LaneW;  // the tile's lanes
    logic [L3-1:0]                lsel3_q;  // block3_q's lane, one-hot (a window write's word line)
    logic [3:0]                   strb3_q;
    logic [31:0]                  tmask_q;
    // Stage 3's write of word D and the forwarding of it into stage 2's A, decoded a clock
    // ahead, so that the tile's write and forward multiplexers take their selects from
    // registers. ws3_q: the write the executing entry makes in this tile, one bit each (0 where
    // none executes): {a window write of one word here, BITCOPY, WRITES, FUNC/LSHIFT/RSHIFT,
    // ADD/SUB/DIVSTEP}. fwd_a3_q: there is one, and the entry in stage 2 reads that word as A.
    // Both follow the stages' own loads (stage 3 takes stage 2's entry unless it holds).
    logic [4:0]                   ws3_q, ws2, ws3_n;
    // aop3_q: the ALU's opcode, the executing entry's where it is an instruction the ALU
    // serves (any but BITCOPY, which the tile does itself), NOP otherwise.
    logic [fmpp_pkg::F_OP_W-1:0]  aop3_q;
    logic                         fwd_a3_q, mv3;
    logic [WIdxW-1:0]             d3_n;
    logic [fmpp_pkg::F_F_W-1:0]   f3_n;  // F of the entry in stage 3 after the next edge
    assign mv3 = g_bc[t / GroupW].v2_q && !g_bc[t / GroupW].hold_g;  // stage 2's entry moves on
    // The write in this tile of the entry in stage 2: an instruction's (the same in every
    // tile), or a window write of one word of this tile.
    assign ws2 = {g_bc[t / GroupW].kind2_q == fmpp_pkg::QE_WORD &&
                  g_bc[t / GroupW].block2_q[fmpp_pkg::BlockIdxW-1:fmpp_pkg::LaneIdxW] ==
                  BlockHiW'((t * fmpp_pkg::LaneW) >> fmpp_pkg::LaneIdxW), g_bc[t / GroupW].wk2_q};
    assign ws3_n = g_bc[t / GroupW].hold_g ? ws3_q : (g_bc[t / GroupW].v2_q ? ws2 : '0);
    assign d3_n  = mv3 ? g_bc[t / GroupW].d2_q[WIdxW-1:0] : d3_q[WIdxW-1:0];
    assign f3_n  = mv3 ? g_bc[t / GroupW].f2_q : f3_q;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        {ws3_q, fwd_a3_q} <= '0;
        aop3_q <= fmpp_pkg::OP_NOP;
      end else begin
        ws3_q    <= ws3_n;
        if (!g_bc[t / GroupW].hold_g) aop3_q <= g_bc[t / GroupW].v2_q ? g_bc[t / GroupW].aop2_q : fmpp_pkg::OP_NOP;
        fwd_a3_q <= ws3_n != '0 && g_bc[t / GroupW].a2_n == d3_n;
      end
    end
    logic [fmpp_pkg::WordW-1:0]   wpl3_q;
    logic [3:0]                   rk3_q;
`ifndef VERILATOR
    logic [fmpp_pkg::F_IMM_W-1:0] imm3_n;
    logic [3:0]                   strb3_n;
    logic [31:0]                  tmask_n;
    logic [fmpp_pkg::F_OP_W-1:0]  aop3_n;
    logic [fmpp_pkg::FUNC_FN_W-1:0] fn3_n;
    assign aop3_n = g_bc[t / GroupW].hold_g ? aop3_q : (g_bc[t / GroupW].v2_q ? g_bc[t / GroupW].aop2_q : fmpp_pkg::OP_NOP);
    assign fn3_n  = mv3 ? g_bc[t / GroupW].x2_q[fmpp_pkg::FUNC_FN_LSB +: fmpp_pkg::FUNC_FN_W]
                        : x3_q[fmpp_pkg::FUNC_FN_LSB +: fmpp_pkg::FUNC_FN_W];
    assign imm3_n  = mv3 ? g_bc[t / GroupW].imm2_q : imm3_q;
    assign strb3_n = mv3 ? g_bc[t / GroupW].strb2_q : strb3_q;
    assign tmask_n = (v3_q && kind3_q == fmpp_pkg::QE_INSTR && op3_q == fmpp_pkg::OP_MASKSET) ? imm3_q : tmask_q;
    always_ff @(posedge clk_i) begin
      for (int k = 0; k < fmpp_pkg::WordW; k++) begin
        wpl3_q[k] <= rst_ni && (ws3_n[1] || (ws3_n[2] && !tmask_n[k]) || (ws3_n[4] && strb3_n[k / 8]) ||
                                (ws3_n[3] && imm3_n[fmpp_pkg::BIT_J_LSB +: fmpp_pkg::BIT_J_W] == 5'(k)));
      end
      rk3_q <= '0;
      if (rst_ni) begin
        rk3_q[3] <= aop3_n == fmpp_pkg::OP_RSHIFT;
        rk3_q[2] <= aop3_n == fmpp_pkg::OP_LSHIFT;
        if (aop3_n == fmpp_pkg::OP_FUNC) begin
          rk3_q[1:0] <= fn3_n == fmpp_pkg::FUNC_FN_AND ? 2'd1 : fn3_n == fmpp_pkg::FUNC_FN_OR ? 2'd2 : 2'd3;
        end
      end
    end
`else
    assign {wpl3_q, rk3_q} = '0;
`endif
    (* keep *) always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        {v3_q, tmask_q} <= '0;
      end else begin
        if (!g_bc[t / GroupW].hold_g) v3_q <= g_bc[t / GroupW].v2_q;
        if (v3_q && kind3_q == fmpp_pkg::QE_INSTR && op3_q == fmpp_pkg::OP_MASKSET) tmask_q <= imm3_q;
      end
    end
    (* keep *) always_ff @(posedge clk_i) begin
      if (g_bc[t / GroupW].v2_q && !g_bc[t / GroupW].hold_g) begin
        {kind3_q, op3_q, f3_q, d3_q, x3_q} <= {g_bc[t / GroupW].kind2_q, g_bc[t / GroupW].op2_q,
                                               g_bc[t / GroupW].f2_q, g_bc[t / GroupW].d2_q, g_bc[t / GroupW].x2_q};
        lsel3_q                           <= L3'(1) << g_bc[t / GroupW].block2_q[fmpp_pkg::LaneIdxW-1:0];
        {imm3_q, block3_q, strb3_q}       <= {g_bc[t / GroupW].imm2_q, g_bc[t / GroupW].block2_q,
                                               g_bc[t / GroupW].strb2_q};
      end
    end
  end

  // Tiles
  logic        t_flagop_any [NumTiles];
  logic        t_sel_any    [NumTiles];
  logic [31:0] t_sel_count  [NumTiles];
  logic [fmpp_pkg::LaneIdxW-1:0] t_sel_first [NumTiles];
  logic        t_ovf_any    [NumTiles];
  logic [63:0] t_rd_data    [NumTiles];
  logic [31:0] t_rd_late    [NumTiles];

  for (genvar t = 0; t < NumTiles; t++) begin : g_tile
    localparam int unsigned Lanes = (t == NumTiles - 1) ? LastLanes : LaneW;
    fmpp_tile #(.Lanes(Lanes), .NumWords(NumWords)) u_tile (
      .clk_i,
      .rst_ni,
      .base_i       (t * LaneW),
      .opr_a_en_i   (g_bc[t / GroupW].v2_q && g_bc[t / GroupW].rd_a2_q),
      .opr_b_en_i   (g_bc[t / GroupW].v2_q && g_bc[t / GroupW].ld_b2_q),
      .a_i          (g_bc[t / GroupW].a2_q),
      .b_i          (g_bc[t / GroupW].b2_q),
      .opr_op_i     (g_bc[t / GroupW].op2_q),
      .opr_imm_i    (g_bc[t / GroupW].imm2_q),
      .opr_shr_i    (g_bc[t / GroupW].shr2_q),
      .opr_shc_i    (g_bc[t / GroupW].shc2_q),
      .opr_shf_i    (g_bc[t / GroupW].shf2_q),
      .opr_shv_i    (g_bc[t / GroupW].shv2_q),
      .fwd_a_i      (g_t3[t].fwd_a3_q),
      .exec_i       (g_t3[t].v3_q),
      .alu_op_i     (g_t3[t].aop3_q),
      .ws_sum_i     (g_t3[t].ws3_q[0]),
      .ws_alu_i     (g_t3[t].ws3_q[1]),
      .ws_writes_i  (g_t3[t].ws3_q[2]),
      .ws_bitcopy_i (g_t3[t].ws3_q[3]),
      .ws_word_i    (g_t3[t].ws3_q[4]),
      .kind_i       (g_t3[t].kind3_q),
      .op_i         (g_t3[t].op3_q),
      .f_nx_i       (g_t3[t].f3_n),
      .f_i          (g_t3[t].f3_q),
      .d_i          (g_t3[t].d3_q),
      .x_i          (g_t3[t].x3_q),
      .imm_i        (g_t3[t].imm3_q),
      .mask_i       (g_t3[t].tmask_q),
      .wpl_i        (g_t3[t].wpl3_q),
      .rk_i         (g_t3[t].rk3_q),
      .a_nx_i       (6'(g_bc[t / GroupW].a2_n)),
      .b_nx_i       (6'(g_bc[t / GroupW].b2_n)),
      .d_nx_i       (6'(g_t3[t].d3_n)),
      .hw_block_i   (g_t3[t].block3_q),
      .hw_lane_sel_i (g_t3[t].lsel3_q),
      .hw_strb_i    (g_t3[t].strb3_q),
      .hw_data_i    (g_t3[t].imm3_q),
      // The tiles write FLAGOP's "if any" only once the tree has answered (none while holding).
      .flagop_any_i (g_bc[t / GroupW].ans_q && !g_bc[t / GroupW].hold_g),
      .flagop_any_o (t_flagop_any[t]),
      .rd_en_i      (rd_en_i),
      .rd_kind_i    (rd_kind_i),
      .rd_block_i   (rd_block_i),
      .rd_word_i    (rd_word_i),
      .rd_flag_i    (rd_flag_i),
      .rd_data_o    (t_rd_data[t]),
      .rd_acc_i     (rd_acc_i),
      .rd_late_o    (t_rd_late[t]),
      .resp_en_i    (resp_en_i),
      .sel_any_o    (t_sel_any[t]),
      .sel_count_o  (t_sel_count[t]),
      .sel_first_o  (t_sel_first[t]),
      .ovf_any_o    (t_ovf_any[t])
    );
  end


  // Read data: only the addressed tile drives a non-zero value.
  always_comb begin
    rd_data_o = '0;
    for (int t = 0; t < NumTiles; t++) rd_data_o = rd_data_o | t_rd_data[t];
    // In synthesis the tiles answer by the address alone and rd_en_i enters here, last
    // (0 for any read but a mapped window's); simulators gate each tile instead.
    if (!rd_en_i) rd_data_o = '0;
  end
  always_comb begin
    rd_late_o = '0;
    for (int t = 0; t < NumTiles; t++) rd_late_o = rd_late_o | t_rd_late[t];
  end

  // The reduction trees: each tile's answers are registered in the tile, a register per group
  // of TreeGroup tiles combines its tiles', and a top register combines the groups'. The
  // responders follow the flags while a RESP or STATUS read waits (resp_en_i) and the slave
  // accepts the read RespLatency clocks after the queue drained; FLAGOP's any runs every clock.
  logic        g_any_q   [NumGroups];
  logic [31:0] g_count_q [NumGroups];
  logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] g_first_q [NumGroups];
  logic        g_ovf_q   [NumGroups];
  logic        g_flag_q  [NumGroups];

  // FIRST is the lowest selected block, so each scan runs from the top down.
  always_ff @(posedge clk_i) begin
    for (int g = 0; g < NumGroups; g++) begin
      logic any, ovf, fl;
      logic [31:0] count;
      logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] first;
      {any, ovf, fl, count, first} = '0;
      for (int t = GroupW - 1; t >= 0; t--) begin
        if (g * GroupW + t < NumTiles) begin
          count = count + t_sel_count[g * GroupW + t];
          ovf   = ovf | t_ovf_any[g * GroupW + t];
          fl    = fl | t_flagop_any[g * GroupW + t];
          if (t_sel_any[g * GroupW + t]) begin
            any   = 1'b1;
            first = fmpp_pkg::REG_RESP_FIRST_W'((g * GroupW + t) * LaneW) |
                    fmpp_pkg::REG_RESP_FIRST_W'(t_sel_first[g * GroupW + t]);
          end
        end
      end
      g_flag_q[g] <= fl;
      if (resp_en_i) begin
        g_any_q[g]   <= any;
        g_count_q[g] <= count;
        g_first_q[g] <= first;
        g_ovf_q[g]   <= ovf;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    logic any, ovf, fl;
    logic [fmpp_pkg::REG_RESP_COUNT_W-1:0] count;
    logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] first;
    {any, ovf, fl, count, first} = '0;
    for (int g = NumGroups - 1; g >= 0; g--) begin
      count = count + fmpp_pkg::REG_RESP_COUNT_W'(g_count_q[g]);
      ovf   = ovf | g_ovf_q[g];
      fl    = fl | g_flag_q[g];
      if (g_any_q[g]) begin
        any   = 1'b1;
        first = g_first_q[g];
      end
    end
    top_flag_q <= fl;
    if (resp_en_i) begin
      resp_any_o   <= any;
      resp_count_o <= count;
      resp_first_o <= first;
      ovf_any_o    <= ovf;
    end
  end

`ifndef SYNTHESIS
  // The executing opcode by name, for waveforms.
  /* verilator lint_off UNUSEDSIGNAL */
  fmpp_pkg::opcode_e dbg_op;
  /* verilator lint_on UNUSEDSIGNAL */
  assign dbg_op = fmpp_pkg::opcode_e'(op);
`endif

  // Coverage (make coverage): every opcode executed, every REF function on the data and
  // on the address part, every CMP function with >= and <, FLAGOP "if any" taken and not taken, the sequencer stalled by GAP;
  // and the pipeline's cases: each forwarding path (A, B, both, from each kind of word
  // write), the dependencies that need none (a flag or MASK written by the entry ahead),
  // bubbles, a full pipeline, a read or register access waiting for the drain, a reset
  // dropping entries in flight.
`ifdef FMPP_COVERAGE
  // The words the entries in stages 2 and 3 read and write (every group's copies are alike).
  logic [fmpp_pkg::F_A_W-1:0] s2_a_q;
  logic [fmpp_pkg::F_B_W-1:0] s2_b_q;
  logic [fmpp_pkg::F_D_W-1:0] s3_d_q;
  assign s2_a_q = g_bc[0].a2_q;
  assign s2_b_q = g_bc[0].b2_q;
  assign s3_d_q = g_t3[0].d3_q;
  /* verilator lint_off UNUSEDSIGNAL */
  logic [fmpp_pkg::F_X_W-1:0]   x;  // every sub-field of the executing entry's X
  /* verilator lint_on UNUSEDSIGNAL */
  logic [fmpp_pkg::F_IMM_W-1:0] imm;
  assign x      = g_t3[0].x3_q;
  assign imm    = s3_imm_q;
  // Executed at this edge: an instruction (ex_instr); which word the entry in stage 3
  // writes and which words the instruction in stage 2 reads.
  logic ex_instr, s3_wr_word, s2_rd_a, s2_rd_b, s2_instr, s3_wr_flag, s2_rd_flag, s2_rd_mask;
  assign ex_instr = retire && s3_kind_q == fmpp_pkg::QE_INSTR;
  assign s2_instr = s2_valid_q && s2_kind_q == fmpp_pkg::QE_INSTR;
  always_comb begin
    s3_wr_word = 1'b0;
    s3_wr_flag = 1'b0;
    s2_rd_a    = 1'b0;
    s2_rd_b    = 1'b0;
    s2_rd_flag = 1'b0;
    s2_rd_mask = 1'b0;
    if (retire && s3_kind_q == fmpp_pkg::QE_WORD) s3_wr_word = 1'b1;
    if (retire && s3_kind_q == fmpp_pkg::QE_FLAGS) s3_wr_flag = 1'b1;
    if (ex_instr) begin
      case (s3_op_q)
        fmpp_pkg::OP_FUNC, fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_DIVSTEP, fmpp_pkg::OP_BITCOPY,
        fmpp_pkg::OP_LSHIFT, fmpp_pkg::OP_RSHIFT, fmpp_pkg::OP_WRITES: s3_wr_word = 1'b1;
        fmpp_pkg::OP_REF, fmpp_pkg::OP_CMP, fmpp_pkg::OP_SETS, fmpp_pkg::OP_RESETS, fmpp_pkg::OP_SETSADR,
        fmpp_pkg::OP_FLAGOP: s3_wr_flag = 1'b1;
        default: ;
      endcase
    end
    if (s2_instr) begin
      s2_rd_a = g_bc[0].rd_a2_q;
      s2_rd_b = g_bc[0].ld_b2_q && s2_op_q != fmpp_pkg::OP_CMP;  // CMP's addend is IMM
      // Every opcode but NOP and MASKSET reads a flag (the predicate or a source flag);
      // REF and WRITES read MASK.
      s2_rd_flag = s2_op_q != fmpp_pkg::OP_NOP && s2_op_q != fmpp_pkg::OP_MASKSET;
      s2_rd_mask = s2_op_q == fmpp_pkg::OP_REF || s2_op_q == fmpp_pkg::OP_WRITES;
    end
  end
  c_fwd_a: cover property (@(posedge clk_i) s3_wr_word && s2_rd_a && s2_a_q == s3_d_q && !(s2_rd_b && s2_b_q == s3_d_q));
  c_fwd_b: cover property (@(posedge clk_i) s3_wr_word && s2_rd_b && s2_b_q == s3_d_q && s2_a_q != s3_d_q);
  c_fwd_ab: cover property (@(posedge clk_i) s3_wr_word && s2_rd_a && s2_rd_b && s2_a_q == s3_d_q && s2_b_q == s3_d_q);
  c_fwd_from_alu: cover property (@(posedge clk_i) s3_wr_word && ex_instr && s3_op_q == fmpp_pkg::OP_ADD && s2_rd_a && s2_a_q == s3_d_q);
  c_fwd_from_writes: cover property (@(posedge clk_i) s3_wr_word && ex_instr && s3_op_q == fmpp_pkg::OP_WRITES && s2_rd_a && s2_a_q == s3_d_q);
  c_fwd_from_bitcopy: cover property (@(posedge clk_i) s3_wr_word && ex_instr && s3_op_q == fmpp_pkg::OP_BITCOPY && s2_rd_a && s2_a_q == s3_d_q);
  c_fwd_from_window: cover property (@(posedge clk_i) s3_wr_word && !ex_instr && s2_rd_a && s2_a_q == s3_d_q);
  c_fwd_none: cover property (@(posedge clk_i) s3_wr_word && s2_rd_a && s2_a_q != s3_d_q && !(s2_rd_b && s2_b_q == s3_d_q));
  c_dep_flag: cover property (@(posedge clk_i) s3_wr_flag && s2_rd_flag);
  c_dep_flags_window: cover property (@(posedge clk_i) s3_wr_flag && !ex_instr && s2_rd_flag);
  c_dep_mask: cover property (@(posedge clk_i) ex_instr && s3_op_q == fmpp_pkg::OP_MASKSET && s2_rd_mask);
  c_pipe_full: cover property (@(posedge clk_i) pop && s2_valid_q && s3_valid_q);
  c_bubble_s2: cover property (@(posedge clk_i) rst_ni && pop && !s2_valid_q && s3_valid_q);
  c_bubble_s3: cover property (@(posedge clk_i) rst_ni && s2_valid_q && !s3_valid_q);
  c_gap_in_flight: cover property (@(posedge clk_i) head_valid_i && gap_q != '0 && busy_o);
  c_drain_wait: cover property (@(posedge clk_i) rst_ni && !head_valid_i && busy_o && (rd_en_i || resp_en_i));
  c_reset_in_flight: cover property (@(posedge clk_i) !rst_ni && busy_o);
  // One line per point: Verilator 5.006 merges the iterations of a generate loop into one
  // cover point, so a loop would not tell the opcodes apart.
  c_op_nop: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_NOP);
  c_op_maskset: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_MASKSET);
  c_op_ref: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF);
  c_op_func: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_FUNC);
  c_op_add: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_ADD);
  c_op_sub: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_SUB);
  c_op_bitcopy: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_BITCOPY);
  c_op_lshift: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_LSHIFT);
  c_op_rshift: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_RSHIFT);
  c_op_writes: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_WRITES);
  c_op_sets: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_SETS);
  c_op_resets: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_RESETS);
  c_op_setsadr: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_SETSADR);
  c_op_flagop: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_FLAGOP);
  c_op_cmp: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP);
  c_op_divstep: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_DIVSTEP);
  c_ref_through_data: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_THROUGH && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_DATA);
  c_ref_through_addr: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_THROUGH && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_ADDR);
  c_ref_and_data: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_AND && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_DATA);
  c_ref_and_addr: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_AND && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_ADDR);
  c_ref_or_data: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_OR && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_DATA);
  c_ref_or_addr: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_REF && x[fmpp_pkg::REF_FN_LSB +: fmpp_pkg::REF_FN_W] == fmpp_pkg::REF_FN_OR && x[fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W] == fmpp_pkg::REF_PART_ADDR);
  c_cmp_through_ge: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_THROUGH && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_through_lt: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_THROUGH && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_cmp_and_ge: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_AND && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_and_lt: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_AND && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_cmp_or_ge: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_OR && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_or_lt: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_OR && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_flagop_any_taken: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_FLAGOP && imm[fmpp_pkg::FLAG_ANY_LSB] && g_bc[0].ans_q);
  c_flagop_any_holds: cover property (@(posedge clk_i) hold && s2_valid_q && head_valid_i);
  c_flagop_any_skipped: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_FLAGOP && imm[fmpp_pkg::FLAG_ANY_LSB] && !g_bc[0].ans_q);
  c_shr_add_max: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_ADD && &imm[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W]);
  c_shr_sub: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_SUB && |imm[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W]);
  c_shr_rshift: cover property (@(posedge clk_i) ex_instr && op == fmpp_pkg::OP_RSHIFT && |imm[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W]);
  c_shr_fwd: cover property (@(posedge clk_i) s3_wr_word && ex_instr && s2_rd_a && s2_a_q == s3_d_q && s2_op_q == fmpp_pkg::OP_ADD && |s2_imm_q[fmpp_pkg::SHR_A_LSB +: fmpp_pkg::SHR_A_W]);
  c_word_write: cover property (@(posedge clk_i) retire && s3_kind_q == fmpp_pkg::QE_WORD);
  c_flags_write: cover property (@(posedge clk_i) retire && s3_kind_q == fmpp_pkg::QE_FLAGS);
  c_gap_stall: cover property (@(posedge clk_i) head_valid_i && gap_q != '0);
`endif

  // Assertions
`ifndef SYNTHESIS
  if (NumBlocks < 1 || NumBlocks > fmpp_pkg::MaxBlocks) begin : g_bad_blocks
    $error("fmpp_array: NumBlocks = %0d outside [1, %0d]", NumBlocks, fmpp_pkg::MaxBlocks);
  end
  // The tiles' 64-lane bit-plane indexing: a block's lane is its low 6 bits, its tile the
  // bits above (compared with the tile's base_i), and the index bits 0-5 of a lane come
  // from its lane number. All of that holds only for 64 lanes per tile.
  if (fmpp_pkg::LaneW != 64) begin : g_bad_lane_width
    $error("fmpp_array: the tiles' lane indexing assumes fmpp_pkg::LaneW = 64, not %0d", fmpp_pkg::LaneW);
  end
  a_hw_block: assert property (@(posedge clk_i) disable iff (!rst_ni)
                               (pop && !is_instr) |-> 32'(head_i.block) < NumBlocks)
    else $error("fmpp_array: window write to block %0d of %0d", head_i.block, NumBlocks);
  a_hw_word: assert property (@(posedge clk_i) disable iff (!rst_ni)
                              (pop && head_i.kind == fmpp_pkg::QE_WORD) |-> 32'(head_i.word) < NumWords)
    else $error("fmpp_array: window write to word %0d of %0d", head_i.word, NumWords);
  a_kind: assert property (@(posedge clk_i) disable iff (!rst_ni)
                           pop |-> head_i.kind != 2'd3)
    else $error("fmpp_array: queue entry of unknown kind");
`endif

endmodule
