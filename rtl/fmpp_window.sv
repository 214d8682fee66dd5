// fmpp_window: whether an address falls in [Base, Base + Size) and its offset there
// (the offset is meaningful only inside the window).
module fmpp_window #(
  parameter logic [fmpp_pkg::AddrW-1:0] Base = '0,
  parameter logic [fmpp_pkg::AddrW-1:0] Size = 1
) (
  input  logic [fmpp_pkg::AddrW-1:0] addr_i,
  output logic                       in_o,
  output logic [fmpp_pkg::AddrW-1:0] off_o
);
  localparam int unsigned AW = fmpp_pkg::AddrW;
  localparam bit Aligned = Size != '0 && (Size & (Size - 1'b1)) == '0 && (Base & (Size - 1'b1)) == '0;

  if (Aligned) begin : g_aligned
    localparam logic [AW-1:0] Low = Size - 1'b1;
    assign in_o  = (addr_i & ~Low) == Base;
    assign off_o = addr_i & Low;
  end else begin : g_general
    assign off_o = addr_i - Base;
    assign in_o  = addr_i >= Base && off_o < Size;
  end

endmodule
