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

endmodule
