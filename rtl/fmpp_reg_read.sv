// fmpp_reg_read: what a read returns, and its error cause. The registers' values are
// packed by the map's layouts (fmpp_pkg::<name>_reg_t, reserved bits 0); a read of a
// window returns the array's read port; anything else is an error with no data.
// Combinational: fmpp_axil_slave registers the answer. Map: docs/generated/memory-map.md.
module fmpp_reg_read #(
  parameter int unsigned NumBlocks = 64,
  parameter int unsigned NumWords  = 32
) (
  // The ports are fmpp_axil_slave's own nets, whose toggles its coverage counts already:
  // left out here, so that each bit is one toggle point (make coverage).
  /*verilator coverage_off*/
  // The read address, decoded (fmpp_addr_decode)
  input  logic                         aligned_i,
  input  logic                         is_reg_i,
  input  logic [11:0]                  reg_i,
  input  logic                         is_window_i,  // a mapped PLANES, FLAGS or WORDS address
  input  logic [63:0]                  rd_data_i,    // the array's read port

  // State shown in registers
  input  logic                         resp_any_i,
  input  logic [fmpp_pkg::REG_RESP_COUNT_W-1:0] resp_count_i,
  input  logic [fmpp_pkg::REG_RESP_FIRST_W-1:0] resp_first_i,
  input  logic                         ovf_any_i,
  input  logic                         err_sticky_i,
  input  fmpp_pkg::err_e               err_cause_i,
  input  logic [fmpp_pkg::REG_ERROR_COUNT_W-1:0] err_count_i,
  input  logic [fmpp_pkg::AddrW-1:0]   err_addr_i,
  input  logic [fmpp_pkg::REG_CTRL_GAP_W-1:0] gap_i,
  input  logic [fmpp_pkg::REG_CYCLES_VALUE_W-1:0] cycles_i,
  input  logic [fmpp_pkg::REG_INSTRET_VALUE_W-1:0] instret_i,
  input  logic [fmpp_pkg::REG_MASK_VALUE_W-1:0] mask_i,

  output fmpp_pkg::err_e               cause_o,
  output logic [63:0]                  data_o
  /*verilator coverage_on*/
);
  // WORDS block stride: log2 of the bytes of a beat, plus the word index bits.
  localparam int unsigned WShift = $clog2(fmpp_pkg::DataW / 8) + $clog2(NumWords);

  fmpp_pkg::id_reg_t      id_v;
  fmpp_pkg::config_reg_t  config_v;
  fmpp_pkg::status_reg_t  status_v;
  fmpp_pkg::error_reg_t   error_v;
  fmpp_pkg::ctrl_reg_t    ctrl_v;
  fmpp_pkg::resp_reg_t    resp_v;
  fmpp_pkg::cycles_reg_t  cycles_v;
  fmpp_pkg::instret_reg_t instret_v;
  fmpp_pkg::mask_reg_t    mask_v;
  always_comb begin
    id_v             = '0;
    id_v.magic       = fmpp_pkg::Magic;
    id_v.major       = fmpp_pkg::VersionMajor;
    id_v.minor       = fmpp_pkg::VersionMinor;
    config_v         = '0;
    config_v.wshift  = 8'(WShift);
    config_v.lanes   = 8'(fmpp_pkg::LaneW);
    config_v.qdepth  = 8'(fmpp_pkg::QueueDepth);
    config_v.words   = 8'(NumWords);
    config_v.blocks  = 32'(NumBlocks);
    status_v         = '0;
    status_v.any     = resp_any_i;
    status_v.ovf     = ovf_any_i;
    status_v.err     = err_sticky_i;
    error_v          = '0;
    error_v.addr     = err_addr_i;
    error_v.count    = err_count_i;
    error_v.cause    = err_cause_i;
    error_v.sticky   = err_sticky_i;
    ctrl_v           = '0;
    ctrl_v.gap       = gap_i;
    resp_v           = '0;
    resp_v.any       = resp_any_i;
    resp_v.first     = resp_first_i;
    resp_v.count     = resp_count_i;
    cycles_v         = '0;
    cycles_v.value   = cycles_i;
    instret_v        = '0;
    instret_v.value  = instret_i;
    mask_v           = '0;
    mask_v.value     = mask_i;
  end

  always_comb begin
    cause_o = fmpp_pkg::ERR_NONE;
    data_o  = '0;
    if (!aligned_i) begin
      cause_o = fmpp_pkg::ERR_ALIGN;
    end else if (is_reg_i) begin
      unique case (reg_i)
        fmpp_pkg::REG_ID[11:0]:      data_o = id_v;
        fmpp_pkg::REG_CONFIG[11:0]:  data_o = config_v;
        fmpp_pkg::REG_STATUS[11:0]:  data_o = status_v;
        fmpp_pkg::REG_ERROR[11:0]:   data_o = error_v;
        fmpp_pkg::REG_CTRL[11:0]:    data_o = ctrl_v;
        fmpp_pkg::REG_RESP[11:0]:    data_o = resp_v;
        fmpp_pkg::REG_CYCLES[11:0]:  data_o = cycles_v;
        fmpp_pkg::REG_INSTRET[11:0]: data_o = instret_v;
        fmpp_pkg::REG_MASK[11:0]:    data_o = mask_v;
        fmpp_pkg::REG_QUEUE[11:0]:   cause_o = fmpp_pkg::ERR_WRITEONLY;
        default:                     cause_o = fmpp_pkg::ERR_UNMAPPED;
      endcase
    end else if (is_window_i) begin
      data_o = rd_data_i;
    end else begin
      cause_o = fmpp_pkg::ERR_UNMAPPED;
    end
  end

endmodule
