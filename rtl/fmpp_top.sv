// fmpp_top: the FMPP, a SIMD processor-in-memory of NumBlocks blocks (each
// NumWords 32-bit words, 8 flags and one ALU), seen by the host as an AXI4-Lite
// slave. Host writes of instructions and data pass through the instruction queue
// (fmpp_fifo) to the array (fmpp_array), whose three-stage pipeline executes one entry
// per clock. Reads wait until the queue is empty and the pipeline has drained.
module fmpp_top #(
  parameter int unsigned NumBlocks = 64,
  parameter int unsigned NumWords  = 32
) (
  input  logic                         clk_i,
  // Active-low reset, sampled synchronously by every flop; only the assertions'
  // `disable iff` uses it asynchronously (hence the lint waiver).
  /* verilator lint_off SYNCASYNCNET */
  input  logic                         rst_ni,
  /* verilator lint_on SYNCASYNCNET */

  input  logic                         s_axil_awvalid_i,
  output logic                         s_axil_awready_o,
  input  logic [fmpp_pkg::AddrW-1:0]   s_axil_awaddr_i,
  input  logic [2:0]                   s_axil_awprot_i,
  input  logic                         s_axil_wvalid_i,
  output logic                         s_axil_wready_o,
  input  logic [63:0]                  s_axil_wdata_i,
  input  logic [7:0]                   s_axil_wstrb_i,
  output logic                         s_axil_bvalid_o,
  input  logic                         s_axil_bready_i,
  output logic [1:0]                   s_axil_bresp_o,
  input  logic                         s_axil_arvalid_i,
  output logic                         s_axil_arready_o,
  input  logic [fmpp_pkg::AddrW-1:0]   s_axil_araddr_i,
  input  logic [2:0]                   s_axil_arprot_i,
  output logic                         s_axil_rvalid_o,
  input  logic                         s_axil_rready_i,
  output logic [63:0]                  s_axil_rdata_o,
  output logic [1:0]                   s_axil_rresp_o
);
  localparam int unsigned QDepth = fmpp_pkg::QueueDepth;

  logic                 push, pop, q_full, q_empty, busy;

  // An access that waits for the array (a read, a register write) waits until the array has
  // been idle a whole clock: the words and flags a read returns have then stood still for two
  // clocks, so the read data's path from a tile's storage across the die to the read register
  // has two clocks (tools/asic_chip.py times it so; a_read_still below checks it).
  logic                 busy_q;
  always_ff @(posedge clk_i) busy_q <= rst_ni && busy;
  fmpp_pkg::qentry_t    push_entry, head;
  logic [$clog2(QDepth+1)-1:0] q_level;

  logic                 rd_en, resp_en;
  fmpp_pkg::rkind_e     rd_kind;
  logic [fmpp_pkg::BlockIdxW-1:0] rd_block;
  logic [fmpp_pkg::WordIdxW-1:0]  rd_word;
  logic [fmpp_pkg::FlagIdxW-1:0]  rd_flag;
  logic [63:0]          rd_data;
  logic [31:0]          rd_late;  // a word read answered a clock after its accept (FMPP_BRAM_WORDS_HOST)
  logic                 resp_any, ovf_any;
  logic [fmpp_pkg::REG_RESP_COUNT_W-1:0]    resp_count;
  logic [fmpp_pkg::REG_RESP_FIRST_W-1:0]    resp_first;
  logic [fmpp_pkg::REG_MASK_VALUE_W-1:0]    mask;
  logic [fmpp_pkg::REG_INSTRET_VALUE_W-1:0] instret;
  logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap;

  fmpp_axil_slave #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_slave (
    .clk_i,
    .rst_ni,
    .awvalid_i    (s_axil_awvalid_i),
    .awready_o    (s_axil_awready_o),
    .awaddr_i     (s_axil_awaddr_i),
    .awprot_i     (s_axil_awprot_i),
    .wvalid_i     (s_axil_wvalid_i),
    .wready_o     (s_axil_wready_o),
    .wdata_i      (s_axil_wdata_i),
    .wstrb_i      (s_axil_wstrb_i),
    .bvalid_o     (s_axil_bvalid_o),
    .bready_i     (s_axil_bready_i),
    .bresp_o      (s_axil_bresp_o),
    .arvalid_i    (s_axil_arvalid_i),
    .arready_o    (s_axil_arready_o),
    .araddr_i     (s_axil_araddr_i),
    .arprot_i     (s_axil_arprot_i),
    .rvalid_o     (s_axil_rvalid_o),
    .rready_i     (s_axil_rready_i),
    .rdata_o      (s_axil_rdata_o),
    .rresp_o      (s_axil_rresp_o),
    .push_o       (push),
    .push_entry_o (push_entry),
    .q_full_i     (q_full),
    .q_empty_i    (q_empty && !busy && !busy_q),  // every push executed, a clock ago
    .rd_en_o      (rd_en),
    .rd_kind_o    (rd_kind),
    .rd_block_o   (rd_block),
    .rd_word_o    (rd_word),
    .rd_flag_o    (rd_flag),
    .rd_data_i    (rd_data),
    .rd_late_i    (rd_late),
    .resp_en_o    (resp_en),
    .resp_any_i   (resp_any),
    .resp_count_i (resp_count),
    .resp_first_i (resp_first),
    .ovf_any_i    (ovf_any),
    .mask_i       (mask),
    .instret_i    (instret),
    .gap_o        (gap)
  );

  fmpp_fifo #(.Width(fmpp_pkg::QEntryW), .Depth(QDepth)) u_queue (
    .clk_i,
    .rst_ni,
    .push_i  (push),
    .data_i  (push_entry),
    .pop_i   (pop),
    .head_o  (head),
    .empty_o (q_empty),
    .full_o  (q_full),
    .level_o (q_level)
  );

  fmpp_array #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_array (
    .clk_i,
    .rst_ni,
    .head_i       (head),
    .head_valid_i (!q_empty),
    .pop_o        (pop),
    .gap_i        (gap),
    .busy_o       (busy),
    .rd_en_i      (rd_en),
    .rd_kind_i    (rd_kind),
    .rd_block_i   (rd_block),
    .rd_word_i    (rd_word),
    .rd_flag_i    (rd_flag),
    .rd_data_o    (rd_data),
    .rd_acc_i     (s_axil_arvalid_i && s_axil_arready_o),
    .rd_late_o    (rd_late),
    .resp_en_i    (resp_en),
    .resp_any_o   (resp_any),
    .resp_count_o (resp_count),
    .resp_first_o (resp_first),
    .ovf_any_o    (ovf_any),
    .mask_o       (mask),
    .instret_o    (instret)
  );

  logic unused_level;
  assign unused_level = ^q_level;

`ifndef SYNTHESIS
  // The array wrote nothing at the edge before a read is accepted (the two-clock read path).
  a_read_still: assert property (@(posedge clk_i) disable iff (!rst_ni)
      (s_axil_arvalid_i && s_axil_arready_o) |-> !busy_q)
    else $error("fmpp_top: read accepted in the clock after the array was busy");
`endif
endmodule
