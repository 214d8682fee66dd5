// Formal harness of the AXI4-Lite slave (fmpp_axil_slave). Every input is free except
// for what the AXI4 specification asks of a master (VALID and the payload held until
// READY) and what the queue can show (never full and empty at once). The harness keeps
// its own account of the requests and checks the slave against it and against the
// access rules of docs/generated/memory-map.md, written here independently of the RTL decoder:
// the legality of an instruction comes from fmpp_instr_ref (generated from the map).
// Run by tools/formal.sh (bounded model check, then k-induction).
module fmpp_axil_slave_formal #(
  parameter int unsigned NumBlocks = 100,
  parameter int unsigned NumWords  = 10
) (
  input logic                       clk_i,
  input logic                       rst_ni,
  input logic                       awvalid_i,
  input logic [fmpp_pkg::AddrW-1:0] awaddr_i,
  input logic [2:0]                 awprot_i,
  input logic                       wvalid_i,
  input logic [63:0]                wdata_i,
  input logic [7:0]                 wstrb_i,
  input logic                       bready_i,
  input logic                       arvalid_i,
  input logic [fmpp_pkg::AddrW-1:0] araddr_i,
  input logic [2:0]                 arprot_i,
  input logic                       rready_i,
  input logic                       q_full_i,
  input logic                       q_empty_i,
  input logic [63:0]                rd_data_i,
  input logic                       resp_any_i,
  input logic [31:0]                resp_count_i,
  input logic [30:0]                resp_first_i,
  input logic                       ovf_any_i,
  input logic [31:0]                mask_i,
  input logic [63:0]                instret_i
);
  localparam logic [1:0] Okay = 2'b00, SlvErr = 2'b10;
  localparam int unsigned NumTiles = (NumBlocks + fmpp_pkg::LaneW - 1) / fmpp_pkg::LaneW;
  localparam int unsigned WBits    = $clog2(NumWords);       // WORDS: 2^WBits word slots per block

  logic awready, wready, bvalid, arready, rvalid, push, rd_en, resp_en;
  logic [1:0] bresp, rresp;
  logic [63:0] rdata;
  fmpp_pkg::qentry_t push_entry;
  fmpp_pkg::rkind_e rd_kind;
  logic [15:0] rd_block;
  logic [5:0] rd_word;
  logic [2:0] rd_flag;
  logic [7:0] gap;

  fmpp_axil_slave #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_dut (
    .clk_i, .rst_ni,
    .awvalid_i, .awready_o (awready), .awaddr_i, .awprot_i,
    .wvalid_i, .wready_o (wready), .wdata_i, .wstrb_i,
    .bvalid_o (bvalid), .bready_i, .bresp_o (bresp),
    .arvalid_i, .arready_o (arready), .araddr_i, .arprot_i,
    .rvalid_o (rvalid), .rready_i, .rdata_o (rdata), .rresp_o (rresp),
    .push_o (push), .push_entry_o (push_entry), .q_full_i, .q_empty_i,
    .rd_en_o (rd_en), .rd_kind_o (rd_kind), .rd_block_o (rd_block), .rd_word_o (rd_word),
    .rd_flag_o (rd_flag), .rd_data_i, .rd_late_i ('0), .resp_en_o (resp_en), .resp_any_i, .resp_count_i,
    .resp_first_i, .ovf_any_i, .mask_i, .instret_i, .gap_o (gap)
  );

  // ------------------------------------------------ the access rules, from the docs
  logic instr_legal;
  fmpp_instr_ref #(.NumWords(NumWords)) u_ref (.instr_i (wdata_i), .legal_o (instr_legal));

  // Where an address points: 0 none, 1 register, 2 PLANES, 3 FLAGS, 4 WORDS (mapped only).
  function automatic logic [2:0] target(input logic [31:0] a);
    logic [31:0] off;
    target = 3'd0;
    if (a < 32'h1000) begin
      target = 3'd1;
    end else if (a >= fmpp_pkg::WIN_PLANES_BASE && a < fmpp_pkg::WIN_PLANES_BASE + fmpp_pkg::WIN_PLANES_SIZE) begin
      off = a - fmpp_pkg::WIN_PLANES_BASE;
      if ({19'd0, off[12:3]} < NumTiles) target = 3'd2;  // (off mod 2^13) / 8
    end else if (a >= fmpp_pkg::WIN_FLAGS_BASE && a < fmpp_pkg::WIN_FLAGS_BASE + fmpp_pkg::WIN_FLAGS_SIZE) begin
      off = a - fmpp_pkg::WIN_FLAGS_BASE;
      if ((off >> 3) < NumBlocks) target = 3'd3;
    end else if (a >= fmpp_pkg::WIN_WORDS_BASE && a < fmpp_pkg::WIN_WORDS_BASE + fmpp_pkg::WIN_WORDS_SIZE) begin
      off = a - fmpp_pkg::WIN_WORDS_BASE;
      if ((off >> (3 + WBits)) < NumBlocks && ((off >> 3) & ((1 << WBits) - 1)) < NumWords) target = 3'd4;
    end
  endfunction

  logic [2:0] aw_t, ar_t;
  logic       w_ok, w_push, w_queued, r_ok;
  assign aw_t = target(awaddr_i);
  assign ar_t = target(araddr_i);
  // A write to QUEUE, FLAGS or WORDS (aligned) takes room in the queue, legal or not.
  assign w_queued = awaddr_i[2:0] == 3'd0 && (awaddr_i == fmpp_pkg::REG_QUEUE || aw_t == 3'd3 || aw_t == 3'd4);
  always @(*) begin
    w_ok   = 1'b0;
    w_push = 1'b0;
    if (awaddr_i[2:0] == 3'd0) begin
      unique case (aw_t)
        3'd1: begin  // writable registers need all eight strobes; QUEUE a legal instruction
          if (awaddr_i == fmpp_pkg::REG_QUEUE) begin
            w_ok = wstrb_i == 8'hFF && instr_legal;
            w_push = w_ok;
          end else if (awaddr_i == fmpp_pkg::REG_CTRL || awaddr_i == fmpp_pkg::REG_ERROR) begin
            w_ok = wstrb_i == 8'hFF;
          end
        end
        3'd3: begin w_ok = wstrb_i == 8'h01; w_push = w_ok; end  // FLAGS: byte 0 only
        3'd4: begin w_ok = wstrb_i != 8'h00 && wstrb_i <= 8'h0F; w_push = w_ok; end  // WORDS: bytes 0-3
        default: ;  // PLANES is read-only; unmapped
      endcase
    end
    r_ok = araddr_i[2:0] == 3'd0 && ar_t != 3'd0;
    if (ar_t == 3'd1) begin
      r_ok = araddr_i[2:0] == 3'd0 && araddr_i <= fmpp_pkg::REG_MASK;  // QUEUE is write-only
    end
  end

  // --------------------------------------------------------- the environment
  logic f_init = 1'b1;
  logic f_aw_wait, f_w_wait, f_ar_wait;  // a request was left waiting at the last edge
  logic [31:0] f_awaddr, f_araddr;
  logic [63:0] f_wdata;
  logic [7:0]  f_wstrb;
  always_ff @(posedge clk_i) begin
    f_init    <= 1'b0;
    f_aw_wait <= rst_ni && awvalid_i && !awready;
    f_w_wait  <= rst_ni && wvalid_i && !wready;
    f_ar_wait <= rst_ni && arvalid_i && !arready;
    f_awaddr  <= awaddr_i;
    f_wdata   <= wdata_i;
    f_wstrb   <= wstrb_i;
    f_araddr  <= araddr_i;
  end
  always @(*) begin
    if (f_init) assume (!rst_ni);
    // AXI4 A3.2.1: once VALID is high, it and the payload stay until READY.
    if (rst_ni && f_aw_wait) assume (awvalid_i && awaddr_i == f_awaddr);
    if (rst_ni && f_w_wait)  assume (wvalid_i && wdata_i == f_wdata && wstrb_i == f_wstrb);
    if (rst_ni && f_ar_wait) assume (arvalid_i && araddr_i == f_araddr);
    assume (!(q_full_i && q_empty_i));
  end

  // ------------------------------------------------ the harness's own accounting
  logic f_rst_seen_q = 1'b0;
  logic f_b_pend_q, f_r_pend_q;     // an accepted request awaits its response
  logic f_b_err_q, f_r_err_q;       // ... and that response must be SLVERR
  logic w_hs, r_hs;
  assign w_hs = awvalid_i && awready;
  assign r_hs = arvalid_i && arready;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      f_rst_seen_q <= 1'b1;
      f_b_pend_q   <= 1'b0;
      f_r_pend_q   <= 1'b0;
    end else begin
      if (w_hs) begin
        f_b_pend_q <= 1'b1;
        f_b_err_q  <= !w_ok;
      end else if (bready_i) begin
        f_b_pend_q <= 1'b0;
      end
      if (r_hs) begin
        f_r_pend_q <= 1'b1;
        f_r_err_q  <= !r_ok;
      end else if (rready_i) begin
        f_r_pend_q <= 1'b0;
      end
    end
  end

  // An access that changes ERROR (an error, or any write to ERROR) was accepted at the
  // last edge: the slave applies it at this one, and a read waits for it.
  logic f_err_ev_q;
  always_ff @(posedge clk_i) begin
    f_err_ev_q <= rst_ni && ((w_hs && (!w_ok || awaddr_i == fmpp_pkg::REG_ERROR)) || (r_hs && !r_ok));
  end
  // Clocks in a row that the read on AR could have been served.
  logic       f_servable;
  logic [7:0] f_rwait_q;
  assign f_servable = arvalid_i && (!rvalid || rready_i) && q_empty_i && !f_err_ev_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni || !f_servable || arready) f_rwait_q <= 8'd0;
    else f_rwait_q <= f_rwait_q + 8'd1;
  end

  logic [1:0]  f_bresp_q, f_rresp_q;
  logic        f_bvalid_q, f_rvalid_q, f_bready_q, f_rready_q;
  always_ff @(posedge clk_i) begin
    f_bresp_q  <= bresp;
    f_rresp_q  <= rresp;
    f_bvalid_q <= bvalid && rst_ni;
    f_rvalid_q <= rvalid && rst_ni;
    f_bready_q <= bready_i;
    f_rready_q <= rready_i;
  end

  always @(*) begin
    if (f_rst_seen_q && rst_ni) begin
      // p_b_one_per_write: BVALID is high exactly while an accepted write awaits its
      // response: no response without a request, one response per request.
      p_b_one_per_write: assert (bvalid == f_b_pend_q);
      p_r_one_per_read: assert (rvalid == f_r_pend_q);
      // p_no_lost_response: a request is accepted only when the previous response
      // is gone or leaves in this clock (otherwise it would be overwritten).
      p_no_lost_response: assert ((!awready || !bvalid || bready_i) && (!arready || !rvalid || rready_i));
      // p_aw_w_together: AW and W are accepted together, and only when both are valid.
      p_aw_w_together: assert (awready == wready && (!awready || (awvalid_i && wvalid_i)) &&
                               (!arready || arvalid_i));
      // p_b_held / p_r_held: a response waiting for READY keeps VALID and its response
      // code. (RDATA is left out of the formal run: with it in the model, the read-data
      // and ERROR-register logic it pulls in stalls z3 in the first step. The lockstep
      // compares every read's data and the ERROR state with the golden model instead.)
      if (f_bvalid_q && !f_bready_q) p_b_held: assert (bvalid && bresp == f_bresp_q);
      if (f_rvalid_q && !f_rready_q) p_r_held: assert (rvalid && rresp == f_rresp_q);
      // p_slverr_exact: SLVERR exactly for the documented bad accesses, OKAY otherwise.
      if (bvalid) p_slverr_exact_w: assert (bresp == (f_b_err_q ? SlvErr : Okay));
      if (rvalid) p_slverr_exact_r: assert (rresp == (f_r_err_q ? SlvErr : Okay));
      // p_push_exact: a write is queued exactly when it is a good QUEUE, FLAGS or WORDS
      // write being accepted, with its kind, block, word and strobes. (Its data is
      // WDATA by a plain assignment, checked by the lockstep.)
      p_push_exact: assert (push == (w_hs && w_push));
      if (push) begin
        p_push_entry: assert (push_entry.strb == wstrb_i[3:0] &&
            push_entry.kind == (aw_t == 3'd1 ? fmpp_pkg::QE_INSTR : aw_t == 3'd3 ? fmpp_pkg::QE_FLAGS
                                                                     : fmpp_pkg::QE_WORD) &&
            (aw_t == 3'd1 || 32'(push_entry.block) == (aw_t == 3'd3 ? (awaddr_i - fmpp_pkg::WIN_FLAGS_BASE) >> 3
                                                     : (awaddr_i - fmpp_pkg::WIN_WORDS_BASE) >> (3 + WBits))) &&
            (aw_t != 3'd4 || 32'(push_entry.word) ==
                             (((awaddr_i - fmpp_pkg::WIN_WORDS_BASE) >> 3) & ((1 << WBits) - 1))));
        // p_push_room: nothing is pushed into a full queue (the queue never overflows).
        p_push_room: assert (!q_full_i);
      end
      // p_ordered: every access other than a write to a queued target waits for the queue
      // to drain.
      p_ordered: assert ((!arready || q_empty_i) && (!awready || w_queued || q_empty_i));
      // p_queued_room: a write to a queued target is accepted only with room in the queue.
      p_queued_room: assert (!awready || !w_queued || !q_full_i);
      // p_no_stall: the slave never holds off a request it can serve: with the response
      // channel free and room in the queue (a write to QUEUE, FLAGS or WORDS) or the queue
      // empty (anything else),
      // the request is accepted in this clock; a read, also with no change of ERROR
      // pending from the last clock. With the array draining the queue, no
      // back-pressure pattern on B and R can deadlock the port.
      if (awvalid_i && wvalid_i && (!bvalid || bready_i) && (w_queued ? !q_full_i : q_empty_i))
        p_no_stall_w: assert (awready);
      // A RESP or STATUS read (resp_en) is accepted after RespLatency clocks in which it could be
      // served (the responder tree's registers), and not before.
      if (f_servable && (!resp_en || 32'(f_rwait_q) == fmpp_pkg::RespLatency)) p_no_stall_r: assert (arready);
      if (arready && resp_en) p_resp_waits: assert (32'(f_rwait_q) == fmpp_pkg::RespLatency);
    end
  end

  // Non-vacuity: the interesting cases are reachable.
  always @(*) begin
    if (f_rst_seen_q && rst_ni) begin
      c_push: cover (push);
      c_w_slverr: cover (bvalid && bresp == SlvErr);
      c_r_slverr: cover (rvalid && rresp == SlvErr);
      c_b_backpressure: cover (f_bvalid_q && !f_bready_q && bvalid);
      c_back_to_back: cover (w_hs && bvalid && bready_i);
    end
  end

  logic unused;
  assign unused = ^{rd_en, rd_kind, rd_block, rd_word, rd_flag, gap, awprot_i, arprot_i};
endmodule
