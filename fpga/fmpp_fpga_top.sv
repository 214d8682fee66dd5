// fmpp_fpga_top: a pin-saving harness that puts a small FMPP on an iCE40 for
// place-and-route and timing (tools/fpga.sh, figures in docs/generated/area.md).
//
// The full AXI4-Lite port needs about 220 pins, more than the iCE40 packages have.
// Here every input of fmpp_top comes from a flip-flop of one shift chain loaded
// through the pin sin_i, and every output goes into a flip-flop whose values are
// folded (XOR) into one registered pin, sout_o. No input is constant and every
// output reaches a pin, so synthesis can remove none of the FMPP's logic, and
// every timing path of the FMPP starts and ends at a flip-flop of the same clock:
// the maximum frequency reported is that of fmpp_top itself, not of pins.
// Not a way to run the FMPP on a board: it only measures size and speed.
module fmpp_fpga_top #(
  parameter int unsigned NumBlocks = 2,
  parameter int unsigned NumWords  = 8
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic sin_i,
  output logic sout_o
);
  localparam int unsigned AW = fmpp_pkg::AddrW;
  // awvalid, awaddr, awprot, wvalid, wdata, wstrb, bready, arvalid, araddr, arprot, rready
  localparam int unsigned InW  = 1 + AW + 3 + 1 + 64 + 8 + 1 + 1 + AW + 3 + 1;
  // awready, wready, bvalid, bresp, arready, rvalid, rdata, rresp
  localparam int unsigned OutW = 1 + 1 + 1 + 2 + 1 + 1 + 64 + 2;

  logic [InW-1:0]  in_q;
  logic [OutW-1:0] out_d, out_q;
  logic            rst_q, sout_q;

  always_ff @(posedge clk_i) begin
    in_q   <= {in_q[InW-2:0], sin_i};
    rst_q  <= rst_ni;
    out_q  <= out_d;
    sout_q <= ^out_q;
  end
  assign sout_o = sout_q;

  fmpp_top #(.NumBlocks(NumBlocks), .NumWords(NumWords)) u_fmpp (
    .clk_i            (clk_i),
    .rst_ni           (rst_q),
    .s_axil_awvalid_i (in_q[0]),
    .s_axil_awaddr_i  (in_q[1 +: AW]),
    .s_axil_awprot_i  (in_q[1 + AW +: 3]),
    .s_axil_wvalid_i  (in_q[4 + AW]),
    .s_axil_wdata_i   (in_q[5 + AW +: 64]),
    .s_axil_wstrb_i   (in_q[69 + AW +: 8]),
    .s_axil_bready_i  (in_q[77 + AW]),
    .s_axil_arvalid_i (in_q[78 + AW]),
    .s_axil_araddr_i  (in_q[79 + AW +: AW]),
    .s_axil_arprot_i  (in_q[79 + 2 * AW +: 3]),
    .s_axil_rready_i  (in_q[82 + 2 * AW]),
    .s_axil_awready_o (out_d[0]),
    .s_axil_wready_o  (out_d[1]),
    .s_axil_bvalid_o  (out_d[2]),
    .s_axil_bresp_o   (out_d[3 +: 2]),
    .s_axil_arready_o (out_d[5]),
    .s_axil_rvalid_o  (out_d[6]),
    .s_axil_rdata_o   (out_d[7 +: 64]),
    .s_axil_rresp_o   (out_d[71 +: 2])
  );

  // Elaboration check: the chain above is laid out for exactly InW input bits.
  if (InW != 83 + 2 * AW) begin : g_bad_chain
    $error("fmpp_fpga_top: input chain of %0d bits does not match its layout", InW);
  end

endmodule
