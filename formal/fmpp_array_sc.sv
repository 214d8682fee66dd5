// The single-cycle FMPP array, the reference of the pipelined one in formal runs
// (formal/fmpp_pipe_formal.sv): fmpp_array and fmpp_tile as they were before the
// pipeline, when the queue head was decoded, read, executed and written back in the
// clock of its pop. Millions of lockstep instructions checked it against the golden
// model. Only its coverage points, assertions and Verilator pragmas are left out; it
// shares the ALU with the pipelined array (fmpp_alu: the addend and the execute part that
// the pipelined tile uses in stages 2 and 3, here in one clock).
module fmpp_array_sc #(
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
  logic [31:0] mask_q;
  logic [63:0] instret_q;
  logic        pop;
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
    fmpp_tile_sc #(.Lanes(Lanes), .NumWords(NumWords)) u_tile (
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




endmodule
