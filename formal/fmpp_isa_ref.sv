// The FMPP's instruction set as docs/isa.md states it, the reference of the pipelined array
// in formal runs (formal/fmpp_pipe_formal.sv with IsaRef = 1). Written from the ISA's table,
// not from the RTL: each block is NumWords 32-bit words and 8 flags, and one popped entry
// changes them at once, word by word, with `+`, `-`, `>>>` and comparisons on whole words.
// Nothing here knows of tiles, bit planes, lanes, the pipeline or the adder's texts, so a
// proof against it covers the global networks (the FLAGOP "if any" OR across tiles, the
// responders, the read data) at whatever NumBlocks the job sets.
//
// The ports are those of fmpp_array_sc (formal/fmpp_array_sc.sv): the queue head (an
// instruction or a window write), CTRL.GAP, the host read port and the responders.
module fmpp_isa_ref #(
  parameter int unsigned NumBlocks = 2,
  parameter int unsigned NumWords  = 4
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  fmpp_pkg::qentry_t    head_i,
  input  logic                 head_valid_i,
  output logic                 pop_o,
  input  logic [7:0]           gap_i,
  input  logic                 rd_en_i,
  input  fmpp_pkg::rkind_e     rd_kind_i,
  input  logic [15:0]          rd_block_i,   // block (WORD, FLAGS) or group of 64 blocks (PLANE)
  input  logic [5:0]           rd_word_i,
  input  logic [2:0]           rd_flag_i,
  output logic [63:0]          rd_data_o,
  input  logic                 resp_en_i,
  output logic                 resp_any_o,
  output logic [31:0]          resp_count_o,
  output logic [30:0]          resp_first_o,
  output logic                 ovf_any_o,
  output logic [31:0]          mask_o,
  output logic [63:0]          instret_o
);
  localparam int unsigned SEL = fmpp_pkg::FlagSEL;
  localparam int unsigned V   = fmpp_pkg::FlagV;
  localparam int unsigned WIdxW = (NumWords > 1) ? $clog2(NumWords) : 1;

  logic [31:0] mask_q;
  logic [63:0] instret_q;
  logic [7:0]  gap_q;
  logic        pop, is_instr;
  logic [4:0]  op;
  logic [31:0] imm;
  assign pop      = rst_ni && head_valid_i && gap_q == '0;
  assign pop_o    = pop;
  assign is_instr = head_i.kind == fmpp_pkg::QE_INSTR;
  assign op       = head_i.data[fmpp_pkg::F_OP_LSB +: 5];
  assign imm      = head_i.data[fmpp_pkg::F_IMM_LSB +: 32];

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      gap_q     <= '0;
      mask_q    <= '0;
      instret_q <= '0;
    end else begin
      if (pop) gap_q <= gap_i;
      else if (gap_q != '0) gap_q <= gap_q - 1'b1;
      if (pop && is_instr) begin
        instret_q <= instret_q + 1'b1;
        if (op == fmpp_pkg::OP_MASKSET) mask_q <= imm;
      end
    end
  end
  assign mask_o    = mask_q;
  assign instret_o = instret_q;

  // The blocks, and FLAGOP.any: whether v = 1 in some block of the whole machine.
  logic [31:0] b_word  [NumBlocks];  // word rd_word_i of each block
  logic [7:0]  b_flags [NumBlocks];
  logic        b_v     [NumBlocks];
  logic        any_v;
  for (genvar bl = 0; bl < NumBlocks; bl++) begin : g_block
    fmpp_isa_block #(.NumWords(NumWords), .Index(bl)) u_block (
      .clk_i, .rst_ni, .pop_i (pop), .head_i, .mask_i (mask_q), .any_v_i (any_v),
      .rd_word_i, .word_o (b_word[bl]), .flags_o (b_flags[bl]), .v_o (b_v[bl]));
  end
  always_comb begin
    any_v = 1'b0;
    for (int bl = 0; bl < NumBlocks; bl++) any_v = any_v | b_v[bl];
  end

  // The host's reads: a word or the flags of one block, or one flag of 64 blocks.
  always_comb begin
    rd_data_o = '0;
    if (rd_en_i) begin
      for (int bl = 0; bl < NumBlocks; bl++) begin
        if (rd_kind_i == fmpp_pkg::RK_WORD && 32'(rd_block_i) == 32'(bl)) rd_data_o = {32'd0, b_word[bl]};
        if (rd_kind_i == fmpp_pkg::RK_FLAGS && 32'(rd_block_i) == 32'(bl)) rd_data_o = {56'd0, b_flags[bl]};
        if (rd_kind_i == fmpp_pkg::RK_PLANE && 32'(rd_block_i) == 32'(bl / 64)) rd_data_o[bl % 64] = b_flags[bl][rd_flag_i];
      end
    end
  end

  // The responders: some SEL, how many, the lowest block with SEL; some V.
  always_comb begin
    resp_any_o   = 1'b0;
    resp_count_o = '0;
    resp_first_o = '0;
    ovf_any_o    = 1'b0;
    if (resp_en_i) begin
      for (int bl = NumBlocks - 1; bl >= 0; bl--) begin
        resp_count_o = resp_count_o + 32'(b_flags[bl][SEL]);
        ovf_any_o    = ovf_any_o | b_flags[bl][V];
        if (b_flags[bl][SEL]) begin
          resp_any_o   = 1'b1;
          resp_first_o = 31'(bl);
        end
      end
    end
  end
endmodule

// One block of the ISA's machine: its words and flags, changed by each popped entry (an
// instruction, or a window write naming this block).
module fmpp_isa_block #(
  parameter int unsigned NumWords = 4,
  parameter int unsigned Index    = 0
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              pop_i,
  input  fmpp_pkg::qentry_t head_i,
  input  logic [31:0]       mask_i,
  input  logic              any_v_i,   // FLAGOP: some block of the machine has v = 1
  input  logic [5:0]        rd_word_i,
  output logic [31:0]       word_o,    // word rd_word_i
  output logic [7:0]        flags_o,
  output logic              v_o        // FLAGOP: this block's v
);
  localparam int unsigned C   = fmpp_pkg::FlagC;
  localparam int unsigned V   = fmpp_pkg::FlagV;
  localparam int unsigned SEL = fmpp_pkg::FlagSEL;
  localparam int unsigned WIdxW = (NumWords > 1) ? $clog2(NumWords) : 1;

  logic [31:0] word_q [NumWords];
  logic [7:0]  flags_q;
  logic [63:0] ins;
  logic [4:0]  op;
  logic [2:0]  f;
  logic [WIdxW-1:0] wd, wa, wb;
  logic [5:0]  x;
  logic [31:0] imm;
  assign ins = head_i.data;
  assign op  = ins[fmpp_pkg::F_OP_LSB +: 5];
  assign f   = ins[fmpp_pkg::F_F_LSB +: 3];
  assign wd  = WIdxW'(ins[fmpp_pkg::F_D_LSB +: 6]);
  assign wa  = WIdxW'(ins[fmpp_pkg::F_A_LSB +: 6]);
  assign wb  = WIdxW'(ins[fmpp_pkg::F_B_LSB +: 6]);
  assign x   = ins[fmpp_pkg::F_X_LSB +: 6];
  assign imm = ins[fmpp_pkg::F_IMM_LSB +: 32];

  // FLAGOP's table: v = lut[2 fa + fb].
  function automatic lut_v(input logic [3:0] lut, input logic fa, input logic fb);
    lut_v = lut[{fa, fb}];
  endfunction

  // One block's instruction: its words A, B, D, flags and index in (and the machine's mask
  // and FLAGOP "if any"), {its new word D, its new flags} out.
  function automatic [39:0] exec(input logic [4:0] op, input logic [2:0] f, input logic [5:0] x,
                                       input logic [31:0] imm, input logic [31:0] mask, input logic any_v,
                                       input logic [31:0] a, input logic [31:0] b, input logic [31:0] d,
                                       input logic [7:0] fl, input logic [31:0] index);
    logic [31:0] a_s, r, d_o;
    logic [7:0]  fl_o;
    logic [32:0] wide;
    logic        m, carry, ovf, pred, v;
    logic [4:0]  k;
    logic [1:0]  fn;
    logic [2:0]  fs;
    d_o  = d;
    fl_o = fl;
    pred = fl[f];
    fn   = x[1:0];
    case (op)
      fmpp_pkg::OP_REF, fmpp_pkg::OP_CMP: begin
        if (op == fmpp_pkg::OP_REF) begin
          m  = (((x[fmpp_pkg::REF_PART_LSB] ? index : a) ^ imm) & ~mask) == 32'd0;
          fs = x[fmpp_pkg::REF_FS_LSB +: 3];
        end else begin
          m  = ($signed(a) >= $signed(imm)) ^ x[fmpp_pkg::CMP_LT_LSB];
          fs = x[fmpp_pkg::CMP_FS_LSB +: 3];
        end
        fl_o[f] = fn == 2'd1 ? fl[fs] & m : fn == 2'd2 ? fl[fs] | m : m;
      end
      fmpp_pkg::OP_SETS:    fl_o[SEL] = 1'b1;
      fmpp_pkg::OP_RESETS:  fl_o[SEL] = 1'b0;
      fmpp_pkg::OP_SETSADR: fl_o[SEL] = index == imm;
      fmpp_pkg::OP_FLAGOP: begin
        v = lut_v(imm[fmpp_pkg::FLAG_LUT_LSB +: 4], fl[x[fmpp_pkg::FLAG_FA_LSB +: 3]], fl[x[fmpp_pkg::FLAG_FB_LSB +: 3]]);
        if (!imm[fmpp_pkg::FLAG_ANY_LSB] || any_v) fl_o[f] = v;
      end
      fmpp_pkg::OP_WRITES: if (pred) d_o = (d & mask) | (imm & ~mask);
      fmpp_pkg::OP_FUNC: if (pred) d_o = fn == 2'd0 ? a & b : fn == 2'd1 ? a | b : a ^ b;
      fmpp_pkg::OP_BITCOPY: if (pred) d_o[imm[fmpp_pkg::BIT_J_LSB +: 5]] = a[imm[fmpp_pkg::BIT_I_LSB +: 5]];
      fmpp_pkg::OP_ADD, fmpp_pkg::OP_SUB, fmpp_pkg::OP_DIVSTEP: if (pred) begin
        if (op == fmpp_pkg::OP_DIVSTEP) a_s = a << 1;
        else a_s = $signed(a) >>> imm[fmpp_pkg::SHR_A_LSB +: 5];
        if (op == fmpp_pkg::OP_ADD || (op == fmpp_pkg::OP_DIVSTEP && a[31])) begin
          wide = {1'b0, a_s} + {1'b0, b};
          ovf  = a_s[31] == b[31] && wide[31] != a_s[31];
        end else begin
          wide = {1'b0, a_s} + {1'b0, ~b} + 33'd1;
          ovf  = a_s[31] != b[31] && wide[31] != a_s[31];
        end
        if (op == fmpp_pkg::OP_DIVSTEP) ovf = ovf | (a[31] ^ a[30]);
        d_o     = wide[31:0];
        fl_o[C] = wide[32];
        fl_o[V] = fl[V] | ovf;
      end
      fmpp_pkg::OP_LSHIFT: if (pred) begin
        d_o     = a << 1;
        fl_o[C] = a[31];
        fl_o[V] = fl[V] | (a[31] ^ a[30]);
      end
      fmpp_pkg::OP_RSHIFT: if (pred) begin
        k       = imm[fmpp_pkg::SHR_A_LSB +: 5];  // shifts by k + 1
        r       = $signed(a) >>> k;
        d_o     = $signed(r) >>> 1;
        fl_o[C] = r[0];
      end
      default: ;  // NOP, MASKSET: no block changes
    endcase
    exec = {d_o, fl_o};
  endfunction

  assign v_o = head_i.kind == fmpp_pkg::QE_INSTR && op == fmpp_pkg::OP_FLAGOP &&
               lut_v(imm[fmpp_pkg::FLAG_LUT_LSB +: 4], flags_q[x[fmpp_pkg::FLAG_FA_LSB +: 3]], flags_q[x[fmpp_pkg::FLAG_FB_LSB +: 3]]);

  logic [39:0] res;
  assign res = exec(op, f, x, imm, mask_i, any_v_i, word_q[wa], word_q[wb], word_q[wd], flags_q, 32'(Index));

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      flags_q <= '0;
    end else if (pop_i && head_i.kind == fmpp_pkg::QE_INSTR) begin
      flags_q <= res[7:0];
    end else if (pop_i && head_i.kind == fmpp_pkg::QE_FLAGS && 32'(head_i.block) == 32'(Index)) begin
      flags_q <= head_i.data[7:0];
    end
    if (pop_i && head_i.kind == fmpp_pkg::QE_INSTR) begin
      word_q[wd] <= res[39:8];
    end else if (pop_i && head_i.kind == fmpp_pkg::QE_WORD && 32'(head_i.block) == 32'(Index)) begin
      for (int by = 0; by < 4; by++) begin
        if (head_i.strb[by]) word_q[WIdxW'(head_i.word)][by*8 +: 8] <= head_i.data[by*8 +: 8];
      end
    end
  end

  assign word_o  = word_q[WIdxW'(rd_word_i)];
  assign flags_o = flags_q;
endmodule
