// Formal harness of the pipelined array (fmpp_array): it must behave as the
// single-cycle array it replaced (fmpp_array_sc, formal/fmpp_array_sc.sv), or, with
// IsaRef, as the instruction set itself (fmpp_isa_ref, formal/fmpp_isa_ref.sv), run two
// clocks later. Both start from the same state (every register and word 0, then reset); the queue head, its validity,
// CTRL.GAP, the reset and the host's read and responder requests are free inputs, each
// queue entry constrained to what the slave lets into the queue (a legal instruction
// by fmpp_instr_check, a window write inside the machine). Every entry the pipelined
// array pops goes, two clocks later (the pipeline's latency), to the reference, which executes it at once; so
// after every clock edge the two hold the same architectural state, and this harness
// checks everything the host can see of it: the read port for any address the solver
// picks (so any differing word or flag is seen at the step it first differs), the
// responders, MASK and INSTRET, and that busy_o says exactly when entries are in flight.
// Run by tools/formal.sh: a bounded model check from reset with yosys's own SAT solver
// (its depth is in docs/verification.md).
module fmpp_pipe_formal #(
  parameter int unsigned NumBlocks = 2,
  parameter int unsigned NumWords  = 4,
  parameter bit          IsaRef    = 0   // 1: the reference is the ISA (fmpp_isa_ref.sv)
) (
  input logic                 clk_i,
  input logic                 rst_ni,
  input fmpp_pkg::qentry_t    head_i,
  input logic                 head_valid_i,
  input logic [7:0]           gap_i,
  input logic                 rd_en_i,
  input fmpp_pkg::rkind_e     rd_kind_i,
  input logic [15:0]          rd_block_i,
  input logic [5:0]           rd_word_i,
  input logic [2:0]           rd_flag_i,
  input logic                 resp_en_i
);
  // The pipelined array under test.
  logic        pop, busy, any, ovf;
  logic [63:0] rd_data, instret;
  logic [31:0] count, mask, rd_late;
  logic [30:0] first;
  fmpp_array #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_dut (
    .clk_i, .rst_ni, .head_i, .head_valid_i, .pop_o (pop), .gap_i, .busy_o (busy),
    .rd_en_i, .rd_kind_i, .rd_block_i, .rd_word_i, .rd_flag_i, .rd_data_o (rd_data),
    .rd_acc_i (1'b1), .rd_late_o (rd_late),  // every clock accepts (a read may meet a write: the RAM reads the old word)
    .resp_en_i, .resp_any_o (any), .resp_count_o (count), .resp_first_o (first), .ovf_any_o (ovf),
    .mask_o (mask), .instret_o (instret)
  );

  // The entries it popped, delayed by the pipeline's latency (dropped by a reset, as the
  // pipeline drops them), feed the reference. The timing contract is written here again: a
  // FLAGOP with FLAG_ANY in stage 3 holds both stages AnyLatency clocks before it executes.
  // (Two named registers per stage: yosys reads no struct members of array elements.)
  logic              f_valid2_q, f_valid3_q;  // an entry in stage 2, in stage 3
  fmpp_pkg::qentry_t f_entry2_q, f_entry3_q;
  logic [7:0]        f_hold_q;                // clocks the entry in stage 3 has held
  logic              f_hold;
  assign f_hold = f_valid3_q && f_entry3_q.kind == fmpp_pkg::QE_INSTR &&
                  f_entry3_q.data[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W] == fmpp_pkg::OP_FLAGOP &&
                  f_entry3_q.data[fmpp_pkg::F_IMM_LSB + fmpp_pkg::FLAG_ANY_LSB] &&
                  32'(f_hold_q) != fmpp_pkg::AnyLatency;
  always_ff @(posedge clk_i) begin
    if (rst_ni && f_hold) begin
      f_hold_q <= f_hold_q + 8'd1;
    end else begin
      f_valid2_q <= rst_ni && pop;
      f_entry2_q <= head_i;
      f_valid3_q <= rst_ni && f_valid2_q;
      f_entry3_q <= f_entry2_q;
      f_hold_q   <= 8'd0;
    end
  end
  // The responders answer for the flags they have seen RespLatency clocks in a row, asked
  // for (resp_en_i) and with nothing in flight: that is when the bus slave reads them.
  logic [7:0] f_resp_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni || !resp_en_i || busy || pop) f_resp_q <= 8'd0;
    else if (32'(f_resp_q) != fmpp_pkg::RespLatency) f_resp_q <= f_resp_q + 8'd1;
  end

  logic        ref_pop, ref_any, ref_ovf;
  logic [63:0] ref_rd_data, ref_instret;
  logic [31:0] ref_count, ref_mask;
  logic [30:0] ref_first;
  if (IsaRef) begin : g_isa
    fmpp_isa_ref #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_ref (
      .clk_i, .rst_ni, .head_i (f_entry3_q), .head_valid_i (f_valid3_q && !f_hold),
      .pop_o (ref_pop), .gap_i (8'd0),
      .rd_en_i, .rd_kind_i, .rd_block_i, .rd_word_i, .rd_flag_i, .rd_data_o (ref_rd_data),
      .resp_en_i, .resp_any_o (ref_any), .resp_count_o (ref_count), .resp_first_o (ref_first),
      .ovf_any_o (ref_ovf), .mask_o (ref_mask), .instret_o (ref_instret)
    );
  end else begin : g_sc
    fmpp_array_sc #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_ref (
      .clk_i, .rst_ni, .head_i (f_entry3_q), .head_valid_i (f_valid3_q && !f_hold),
      .pop_o (ref_pop), .gap_i (8'd0),
      .rd_en_i, .rd_kind_i, .rd_block_i, .rd_word_i, .rd_flag_i, .rd_data_o (ref_rd_data),
      .resp_en_i, .resp_any_o (ref_any), .resp_count_o (ref_count), .resp_first_o (ref_first),
      .ovf_any_o (ref_ovf), .mask_o (ref_mask), .instret_o (ref_instret)
    );
  end

  // What the slave lets into the queue.
  logic legal;
  fmpp_instr_check #(.NumWords(NumWords)) u_check (.instr_i (head_i.data), .legal_o (legal));
  // The words an entry uses, as the slave queues them (fmpp_entry_use).
  logic use_a, use_b, use_d;
  fmpp_entry_use u_use (.is_instr_i (head_i.kind == fmpp_pkg::QE_INSTR), .is_word_i (head_i.kind == fmpp_pkg::QE_WORD),
                        .op_i (head_i.data[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W]),
                        .ref_part_i (head_i.data[fmpp_pkg::F_X_LSB + fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W]),
                        .rd_a_o (use_a), .rd_b_o (use_b), .wr_d_o (use_d));

  logic f_init = 1'b1;
  always_ff @(posedge clk_i) f_init <= 1'b0;
  always @(*) begin
    // The run starts in reset.
    if (f_init) assume (!rst_ni);
    if (head_valid_i) begin
      assume (head_i.kind != 2'd3);
      if (head_i.kind == fmpp_pkg::QE_INSTR) assume (legal);
      assume ({head_i.rd_a, head_i.rd_b, head_i.wr_d} == {use_a, use_b, use_d});
      if (head_i.kind != fmpp_pkg::QE_INSTR) assume (32'(head_i.block) < NumBlocks);
      if (head_i.kind == fmpp_pkg::QE_WORD) assume (32'(head_i.word) < NumWords && head_i.strb != 4'd0);
    end
    // Host reads address the machine (the slave's decoder sees to it).
    if (rd_en_i && rd_kind_i != fmpp_pkg::RK_PLANE) assume (32'(rd_block_i) < NumBlocks);
    if (rd_en_i && rd_kind_i == fmpp_pkg::RK_PLANE) assume (32'(rd_block_i) * fmpp_pkg::LaneW < NumBlocks);
    if (rd_en_i && rd_kind_i == fmpp_pkg::RK_WORD) assume (32'(rd_word_i) < NumWords);
    assume (rd_kind_i != 2'd3);
  end

  // A word read and what the reference answered, a clock ago (FMPP_BRAM_WORDS_HOST).
  logic        f_word_q;
  logic [63:0] f_ref_word_q;
  always_ff @(posedge clk_i) begin
    f_word_q     <= rst_ni && rd_en_i && rd_kind_i == fmpp_pkg::RK_WORD;
    f_ref_word_q <= ref_rd_data;
  end

  always @(*) begin
    if (!f_init && rst_ni) begin
      // p_read_equal: every word, flag and flag plane reads the same in both.
`ifdef FMPP_BRAM_WORDS_HOST
      // A word read answers a clock later (rd_late): what the reference read then.
      p_read_equal: assert (rd_data == ((rd_en_i && rd_kind_i == fmpp_pkg::RK_WORD) ? 64'd0 : ref_rd_data));
      p_late_equal: assert ({32'd0, rd_late} == (f_word_q ? f_ref_word_q : 64'd0));
`else
      p_read_equal: assert (rd_data == ref_rd_data);
      p_late_zero: assert (rd_late == '0);
`endif
      // p_resp_equal: the responders and the overflow summary agree when the slave would read them.
      if (32'(f_resp_q) == fmpp_pkg::RespLatency)
        p_resp_equal: assert (any == ref_any && count == ref_count && first == ref_first && ovf == ref_ovf);
      // p_regs_equal: MASK and INSTRET agree.
      p_regs_equal: assert (mask == ref_mask && instret == ref_instret);
      // p_busy: busy_o is high exactly while popped entries have not retired.
      p_busy: assert (busy == (f_valid2_q || f_valid3_q));
    end
  end

  // Non-vacuity: the dependencies the forwarding serves occur back to back (the entry
  // in stage 3 writes the word the next one reads as A, or as B), and three entries are
  // in flight at once. (yosys sat, which runs this harness, has no cover(): built with
  // SAT_COVER each point is an assertion of its negation, and its counterexample is the
  // witness that reaches it.)
  logic [fmpp_pkg::F_OP_W-1:0] f_op2, f_op3;
  logic f_cov_fwd_a, f_cov_fwd_b, f_cov_full;
  assign f_op3 = f_entry3_q.data[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W];
  assign f_op2 = f_entry2_q.data[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W];
  assign f_cov_fwd_a = f_valid3_q && f_valid2_q && f_entry3_q.kind == fmpp_pkg::QE_INSTR &&
                       f_entry2_q.kind == fmpp_pkg::QE_INSTR && f_op3 == fmpp_pkg::OP_ADD && f_op2 == fmpp_pkg::OP_ADD &&
                       f_entry3_q.data[fmpp_pkg::F_D_LSB +: fmpp_pkg::F_D_W] ==
                       f_entry2_q.data[fmpp_pkg::F_A_LSB +: fmpp_pkg::F_A_W];
  assign f_cov_fwd_b = f_valid3_q && f_valid2_q && f_entry3_q.kind == fmpp_pkg::QE_WORD &&
                       f_entry2_q.kind == fmpp_pkg::QE_INSTR && f_op2 == fmpp_pkg::OP_SUB &&
                       6'(f_entry3_q.word) == f_entry2_q.data[fmpp_pkg::F_B_LSB +: fmpp_pkg::F_B_W];
  assign f_cov_full  = pop && f_valid2_q && f_valid3_q;
  always @(*) begin
    if (rst_ni) begin
`ifdef SAT_COVER
      c_fwd_a: assert (!f_cov_fwd_a);
      c_fwd_b: assert (!f_cov_fwd_b);
      c_full: assert (!f_cov_full);
`else
      c_fwd_a: cover (f_cov_fwd_a);
      c_fwd_b: cover (f_cov_fwd_b);
      c_full: cover (f_cov_full);
`endif
    end
  end
endmodule
