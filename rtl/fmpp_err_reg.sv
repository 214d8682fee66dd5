// fmpp_err_reg: the slave's sticky ERROR register (fmpp_axil_slave): the first error's
// cause and address, a saturating count of errors, and the sticky bit, cleared by a write
// of 1 to STICKY.
//
// What an access does to it (an error, a clear) is registered as an event at the access's
// edge and applied at the next edge: the slave's address decode and accept then end in
// these few registers, and the count's increment starts from them (on the iCE40 the
// decode, the accept and a 16-bit increment in one clock were the FMPP's longest path).
// pend_o is high in the clock after an access with an error or any write to ERROR; the
// slave holds reads while it is, so what ERROR and STATUS show is always up to date. At
// one edge a clear applies first, then the errors, the write's before the read's.
// The registers are public for the lockstep checker (tb/), which reads ERROR as a read
// would show it: the register with the pending event applied.
module fmpp_err_reg (
  input  logic                          clk_i,
  input  logic                          rst_ni,
  input  logic                          w_err_i,    // a write with an error is accepted
  input  fmpp_pkg::err_e                w_cause_i,
  input  logic [fmpp_pkg::AddrW-1:0]    w_addr_i,
  input  logic                          w_touch_i,  // a write to ERROR is accepted
  input  logic                          w_clear_i,  // ... with STICKY set: a clear
  input  logic                          r_err_i,    // a read with an error is accepted
  input  fmpp_pkg::err_e                r_cause_i,
  input  logic [fmpp_pkg::AddrW-1:0]    r_addr_i,
  output logic                          pend_o,
  output logic                          sticky_o,
  output fmpp_pkg::err_e                cause_o,
  output logic [fmpp_pkg::REG_ERROR_COUNT_W-1:0] count_o,
  output logic [fmpp_pkg::AddrW-1:0]    addr_o
);
  logic           err_sticky_q /*verilator public_flat_rd*/;
  fmpp_pkg::err_e err_cause_q /*verilator public_flat_rd*/;
  localparam int unsigned CW = fmpp_pkg::REG_ERROR_COUNT_W;
  logic [CW-1:0]  err_count_q /*verilator public_flat_rd*/;
  logic [fmpp_pkg::AddrW-1:0] err_addr_q /*verilator public_flat_rd*/;
  // The events waiting for the next edge.
  logic           ev_pend_q /*verilator public_flat_rd*/;
  logic           ev_clear_q /*verilator public_flat_rd*/;
  logic           ev_w_q /*verilator public_flat_rd*/;
  logic           ev_r_q /*verilator public_flat_rd*/;
  fmpp_pkg::err_e ev_wcause_q /*verilator public_flat_rd*/;
  fmpp_pkg::err_e ev_rcause_q /*verilator public_flat_rd*/;
  logic [fmpp_pkg::AddrW-1:0] ev_waddr_q /*verilator public_flat_rd*/;
  logic [fmpp_pkg::AddrW-1:0] ev_raddr_q /*verilator public_flat_rd*/;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ev_pend_q  <= 1'b0;
      ev_clear_q <= 1'b0;
      ev_w_q     <= 1'b0;
      ev_r_q     <= 1'b0;
    end else begin
      ev_pend_q  <= w_err_i || w_touch_i || r_err_i;
      ev_clear_q <= w_clear_i;
      ev_w_q     <= w_err_i;
      ev_r_q     <= r_err_i;
    end
    ev_wcause_q <= w_cause_i;
    ev_rcause_q <= r_cause_i;
    ev_waddr_q  <= w_addr_i;
    ev_raddr_q  <= r_addr_i;
  end

  // The count: after the clear, one more per error of the event, saturating at its
  // maximum. One adder from the register, the clear selecting at its end (two saturating
  // increments in series were the longest path of the 16 x 32 machine in standard cells).
  logic [1:0]     ev_n;
  logic [CW:0]    count_sum;
  logic           err_sticky_d;
  fmpp_pkg::err_e err_cause_d;
  logic [CW-1:0]  err_count_d;
  logic [fmpp_pkg::AddrW-1:0] err_addr_d;
  assign ev_n      = 2'(ev_w_q) + 2'(ev_r_q);
  assign count_sum = {1'b0, err_count_q} + (CW + 1)'(ev_n);

  always_comb begin
    err_sticky_d = err_sticky_q;
    err_cause_d  = err_cause_q;
    err_addr_d   = err_addr_q;
    if (ev_clear_q) begin
      err_sticky_d = 1'b0;
      err_cause_d  = fmpp_pkg::ERR_NONE;
      err_count_d  = CW'(ev_n);
      err_addr_d   = '0;
    end else begin
      err_count_d  = count_sum[CW] ? '1 : count_sum[CW-1:0];
    end
    if (ev_w_q) begin
      if (!err_sticky_d) begin
        err_cause_d = ev_wcause_q;
        err_addr_d  = ev_waddr_q;
      end
      err_sticky_d = 1'b1;
    end
    if (ev_r_q) begin
      if (!err_sticky_d) begin
        err_cause_d = ev_rcause_q;
        err_addr_d  = ev_raddr_q;
      end
      err_sticky_d = 1'b1;
    end
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      err_sticky_q <= 1'b0;
      err_cause_q  <= fmpp_pkg::ERR_NONE;
      err_count_q  <= '0;
      err_addr_q   <= '0;
    end else begin
      err_sticky_q <= err_sticky_d;
      err_cause_q  <= err_cause_d;
      err_count_q  <= err_count_d;
      err_addr_q   <= err_addr_d;
    end
  end

  assign pend_o   = ev_pend_q;
  assign sticky_o = err_sticky_q;
  assign cause_o  = err_cause_q;
  assign count_o  = err_count_q;
  assign addr_o   = err_addr_q;

endmodule
