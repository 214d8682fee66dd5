// fmpp_axil_slave: the FMPP's only port, an AXI4-Lite slave (64-bit data).
//
// Writes to QUEUE and to the WORDS/FLAGS windows are pushes: they are accepted when
// the queue has room, checked here and, if legal, queued for the array in bus order. Every other access
// (all reads, CTRL and ERROR writes) waits until the queue is empty and the array's
// pipeline has drained (q_empty_i), so reads see every earlier push. A bad access
// answers SLVERR, has no other effect, and is recorded in the sticky ERROR register
// one clock later; a read waits for that clock. Rules and timing: docs/generated/memory-map.md.
//
// A write is accepted when AWVALID and WVALID are both high (AWREADY = WREADY),
// a read when ARVALID is high; the response follows one clock later. With
// BREADY/RREADY held high one access per clock is sustained.
module fmpp_axil_slave #(
  parameter int unsigned NumBlocks = 64,
  parameter int unsigned NumWords  = 32
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,

  // AXI4-Lite
  input  logic                         awvalid_i,
  output logic                         awready_o,
  input  logic [fmpp_pkg::AddrW-1:0]   awaddr_i,
  input  logic [2:0]                   awprot_i,
  input  logic                         wvalid_i,
  output logic                         wready_o,
  input  logic [63:0]                  wdata_i,
  input  logic [7:0]                   wstrb_i,
  output logic                         bvalid_o,
  input  logic                         bready_i,
  output logic [1:0]                   bresp_o,
  input  logic                         arvalid_i,
  output logic                         arready_o,
  input  logic [fmpp_pkg::AddrW-1:0]   araddr_i,
  input  logic [2:0]                   arprot_i,
  output logic                         rvalid_o,
  input  logic                         rready_i,
  output logic [63:0]                  rdata_o,
  output logic [1:0]                   rresp_o,

  // Instruction queue
  output logic                         push_o,
  output fmpp_pkg::qentry_t            push_entry_o,
  input  logic                         q_full_i,
  input  logic                         q_empty_i,   // queue empty and every entry executed

  // Array read port, responders and state shown in registers
  output logic                         rd_en_o,
  output fmpp_pkg::rkind_e             rd_kind_o,
  output logic [fmpp_pkg::BlockIdxW-1:0] rd_block_o,
  output logic [fmpp_pkg::WordIdxW-1:0]  rd_word_o,
  output logic [fmpp_pkg::FlagIdxW-1:0]  rd_flag_o,
  input  logic [63:0]                  rd_data_i,
  input  logic [31:0]                  rd_late_i,   // a word read's data from the clock after its accept (else 0)
  output logic                         resp_en_o,
  input  logic                         resp_any_i,
  input  logic [fmpp_pkg::REG_RESP_COUNT_W-1:0] resp_count_i,
  input  logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] resp_first_i,
  input  logic                         ovf_any_i,
  input  logic [fmpp_pkg::REG_MASK_VALUE_W-1:0] mask_i,
  input  logic [fmpp_pkg::REG_INSTRET_VALUE_W-1:0] instret_i,
  output logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap_o
);
  localparam logic [1:0] RespOkay   = 2'b00;
  localparam logic [1:0] RespSlvErr = 2'b10;

  // ---------------------------------------------------------------- write decode
  logic        aw_aligned, aw_is_reg, aw_is_plane, aw_is_flags, aw_is_word, aw_in_plane, aw_in_flags;
  logic [11:0] aw_reg;
  logic [fmpp_pkg::BlockIdxW-1:0] aw_block;
  logic [fmpp_pkg::WordIdxW-1:0]  aw_word;
  logic [fmpp_pkg::FlagIdxW-1:0]  aw_flag;
  logic        instr_legal;

  fmpp_addr_decode #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_aw_decode (
    .addr_i     (awaddr_i),
    .aligned_o  (aw_aligned),
    .is_reg_o   (aw_is_reg),
    .reg_o      (aw_reg),
    .is_plane_o (aw_is_plane),
    .is_flags_o (aw_is_flags),
    .is_word_o  (aw_is_word),
    .block_o    (aw_block),
    .word_o     (aw_word),
    .flag_o     (aw_flag),
    .in_plane_o (aw_in_plane),
    .in_flags_o (aw_in_flags)
  );

  fmpp_instr_check #(.NumWords(NumWords)) u_instr_check (
    .instr_i (wdata_i),
    .legal_o (instr_legal)
  );

  fmpp_pkg::err_e w_cause;
  logic           w_target, w_push, w_ctrl, w_err_write, w_err_clear;
  fmpp_pkg::qentry_t w_entry;
  // The written value seen through the layouts of the writable registers.
  fmpp_pkg::ctrl_reg_t  w_ctrl_v;
  fmpp_pkg::error_reg_t w_error_v;
  assign w_ctrl_v  = wdata_i;
  assign w_error_v = wdata_i;

  // Which words a pushed entry uses (fmpp_array's operand isolation), queued with it. A
  // write that is not pushed carries any.
  logic w_rd_a, w_rd_b, w_wr_d;
  fmpp_entry_use u_use (
    .is_instr_i (!aw_is_word && !aw_is_flags), .is_word_i (aw_is_word),
    .op_i (wdata_i[fmpp_pkg::F_OP_LSB +: fmpp_pkg::F_OP_W]),
    .ref_part_i (wdata_i[fmpp_pkg::F_X_LSB + fmpp_pkg::REF_PART_LSB +: fmpp_pkg::REF_PART_W]),
    .rd_a_o (w_rd_a), .rd_b_o (w_rd_b), .wr_d_o (w_wr_d)
  );

  // The write's error cause, by the documented priority (alignment, then the target,
  // then strobes, then the instruction). Only recorded (ERROR, one clock later): what the
  // accept and the push need is computed flat below, off this chain.
  always_comb begin
    w_cause     = fmpp_pkg::ERR_NONE;
    w_entry.kind  = fmpp_pkg::QE_INSTR;
    w_entry.block = aw_block;
    w_entry.word  = aw_word;
    w_entry.strb  = wstrb_i[3:0];
    {w_entry.rd_a, w_entry.rd_b, w_entry.wr_d} = {w_rd_a, w_rd_b, w_wr_d};
    w_entry.data  = wdata_i;
    if (!aw_aligned) begin
      w_cause = fmpp_pkg::ERR_ALIGN;
    end else if (aw_is_reg) begin
      unique case (aw_reg)
        fmpp_pkg::REG_QUEUE[11:0]: begin
          if (wstrb_i != 8'hFF)  w_cause = fmpp_pkg::ERR_STROBE;
          else if (!instr_legal) w_cause = fmpp_pkg::ERR_ILLEGAL;
        end
        fmpp_pkg::REG_CTRL[11:0]: begin
          if (wstrb_i != 8'hFF) w_cause = fmpp_pkg::ERR_STROBE;
        end
        fmpp_pkg::REG_ERROR[11:0]: begin
          if (wstrb_i != 8'hFF) w_cause = fmpp_pkg::ERR_STROBE;
        end
        fmpp_pkg::REG_ID[11:0], fmpp_pkg::REG_CONFIG[11:0], fmpp_pkg::REG_STATUS[11:0],
        fmpp_pkg::REG_RESP[11:0], fmpp_pkg::REG_CYCLES[11:0], fmpp_pkg::REG_INSTRET[11:0],
        fmpp_pkg::REG_MASK[11:0]:
          w_cause = fmpp_pkg::ERR_READONLY;
        default:
          w_cause = fmpp_pkg::ERR_UNMAPPED;
      endcase
    end else if (aw_is_plane) begin
      w_cause = fmpp_pkg::ERR_READONLY;
    end else if (aw_is_flags) begin
      w_entry.kind = fmpp_pkg::QE_FLAGS;
      if (wstrb_i != 8'h01) w_cause = fmpp_pkg::ERR_STROBE;
    end else if (aw_is_word) begin
      w_entry.kind = fmpp_pkg::QE_WORD;
      if (wstrb_i[7:4] != 4'h0 || wstrb_i[3:0] == 4'h0) w_cause = fmpp_pkg::ERR_STROBE;
    end else begin
      w_cause = fmpp_pkg::ERR_UNMAPPED;
    end
  end

  // The write's decisions as flat logic: a queued target (QUEUE, FLAGS, WORDS) takes
  // room in the queue whether legal or not, and is pushed if legal; CTRL and ERROR take
  // all eight strobes. Anything else is an error (w_cause says which).
  logic w_at_queue, w_at_ctrl, w_at_error, w_strb_all, w_strb_flags, w_strb_word, w_ok;
  assign w_at_queue   = aw_aligned && aw_is_reg && aw_reg == fmpp_pkg::REG_QUEUE[11:0];
  assign w_at_ctrl    = aw_aligned && aw_is_reg && aw_reg == fmpp_pkg::REG_CTRL[11:0];
  assign w_at_error   = aw_aligned && aw_is_reg && aw_reg == fmpp_pkg::REG_ERROR[11:0];
  assign w_strb_all   = wstrb_i == 8'hFF;
  assign w_strb_flags = wstrb_i == 8'h01;
  assign w_strb_word  = wstrb_i[7:4] == 4'h0 && wstrb_i[3:0] != 4'h0;
  assign w_target     = w_at_queue || (aw_aligned && (aw_is_flags || aw_is_word));
  assign w_push       = (w_at_queue && w_strb_all && instr_legal) || (aw_aligned && aw_is_flags && w_strb_flags) ||
                        (aw_aligned && aw_is_word && w_strb_word);
  assign w_ctrl       = w_at_ctrl && w_strb_all;
  assign w_err_write  = w_at_error;
  assign w_err_clear  = w_at_error && w_strb_all && w_error_v.sticky;
  assign w_ok         = w_push || w_ctrl || (w_at_error && w_strb_all);

  // ----------------------------------------------------------------- read decode
  logic        ar_aligned, ar_is_reg, ar_is_plane, ar_is_flags, ar_is_word, ar_in_plane, ar_in_flags;
  logic [11:0] ar_reg;
  logic [fmpp_pkg::BlockIdxW-1:0] ar_block;
  logic [fmpp_pkg::WordIdxW-1:0]  ar_word;
  logic [fmpp_pkg::FlagIdxW-1:0]  ar_flag;

  fmpp_addr_decode #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_ar_decode (
    .addr_i     (araddr_i),
    .aligned_o  (ar_aligned),
    .is_reg_o   (ar_is_reg),
    .reg_o      (ar_reg),
    .is_plane_o (ar_is_plane),
    .is_flags_o (ar_is_flags),
    .is_word_o  (ar_is_word),
    .block_o    (ar_block),
    .word_o     (ar_word),
    .flag_o     (ar_flag),
    .in_plane_o (ar_in_plane),
    .in_flags_o (ar_in_flags)
  );

  // The ERROR register (fmpp_err_reg) and CTRL.GAP. gap_q is public for the lockstep
  // checker (tb/), which reads the state directly.
  logic           err_pend, err_sticky;
  fmpp_pkg::err_e err_cause;
  logic [fmpp_pkg::REG_ERROR_COUNT_W-1:0] err_count;
  logic [fmpp_pkg::AddrW-1:0] err_addr;
  logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap_q /*verilator public_flat_rd*/;
  logic [63:0]    cycles_q, cycles_inc;

  fmpp_pkg::err_e r_cause;
  logic [63:0]    r_data;

  // What the read returns (the registers by the map's layouts, or the read port).
  fmpp_reg_read #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_reg_read (
    .aligned_i    (ar_aligned),
    .is_reg_i     (ar_is_reg),
    .reg_i        (ar_reg),
    .is_window_i  (ar_is_plane || ar_is_flags || ar_is_word),
    .rd_data_i,
    .resp_any_i,
    .resp_count_i,
    .resp_first_i,
    .ovf_any_i,
    .err_sticky_i (err_sticky),
    .err_cause_i  (err_cause),
    .err_count_i  (err_count),
    .err_addr_i   (err_addr),
    .gap_i        (gap_q),
    .cycles_i     (cycles_q),
    .instret_i,
    .mask_i,
    .cause_o      (r_cause),
    .data_o       (r_data)
  );

  assign rd_en_o    = arvalid_i && ar_aligned && (ar_is_plane || ar_is_flags || ar_is_word);
  // The kind by the window alone (rd_en_o tells whether it is mapped): the tiles start their
  // read before the range checks end.
  assign rd_kind_o  = ar_in_plane ? fmpp_pkg::RK_PLANE : (ar_in_flags ? fmpp_pkg::RK_FLAGS : fmpp_pkg::RK_WORD);
  assign rd_block_o = ar_block;
  assign rd_word_o  = ar_word;
  assign rd_flag_o  = ar_flag;
  assign resp_en_o  = arvalid_i && ar_is_reg &&
                      (ar_reg == fmpp_pkg::REG_RESP[11:0] || ar_reg == fmpp_pkg::REG_STATUS[11:0]);

  // ------------------------------------------------------------------ handshakes
  logic bvalid_q, rvalid_q;
  logic [1:0] bresp_q, rresp_q;
  logic [63:0] rdata_q;
  logic w_err, r_err, w_accept, r_accept;

  assign w_err = !w_ok;
  assign r_err = r_cause != fmpp_pkg::ERR_NONE;
  // A write to a queued target (QUEUE, FLAGS, WORDS) needs room in the queue, legal or
  // not: the address alone decides, and the checks of the data and strobes (the
  // instruction's legality, several LUT levels) stay off the accept. Every other access
  // waits for the queue to drain.
  assign w_accept = awvalid_i && wvalid_i && (!bvalid_q || bready_i) && (w_target ? !q_full_i : q_empty_i);
  // A read also waits while an error event is pending (fmpp_err_reg), and a RESP or STATUS
  // read (resp_en_o) for RespLatency more clocks, ready all the while, so that the responder
  // tree's registers (tile, group, top) take the drained machine's flags.
  localparam int unsigned RespLat = fmpp_pkg::RespLatency;
  logic r_ready, r_wait_done;
  logic [$clog2(RespLat + 1)-1:0] resp_wait_q;
  assign r_ready     = arvalid_i && (!rvalid_q || rready_i) && q_empty_i && !err_pend;
  assign r_wait_done = !resp_en_o || 32'(resp_wait_q) == RespLat;
  assign r_accept    = r_ready && r_wait_done;
  always_ff @(posedge clk_i) begin
    if (!rst_ni || !r_ready || r_accept) resp_wait_q <= '0;
    else resp_wait_q <= resp_wait_q + 1'b1;
  end

  assign awready_o    = w_accept;
  assign wready_o     = w_accept;
  assign arready_o    = r_accept;
  assign bvalid_o     = bvalid_q;
  assign bresp_o      = bresp_q;
  assign rvalid_o     = rvalid_q;
  assign rresp_o      = rresp_q;
  // A word read in the FPGA's block RAM (FMPP_BRAM_WORDS_HOST) reads 0 at the accept (the
  // tiles leave it to rd_late_i) and its data joins here, from the RAM's output, which holds
  // until the next accept: the same beat, the same data while it waits.
  assign rdata_o      = rdata_q | {32'd0, rd_late_i};
  assign push_o       = w_accept && w_push;
  assign push_entry_o = w_entry;
  assign gap_o        = gap_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      bvalid_q <= 1'b0;
      bresp_q  <= RespOkay;
      rvalid_q <= 1'b0;
      rresp_q  <= RespOkay;
      rdata_q  <= '0;
    end else begin
      if (w_accept) begin
        bvalid_q <= 1'b1;
        bresp_q  <= w_err ? RespSlvErr : RespOkay;
      end else if (bready_i) begin
        bvalid_q <= 1'b0;
      end
      if (r_accept) begin
        rvalid_q <= 1'b1;
        rresp_q  <= r_err ? RespSlvErr : RespOkay;
        rdata_q  <= r_data;  // 0 for a read with an error (no branch of r_data's decode sets it)
      end else if (rready_i) begin
        rvalid_q <= 1'b0;
      end
    end
  end

  fmpp_err_reg u_err (
    .clk_i,
    .rst_ni,
    .w_err_i   (w_accept && w_err),
    .w_cause_i (w_cause),
    .w_addr_i  (awaddr_i),
    .w_touch_i (w_accept && w_err_write),
    .w_clear_i (w_accept && w_err_clear),
    .r_err_i   (r_accept && r_err),
    .r_cause_i (r_cause),
    .r_addr_i  (araddr_i),
    .pend_o    (err_pend),
    .sticky_o  (err_sticky),
    .cause_o   (err_cause),
    .count_o   (err_count),
    .addr_o    (err_addr)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      gap_q    <= '0;
      cycles_q <= '0;
    end else begin
      cycles_q <= cycles_inc;
      if (w_accept && w_ctrl) gap_q <= w_ctrl_v.gap;
    end
  end

  fmpp_incr #(.W(64)) u_cycles_inc (.q_i(cycles_q), .inc_o(cycles_inc));

  // Coverage (make coverage): every error cause of a write and of a read, every
  // responder read (RESP and STATUS, with and without a selected block), response
  // back-pressure, and a push into a queue with one free entry.
`ifdef FMPP_COVERAGE
  // (One line per point: Verilator merges the iterations of a generate loop. WRITEONLY
  // is a read's cause only; READONLY, ILLEGAL and STROBE a write's only.)
  c_w_err_unmapped: cover property (@(posedge clk_i) rst_ni && w_accept && w_cause == fmpp_pkg::ERR_UNMAPPED);
  c_w_err_readonly: cover property (@(posedge clk_i) rst_ni && w_accept && w_cause == fmpp_pkg::ERR_READONLY);
  c_w_err_illegal: cover property (@(posedge clk_i) rst_ni && w_accept && w_cause == fmpp_pkg::ERR_ILLEGAL);
  c_w_err_strobe: cover property (@(posedge clk_i) rst_ni && w_accept && w_cause == fmpp_pkg::ERR_STROBE);
  c_w_err_align: cover property (@(posedge clk_i) rst_ni && w_accept && w_cause == fmpp_pkg::ERR_ALIGN);
  c_r_err_unmapped: cover property (@(posedge clk_i) rst_ni && r_accept && r_cause == fmpp_pkg::ERR_UNMAPPED);
  c_r_err_writeonly: cover property (@(posedge clk_i) rst_ni && r_accept && r_cause == fmpp_pkg::ERR_WRITEONLY);
  c_r_err_align: cover property (@(posedge clk_i) rst_ni && r_accept && r_cause == fmpp_pkg::ERR_ALIGN);
  c_resp_any0: cover property (@(posedge clk_i) rst_ni && r_accept && ar_is_reg && ar_reg == fmpp_pkg::REG_RESP[11:0] &&
                                 resp_any_i == 1'b0);
  c_resp_any1: cover property (@(posedge clk_i) rst_ni && r_accept && ar_is_reg && ar_reg == fmpp_pkg::REG_RESP[11:0] &&
                                 resp_any_i == 1'b1);
  c_status_any0: cover property (@(posedge clk_i) rst_ni && r_accept && ar_is_reg && ar_reg == fmpp_pkg::REG_STATUS[11:0] &&
                                 resp_any_i == 1'b0);
  c_status_any1: cover property (@(posedge clk_i) rst_ni && r_accept && ar_is_reg && ar_reg == fmpp_pkg::REG_STATUS[11:0] &&
                                 resp_any_i == 1'b1);
  c_b_backpressure: cover property (@(posedge clk_i) rst_ni && bvalid_q && !bready_i);
  c_r_backpressure: cover property (@(posedge clk_i) rst_ni && rvalid_q && !rready_i);
  c_read_waits_err: cover property (@(posedge clk_i) rst_ni && arvalid_i && (!rvalid_q || rready_i) && q_empty_i &&
                                     err_pend);
  c_resp_waits: cover property (@(posedge clk_i) rst_ni && r_ready && !r_wait_done);
  c_push_full: cover property (@(posedge clk_i) rst_ni && awvalid_i && wvalid_i && w_push && !w_err && q_full_i);
  c_bad_push_busy: cover property (@(posedge clk_i) rst_ni && w_accept && w_target && w_err && !q_empty_i);
`endif

  logic unused_prot;
  assign unused_prot = ^{awprot_i, arprot_i, aw_flag, w_ctrl_v, w_error_v, aw_in_plane, aw_in_flags};

  // Assertions
`ifndef SYNTHESIS
  if (fmpp_pkg::DataW != 64) begin : g_bad_data_width
    $error("fmpp_axil_slave: the map's bus is %0d bits wide; this slave moves 64-bit beats", fmpp_pkg::DataW);
  end
  if (NumWords < 2 || NumWords > fmpp_pkg::MaxWords || NumWords % 2 != 0) begin : g_bad_words
    $error("fmpp_axil_slave: NumWords = %0d must be even and in [2, %0d]", NumWords, fmpp_pkg::MaxWords);
  end
  // What the master must do (AXI4 A3.2.1): hold VALID and the payload until READY.
  a_aw_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (awvalid_i && !awready_o) |=> (awvalid_i && $stable(awaddr_i)))
    else $error("AXI: AWVALID dropped or AWADDR changed before AWREADY");
  a_w_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (wvalid_i && !wready_o) |=> (wvalid_i && $stable(wdata_i) && $stable(wstrb_i)))
    else $error("AXI: WVALID dropped or WDATA/WSTRB changed before WREADY");
  a_ar_stable: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (arvalid_i && !arready_o) |=> (arvalid_i && $stable(araddr_i)))
    else $error("AXI: ARVALID dropped or ARADDR changed before ARREADY");
  // What this slave guarantees.
  a_b_hold: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (bvalid_o && !bready_i) |=> (bvalid_o && $stable(bresp_o)))
    else $error("AXI: BVALID dropped or BRESP changed before BREADY");
  a_r_hold: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (rvalid_o && !rready_i) |=> (rvalid_o && $stable(rdata_o) && $stable(rresp_o)))
    else $error("AXI: RVALID dropped or RDATA/RRESP changed before RREADY");
  a_aw_w_together: assert property (@(posedge clk_i) disable iff (!rst_ni) awready_o == wready_o)
    else $error("fmpp_axil_slave: AWREADY and WREADY differ");
  a_read_ordered: assert property (@(posedge clk_i) disable iff (!rst_ni) r_accept |-> q_empty_i)
    else $error("fmpp_axil_slave: read accepted while pushes are pending");
  a_push_room: assert property (@(posedge clk_i) disable iff (!rst_ni) push_o |-> !q_full_i)
    else $error("fmpp_axil_slave: push into a full queue");
  a_cause_flat: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (awvalid_i && wvalid_i) |-> (w_ok == (w_cause == fmpp_pkg::ERR_NONE)))
    else $error("fmpp_axil_slave: the flat write decision and the error cause disagree");
  a_err_reads_zero: assert property (@(posedge clk_i) disable iff (!rst_ni) (arvalid_i && r_err) |-> r_data == '0)
    else $error("fmpp_axil_slave: a read with an error would return data");
  a_push_legal: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (push_o && w_entry.kind == fmpp_pkg::QE_INSTR) |-> instr_legal)
    else $error("fmpp_axil_slave: illegal instruction queued");
`endif

endmodule
