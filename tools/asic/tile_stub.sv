// A timing stand-in for fmpp_tile, for tools/asic_chip.py only (never in rtl/fmpp.f).
//
// It has fmpp_tile's parameters and ports. Every input ends in a flip-flop and every output
// starts at one, so that fmpp_top synthesized with this module in place of the tile keeps
// exactly the logic between the tiles, as the real fmpp_array.sv writes it, between
// flip-flops: the broadcast from the stage registers to each tile, the OR of the tiles'
// "if any" answers back into every tile, the responder chain and the read data into the
// bus slave. The tile's own share of each of those paths is measured on the real fmpp_tile
// alone, port bit by port bit; asic_chip.py adds the two at each bit, and the wires between.
module fmpp_tile #(
  parameter int unsigned Lanes    = 64,
  parameter int unsigned NumWords = 32
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  input  logic [31:0]                    base_i,
  input  logic                           opr_a_en_i,
  input  logic                           opr_b_en_i,
  input  logic [fmpp_pkg::F_A_W-1:0]     a_i,
  input  logic [fmpp_pkg::F_B_W-1:0]     b_i,
  input  logic [fmpp_pkg::F_OP_W-1:0]    opr_op_i,
  input  logic [fmpp_pkg::F_IMM_W-1:0]   opr_imm_i,
  input  logic [fmpp_pkg::SHR_A_W-1:0]   opr_shr_i,
  input  logic                           fwd_a_i,
  input  logic                           exec_i,
  input  logic [fmpp_pkg::F_OP_W-1:0]    alu_op_i,
  input  logic                           ws_sum_i,
  input  logic                           ws_alu_i,
  input  logic                           ws_writes_i,
  input  logic                           ws_bitcopy_i,
  input  logic                           ws_word_i,
  input  fmpp_pkg::qkind_e               kind_i,
  input  logic [fmpp_pkg::F_OP_W-1:0]    op_i,
  input  logic [fmpp_pkg::F_F_W-1:0]     f_i,
  input  logic [fmpp_pkg::F_F_W-1:0]     f_nx_i,
  input  logic [fmpp_pkg::F_D_W-1:0]     d_i,
  input  logic [fmpp_pkg::F_X_W-1:0]     x_i,
  input  logic [fmpp_pkg::F_IMM_W-1:0]   imm_i,
  input  logic [31:0]                    mask_i,
  input  logic [fmpp_pkg::WordW-1:0]     wpl_i,
  input  logic [3:0]                     rk_i,
  // The FPGA's ports (block RAM and its shifter; unused by standard cells, as in the tile)
  input  logic [3:0]                     opr_shc_i,
  input  logic [7:0]                     opr_shf_i,
  input  logic                           opr_shv_i,
  input  logic [5:0]                     a_nx_i, b_nx_i, d_nx_i,
  input  logic                           rd_acc_i,
  output logic [31:0]                    rd_late_o,
  input  logic [fmpp_pkg::BlockIdxW-1:0] hw_block_i,
  input  logic [Lanes-1:0]               hw_lane_sel_i,
  input  logic [3:0]                     hw_strb_i,
  input  logic [31:0]                    hw_data_i,
  input  logic                           flagop_any_i,
  output logic                           flagop_any_o,
  input  logic                           rd_en_i,
  input  fmpp_pkg::rkind_e               rd_kind_i,
  input  logic [fmpp_pkg::BlockIdxW-1:0] rd_block_i,
  input  logic [fmpp_pkg::WordIdxW-1:0]  rd_word_i,
  input  logic [fmpp_pkg::FlagIdxW-1:0]  rd_flag_i,
  output logic [63:0]                    rd_data_o,
  input  logic                           resp_en_i,
  output logic                           sel_any_o,
  output logic [31:0]                    sel_count_o,
  output logic [fmpp_pkg::LaneIdxW-1:0]  sel_first_o,
  output logic                           ovf_any_o
);
  // One flip-flop vector per port, named q_<port> (asic_chip.py finds them by these names).
  (* keep *) logic                           q_rst_ni, q_opr_a_en_i, q_opr_b_en_i, q_fwd_a_i, q_exec_i, q_flagop_any_i, q_rd_en_i, q_resp_en_i;
  (* keep *) logic                           q_ws_sum_i, q_ws_alu_i, q_ws_writes_i, q_ws_bitcopy_i, q_ws_word_i;
  (* keep *) logic [31:0]                    q_base_i, q_mask_i, q_hw_data_i;
  (* keep *) logic [fmpp_pkg::WordW-1:0]     q_wpl_i;
  (* keep *) logic [3:0]                     q_rk_i;
  (* keep *) logic [fmpp_pkg::F_A_W-1:0]     q_a_i;
  (* keep *) logic [fmpp_pkg::F_B_W-1:0]     q_b_i;
  (* keep *) logic [fmpp_pkg::F_OP_W-1:0]    q_opr_op_i, q_op_i, q_alu_op_i;
  (* keep *) logic [fmpp_pkg::F_IMM_W-1:0]   q_opr_imm_i, q_imm_i;
  (* keep *) logic [fmpp_pkg::SHR_A_W-1:0]   q_opr_shr_i;
  (* keep *) logic [1:0]                     q_kind_i, q_rd_kind_i;
  (* keep *) logic [fmpp_pkg::F_F_W-1:0]     q_f_i, q_f_nx_i;
  (* keep *) logic [fmpp_pkg::F_D_W-1:0]     q_d_i;
  (* keep *) logic [fmpp_pkg::F_X_W-1:0]     q_x_i;
  (* keep *) logic [fmpp_pkg::BlockIdxW-1:0] q_hw_block_i, q_rd_block_i;
  (* keep *) logic [3:0]                     q_hw_strb_i;
  (* keep *) logic [Lanes-1:0]               q_hw_lane_sel_i;
  (* keep *) logic [fmpp_pkg::WordIdxW-1:0]  q_rd_word_i;
  (* keep *) logic [fmpp_pkg::FlagIdxW-1:0]  q_rd_flag_i;
  (* keep *) logic                           q_flagop_any_o, q_sel_any_o, q_ovf_any_o;
  (* keep *) logic [63:0]                    q_rd_data_o;
  // The tile's count of Lanes flags is at most Lanes: its upper bits are 0, as synthesis of
  // the real tile finds, and the adders after it are as narrow as in the real design.
  localparam int unsigned CountW = $clog2(Lanes + 1);
  (* keep *) logic [CountW-1:0]              q_sel_count_o;
  (* keep *) logic [fmpp_pkg::LaneIdxW-1:0]  q_sel_first_o;

  always_ff @(posedge clk_i) begin
    {q_rst_ni, q_opr_a_en_i, q_opr_b_en_i, q_fwd_a_i, q_exec_i, q_flagop_any_i, q_rd_en_i, q_resp_en_i} <=
        {rst_ni, opr_a_en_i, opr_b_en_i, fwd_a_i, exec_i, flagop_any_i, rd_en_i, resp_en_i};
    {q_ws_sum_i, q_ws_alu_i, q_ws_writes_i, q_ws_bitcopy_i, q_ws_word_i} <= {ws_sum_i, ws_alu_i, ws_writes_i, ws_bitcopy_i, ws_word_i};
    {q_base_i, q_mask_i, q_hw_data_i, q_a_i, q_b_i, q_opr_op_i, q_op_i} <= {base_i, mask_i, hw_data_i, a_i, b_i, opr_op_i, op_i};
    {q_opr_imm_i, q_opr_shr_i, q_imm_i, q_kind_i, q_rd_kind_i, q_f_i, q_f_nx_i, q_d_i, q_x_i} <=
        {opr_imm_i, opr_shr_i, imm_i, kind_i, rd_kind_i, f_i, f_nx_i, d_i, x_i};
    {q_alu_op_i, q_hw_lane_sel_i, q_wpl_i, q_rk_i} <= {alu_op_i, hw_lane_sel_i, wpl_i, rk_i};
    {q_hw_block_i, q_rd_block_i, q_hw_strb_i, q_rd_word_i, q_rd_flag_i} <= {hw_block_i, rd_block_i, hw_strb_i, rd_word_i, rd_flag_i};
  end

  // Every input flip-flop reaches an output one: each output vector toggles by the parity of
  // some of the input vectors, so that synthesis keeps them all.
  logic p_ctl, p_words, p_fields, p_addr;
  assign p_ctl    = ^{q_rst_ni, q_opr_a_en_i, q_opr_b_en_i, q_fwd_a_i, q_exec_i, q_ws_sum_i, q_ws_alu_i, q_ws_writes_i,
                       q_ws_bitcopy_i, q_ws_word_i, q_flagop_any_i, q_rd_en_i, q_resp_en_i};
  assign p_words  = ^{q_base_i, q_mask_i, q_hw_data_i, q_a_i, q_b_i, q_opr_op_i, q_op_i, q_alu_op_i, q_wpl_i, q_rk_i};
  assign p_fields = ^{q_opr_imm_i, q_opr_shr_i, q_imm_i, q_kind_i, q_rd_kind_i, q_f_i, q_f_nx_i, q_d_i, q_x_i};
  assign p_addr   = ^{q_hw_block_i, q_hw_lane_sel_i, q_rd_block_i, q_hw_strb_i, q_rd_word_i, q_rd_flag_i};
  always_ff @(posedge clk_i) begin
    q_flagop_any_o <= q_flagop_any_o ^ p_ctl;
    q_rd_data_o    <= q_rd_data_o ^ {64{p_words}};
    q_sel_any_o    <= q_sel_any_o ^ p_fields;
    q_sel_count_o  <= q_sel_count_o ^ {CountW{p_fields}};
    q_sel_first_o  <= q_sel_first_o ^ {fmpp_pkg::LaneIdxW{p_addr}};
    q_ovf_any_o    <= q_ovf_any_o ^ p_addr;
  end

  assign flagop_any_o = q_flagop_any_o;
  assign rd_data_o    = q_rd_data_o;
  assign sel_any_o    = q_sel_any_o;
  assign sel_count_o  = 32'(q_sel_count_o);
  assign sel_first_o  = q_sel_first_o;
  assign ovf_any_o    = q_ovf_any_o;
  assign rd_late_o    = '0;
  logic unused_fpga;
  assign unused_fpga = ^{opr_shc_i, opr_shf_i, opr_shv_i, a_nx_i, b_nx_i, d_nx_i, rd_acc_i};
endmodule
