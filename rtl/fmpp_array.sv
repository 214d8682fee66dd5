// fmpp_array: the FMPP processor array and its sequencer.
//
// Holds NumBlocks blocks in ceil(NumBlocks / 64) tiles (fmpp_tile), the mask
// register and the INSTRET counter. Each clock it may pop the head of the
// instruction queue and execute it in every tile at once (one entry per clock,
// then CTRL.GAP idle clocks). It combines the tiles' responders (ANY, COUNT,
// FIRST over SEL), the FLAGOP "if any" condition and the host read port.
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
  input  logic [7:0]           gap_i,        // CTRL.GAP

  // Host read port (combinational; reads are only accepted while the queue is empty)
  input  logic                 rd_en_i,
  input  fmpp_pkg::rkind_e     rd_kind_i,
  input  logic [15:0]          rd_block_i,   // block (WORD, FLAGS) or tile (PLANE)
  input  logic [5:0]           rd_word_i,
  input  logic [2:0]           rd_flag_i,
  output logic [63:0]          rd_data_o,

  // Responders and summaries (combinational, evaluated when resp_en_i)
  input  logic                 resp_en_i,
  output logic                 resp_any_o,
  output logic [31:0]          resp_count_o,
  output logic [30:0]          resp_first_o,
  output logic                 ovf_any_o,

  output logic [31:0]          mask_o,
  output logic [63:0]          instret_o
);
  localparam int unsigned LaneW    = fmpp_pkg::LaneW;
  localparam int unsigned NumTiles = (NumBlocks + LaneW - 1) / LaneW;
  localparam int unsigned LastLanes = NumBlocks - (NumTiles - 1) * LaneW;

  // Sequencer: pop one entry per clock, then idle for CTRL.GAP clocks.
  logic [7:0]  gap_q;
  // Public for the lockstep checker (tb/), which reads the state directly.
  logic [31:0] mask_q /*verilator public_flat_rd*/;
  logic [63:0] instret_q /*verilator public_flat_rd*/;
  logic        pop /*verilator public_flat_rd*/;
  logic        is_instr;
  logic [63:0] instr;

  // No entry executes while rst_ni is low: the queue's level resets at the same edge,
  // and an entry executed then would write a word (words have no reset) that the reset
  // was meant to drop (found by the soak's resets in the middle of programs).
  assign pop      = rst_ni && head_valid_i && gap_q == '0;
  assign pop_o    = pop;
  assign is_instr = head_i.kind == fmpp_pkg::QE_INSTR;
  assign instr    = head_i.data;

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
      if (pop && is_instr) begin
        instret_q <= instret_q + 1'b1;
        if (instr[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W] == fmpp_pkg::OP_MASKSET) begin
          mask_q <= instr[fmpp_pkg::F_IMM_LSB +: fmpp_pkg::F_IMM_W];
        end
      end
    end
  end

  assign mask_o    = mask_q;
  assign instret_o = instret_q;

  // Decoded execute bus, shared by every tile. Window writes reuse D for the word.
  logic [fmpp_pkg::F_OP_W-1:0]  op;
  logic [fmpp_pkg::F_F_W-1:0]   f;
  logic [fmpp_pkg::F_D_W-1:0]   d;
  logic [fmpp_pkg::F_A_W-1:0]   a;
  logic [fmpp_pkg::F_B_W-1:0]   b;
  logic [fmpp_pkg::F_X_W-1:0]   x;
  logic [fmpp_pkg::F_IMM_W-1:0] imm;

  assign op  = is_instr ? instr[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W] : fmpp_pkg::OP_NOP;
  assign f   = instr[fmpp_pkg::F_F_LSB +: fmpp_pkg::F_F_W];
  assign d   = is_instr ? instr[fmpp_pkg::F_D_LSB +: fmpp_pkg::F_D_W] : head_i.word;
  assign a   = instr[fmpp_pkg::F_A_LSB +: fmpp_pkg::F_A_W];
  assign b   = instr[fmpp_pkg::F_B_LSB +: fmpp_pkg::F_B_W];
  assign x   = instr[fmpp_pkg::F_X_LSB +: fmpp_pkg::F_X_W];
  assign imm = instr[fmpp_pkg::F_IMM_LSB +: fmpp_pkg::F_IMM_W];

  // Tiles
  logic        t_flagop_any [NumTiles];
  logic        t_sel_any    [NumTiles];
  logic [31:0] t_sel_count  [NumTiles];
  logic [5:0]  t_sel_first  [NumTiles];
  logic        t_ovf_any    [NumTiles];
  logic [63:0] t_rd_data    [NumTiles];
  logic        flagop_any;

  for (genvar t = 0; t < NumTiles; t++) begin : g_tile
    localparam int unsigned Lanes = (t == NumTiles - 1) ? LastLanes : LaneW;
    fmpp_tile #(.Lanes(Lanes), .NumWords(NumWords)) u_tile (
      .clk_i,
      .rst_ni,
      .base_i       (t * LaneW),
      .exec_i       (pop),
      .kind_i       (head_i.kind),
      .op_i         (op),
      .f_i          (f),
      .d_i          (d),
      .a_i          (a),
      .b_i          (b),
      .x_i          (x),
      .imm_i        (imm),
      .mask_i       (mask_q),
      .hw_block_i   (head_i.block),
      .hw_strb_i    (head_i.strb),
      .hw_data_i    (head_i.data[31:0]),
      .flagop_any_i (flagop_any),
      .flagop_any_o (t_flagop_any[t]),
      .rd_en_i      (rd_en_i),
      .rd_kind_i    (rd_kind_i),
      .rd_block_i   (rd_block_i),
      .rd_word_i    (rd_word_i),
      .rd_flag_i    (rd_flag_i),
      .rd_data_o    (t_rd_data[t]),
      .resp_en_i    (resp_en_i),
      .sel_any_o    (t_sel_any[t]),
      .sel_count_o  (t_sel_count[t]),
      .sel_first_o  (t_sel_first[t]),
      .ovf_any_o    (t_ovf_any[t])
    );
  end

  always_comb begin
    flagop_any = 1'b0;
    for (int t = 0; t < NumTiles; t++) flagop_any = flagop_any | t_flagop_any[t];
  end

  // Read data: only the addressed tile drives a non-zero value.
  always_comb begin
    rd_data_o = '0;
    for (int t = 0; t < NumTiles; t++) rd_data_o = rd_data_o | t_rd_data[t];
  end

  // Responders: FIRST is the lowest selected block, so scan tiles from the top down.
  always_comb begin
    resp_any_o   = 1'b0;
    resp_count_o = '0;
    resp_first_o = '0;
    ovf_any_o    = 1'b0;
    if (resp_en_i) begin
      for (int t = NumTiles - 1; t >= 0; t--) begin
        resp_count_o = resp_count_o + t_sel_count[t];
        ovf_any_o    = ovf_any_o | t_ovf_any[t];
        if (t_sel_any[t]) begin
          resp_any_o   = 1'b1;
          resp_first_o = 31'(t * LaneW) | {25'd0, t_sel_first[t]};
        end
      end
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
  // on the address part, every CMP function with >= and <, FLAGOP "if any" taken and not taken, the sequencer stalled by GAP.
`ifdef FMPP_COVERAGE
  // One line per point: Verilator 5.006 merges the iterations of a generate loop into one
  // cover point, so a loop would not tell the opcodes apart.
  c_op_nop: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_NOP);
  c_op_maskset: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_MASKSET);
  c_op_ref: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF);
  c_op_func: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_FUNC);
  c_op_add: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_ADD);
  c_op_sub: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_SUB);
  c_op_bitcopy: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_BITCOPY);
  c_op_lshift: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_LSHIFT);
  c_op_rshift: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_RSHIFT);
  c_op_writes: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_WRITES);
  c_op_sets: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_SETS);
  c_op_resets: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_RESETS);
  c_op_setsadr: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_SETSADR);
  c_op_flagop: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_FLAGOP);
  c_op_cmp: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP);
  c_ref_through_data: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd0 && x[2] == 1'b0);
  c_ref_through_addr: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd0 && x[2] == 1'b1);
  c_ref_and_data: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd1 && x[2] == 1'b0);
  c_ref_and_addr: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd1 && x[2] == 1'b1);
  c_ref_or_data: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd2 && x[2] == 1'b0);
  c_ref_or_addr: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_REF && x[1:0] == 2'd2 && x[2] == 1'b1);
  c_cmp_through_ge: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_THROUGH && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_through_lt: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_THROUGH && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_cmp_and_ge: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_AND && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_and_lt: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_AND && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_cmp_or_ge: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_OR && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_GE);
  c_cmp_or_lt: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_CMP && x[fmpp_pkg::CMP_FN_LSB +: fmpp_pkg::CMP_FN_W] == fmpp_pkg::CMP_FN_OR && x[fmpp_pkg::CMP_LT_LSB +: fmpp_pkg::CMP_LT_W] == fmpp_pkg::CMP_LT_LT);
  c_flagop_any_taken: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_FLAGOP && imm[8] && flagop_any);
  c_flagop_any_skipped: cover property (@(posedge clk_i) pop && is_instr && op == fmpp_pkg::OP_FLAGOP && imm[8] && !flagop_any);
  c_word_write: cover property (@(posedge clk_i) pop && head_i.kind == fmpp_pkg::QE_WORD);
  c_flags_write: cover property (@(posedge clk_i) pop && head_i.kind == fmpp_pkg::QE_FLAGS);
  c_gap_stall: cover property (@(posedge clk_i) head_valid_i && gap_q != '0);
`endif

  // Assertions
`ifndef SYNTHESIS
  if (NumBlocks < 1 || NumBlocks > fmpp_pkg::MaxBlocks) begin : g_bad_blocks
    $error("fmpp_array: NumBlocks = %0d outside [1, %0d]", NumBlocks, fmpp_pkg::MaxBlocks);
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
