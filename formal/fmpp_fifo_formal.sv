// Formal harness of the instruction queue (fmpp_fifo) at the FMPP's queue depth. The
// FIFO never looks at its data, so its width only scales the solver's work: the runs
// use Width = 8 for the deep checks and the real entry width (fmpp_pkg::QEntryW) for
// the induction. The properties are in rtl/fmpp_fifo.sv (`ifdef FORMAL`); this harness only
// states what the FIFO may assume of its environment. Run by tools/formal.sh.
module fmpp_fifo_formal #(
  parameter int unsigned Width = 8
) (
  input logic                        clk_i,
  input logic                        rst_ni,
  input logic                        push_i,
  input logic [Width-1:0]            data_i,
  input logic                        pop_i
);
  localparam int unsigned Depth = fmpp_pkg::QueueDepth;
  logic [Width-1:0] head;
  logic empty, full;
  logic [$clog2(Depth+1)-1:0] level;

  fmpp_fifo #(.Width(Width), .Depth(Depth)) u_fifo (
    .clk_i, .rst_ni, .push_i, .data_i, .pop_i,
    .head_o (head), .empty_o (empty), .full_o (full), .level_o (level)
  );

  logic f_init = 1'b1;
  always_ff @(posedge clk_i) f_init <= 1'b0;
  always @(*) begin
    // The run starts in reset.
    if (f_init) assume (!rst_ni);
    // The slave pushes only with room, the array pops only a valid head.
    if (rst_ni) assume (!(push_i && full));
    if (rst_ni) assume (!(pop_i && empty));
  end
endmodule
