// fmpp_fifo: synchronous FIFO (the FMPP instruction queue). The head entry is a
// register output, so the array decodes it without a read latency: an entry pushed
// at one clock edge can execute at the next.
module fmpp_fifo #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 16
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       push_i,
  input  logic [Width-1:0]           data_i,
  input  logic                       pop_i,
  output logic [Width-1:0]           head_o,
  output logic                       empty_o,
  output logic                       full_o,
  output logic [$clog2(Depth+1)-1:0] level_o
);
  localparam int unsigned PtrW = (Depth > 1) ? $clog2(Depth) : 1;
  localparam int unsigned LvlW = $clog2(Depth + 1);

  logic [Width-1:0] mem_q [Depth];
  logic [PtrW-1:0]  rptr_q, wptr_q;
  logic [LvlW-1:0]  level_q /*verilator public_flat_rd*/;

  function automatic logic [PtrW-1:0] next_ptr(input logic [PtrW-1:0] p);
    next_ptr = (p == PtrW'(Depth - 1)) ? '0 : p + 1'b1;
  endfunction

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      rptr_q  <= '0;
      wptr_q  <= '0;
      level_q <= '0;
    end else begin
      if (push_i) wptr_q <= next_ptr(wptr_q);
      if (pop_i)  rptr_q <= next_ptr(rptr_q);
      level_q <= level_q + {{(LvlW-1){1'b0}}, push_i} - {{(LvlW-1){1'b0}}, pop_i};
    end
  end

  always_ff @(posedge clk_i) begin
    if (push_i) mem_q[wptr_q] <= data_i;
  end

  assign head_o  = mem_q[rptr_q];
  assign empty_o = level_q == '0;
  assign full_o  = level_q == LvlW'(Depth);
  assign level_o = level_q;

  // Assertions
`ifndef SYNTHESIS
  a_no_overflow: assert property (@(posedge clk_i) disable iff (!rst_ni) !(push_i && full_o))
    else $error("fmpp_fifo: push while full");
  a_no_underflow: assert property (@(posedge clk_i) disable iff (!rst_ni) !(pop_i && empty_o))
    else $error("fmpp_fifo: pop while empty");
  a_level: assert property (@(posedge clk_i) disable iff (!rst_ni) level_q <= LvlW'(Depth))
    else $error("fmpp_fifo: level %0d above depth %0d", level_q, Depth);
`endif

  // Coverage (make coverage): the queue full, empty, and pushed and popped at once.
`ifdef FMPP_COVERAGE
  c_full: cover property (@(posedge clk_i) rst_ni && full_o);
  c_empty: cover property (@(posedge clk_i) rst_ni && empty_o);
  c_push_pop: cover property (@(posedge clk_i) rst_ni && push_i && pop_i);
  c_full_pop: cover property (@(posedge clk_i) rst_ni && full_o && pop_i);
`endif

  // Formal properties (formal/fmpp_fifo_formal.sv runs them; tools/formal.sh).
  // The environment's side of the contract is assumed there: no push while full, no
  // pop while empty (fmpp_axil_slave and fmpp_array guarantee these; the slave's side
  // is proved in formal/fmpp_axil_slave_formal.sv).
`ifdef FORMAL
  // The state means something only once a reset has been seen (checked from then on;
  // the harness starts the run in reset, so bounded runs check from the second clock).
  logic f_rst_seen_q = 1'b0;
  always_ff @(posedge clk_i) if (!rst_ni) f_rst_seen_q <= 1'b1;

  // Pointers and level agree: the live entries are rptr .. rptr + level - 1 (mod Depth).
  logic [PtrW:0] f_wsum;
  assign f_wsum = {1'b0, rptr_q} + level_q;
  always @(posedge clk_i) begin
    if (f_rst_seen_q) begin
      // p_level_bound: the queue never holds more than Depth entries (never overflows).
      p_level_bound: assert (level_q <= LvlW'(Depth));
      // p_ptr_consistent: the write pointer is level entries after the read pointer.
      p_ptr_consistent: assert (wptr_q == PtrW'(f_wsum >= Depth ? f_wsum - Depth : f_wsum));
      p_ptr_range: assert (rptr_q < Depth && wptr_q < Depth);
      // p_flags: EMPTY and FULL say exactly level = 0 and level = Depth.
      p_flags: assert (empty_o == (level_q == '0) && full_o == (level_q == LvlW'(Depth)));
    end
  end

  // Scoreboard for one entry chosen by the solver (any push may be the one): it must
  // leave the queue at its place in the order (after exactly the entries that were
  // ahead of it) and with its data. As every entry may be chosen, no entry is lost,
  // reordered, duplicated or corrupted.
  (* anyseq *) logic f_pick;
  logic [1:0]       f_state_q;  // 0 = nothing chosen, 1 = chosen entry queued, 2 = it left
  logic [Width-1:0] f_data_q;
  logic [LvlW-1:0]  f_ahead_q;  // entries in front of the chosen one
  logic [PtrW:0]    f_slot_sum;
  logic [PtrW-1:0]  f_slot;     // where the chosen entry is stored
  assign f_slot_sum = {1'b0, rptr_q} + f_ahead_q;
  assign f_slot     = PtrW'(f_slot_sum >= Depth ? f_slot_sum - Depth : f_slot_sum);

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      f_state_q <= 2'd0;
    end else if (f_state_q == 2'd0 && push_i && f_pick) begin
      f_state_q <= 2'd1;
      f_data_q  <= data_i;
      f_ahead_q <= level_q - {{(LvlW-1){1'b0}}, pop_i};
    end else if (f_state_q == 2'd1 && pop_i) begin
      if (f_ahead_q == '0) f_state_q <= 2'd2;
      else                 f_ahead_q <= f_ahead_q - 1'b1;
    end
  end

  always @(posedge clk_i) begin
    if (f_rst_seen_q && rst_ni && f_state_q == 2'd1) begin
      // p_order_data: when the chosen entry is popped it is the head, with its data.
      if (pop_i && f_ahead_q == '0) p_order_data: assert (head_o == f_data_q);
      // p_tracked_inside: the chosen entry is still inside the queue, stored at its slot
      // (the inductive invariant behind p_order_data).
      p_tracked_inside: assert (f_ahead_q < level_q && mem_q[f_slot] == f_data_q);
    end
    if (f_rst_seen_q) p_state_code: assert (f_state_q != 2'd3);
  end
`endif

endmodule
