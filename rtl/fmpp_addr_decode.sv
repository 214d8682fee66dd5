// fmpp_addr_decode: where a bus address points in the FMPP memory map.
//
// Used once for the write address and once for the read address. It only locates
// the target (register, flag plane, block flags, block word) and says whether that
// target exists on this machine; the access rules (read-only, strobes, legality)
// are applied by fmpp_axil_slave. Map: docs/generated/memory-map.md.
module fmpp_addr_decode #(
  parameter int unsigned NumBlocks = 64,
  parameter int unsigned NumWords  = 32
) (
  input  logic [fmpp_pkg::AddrW-1:0] addr_i,
  output logic                       aligned_o,
  output logic                       is_reg_o,     // register region (offset in reg_o)
  output logic [11:0]                reg_o,
  output logic                       is_plane_o,   // PLANES window, mapped
  output logic                       is_flags_o,   // FLAGS window, mapped
  output logic                       is_word_o,    // WORDS window, mapped
  output logic                       in_plane_o,   // PLANES window, mapped or not
  output logic                       in_flags_o,   // FLAGS window, mapped or not
  output logic [fmpp_pkg::BlockIdxW-1:0] block_o,  // block (FLAGS, WORDS) or tile (PLANES)
  output logic [fmpp_pkg::WordIdxW-1:0]  word_o,
  output logic [fmpp_pkg::FlagIdxW-1:0]  flag_o
);
  localparam int unsigned LaneW    = fmpp_pkg::LaneW;
  localparam int unsigned NumTiles = (NumBlocks + LaneW - 1) / LaneW;
  localparam int unsigned WIdxW    = $clog2(NumWords);   // NumWords is even, so >= 1
  localparam int unsigned BeatW    = $clog2(fmpp_pkg::DataW / 8);  // byte offset within a beat
  localparam int unsigned WShift   = BeatW + WIdxW;      // WORDS block stride = 2^WShift bytes
  localparam int unsigned AW       = fmpp_pkg::AddrW;
  localparam int unsigned FShift   = fmpp_pkg::WIN_PLANES_FLAG_SHIFT;  // PLANES: flag above, tile below
  localparam int unsigned BIW      = fmpp_pkg::BlockIdxW;
  localparam int unsigned WOW      = fmpp_pkg::WordIdxW;
  localparam int unsigned FIW      = fmpp_pkg::FlagIdxW;

  logic [AW-1:0] off_plane, off_flags, off_words;
  logic          in_plane, in_flags, in_words;
  logic [31:0]   plane_tile, flags_block, words_block, words_word;

  // A window whose size is a power of two and whose base is a multiple of it is found
  // by comparing the address bits above the size with the base's (a few LUT levels),
  // and its offset is the bits below; any other window by subtraction and comparison
  // (32-bit carry chains). The map's windows are all of the first kind; the second
  // keeps a moved map correct (tests/map).
  fmpp_window #(.Base(fmpp_pkg::WIN_PLANES_BASE), .Size(fmpp_pkg::WIN_PLANES_SIZE)) u_plane (
    .addr_i, .in_o(in_plane), .off_o(off_plane));
  fmpp_window #(.Base(fmpp_pkg::WIN_FLAGS_BASE), .Size(fmpp_pkg::WIN_FLAGS_SIZE)) u_flags (
    .addr_i, .in_o(in_flags), .off_o(off_flags));
  fmpp_window #(.Base(fmpp_pkg::WIN_WORDS_BASE), .Size(fmpp_pkg::WIN_WORDS_SIZE)) u_words (
    .addr_i, .in_o(in_words), .off_o(off_words));

  assign plane_tile  = 32'(off_plane[FShift-1:0]) >> BeatW;
  assign flags_block = off_flags >> BeatW;
  assign words_block = off_words >> WShift;
  logic [WOW-1:0] word_bits;  // the word slot, its bits past NumWords' index cleared
  assign word_bits   = off_words[BeatW +: WOW] & WOW'((1 << WIdxW) - 1);
  assign words_word  = 32'(word_bits);

  // x < N for the constant N, as "no bit from the K-th up" (K = ceil(log2 N)) and a compare
  // of the K bits below: LUTs, not the 32-bit carry chain of a wide compare (on the iCE40
  // that chain stood on the host read's path from the address to the read data).
  localparam int unsigned TK = (NumTiles > 1) ? $clog2(NumTiles) : 1;
  localparam int unsigned BK = (NumBlocks > 1) ? $clog2(NumBlocks) : 1;
  logic tile_ok, flags_ok, words_ok;
  assign tile_ok  = (plane_tile >> TK) == '0 && {1'b0, plane_tile[TK-1:0]} < (TK + 1)'(NumTiles);
  assign flags_ok = (flags_block >> BK) == '0 && {1'b0, flags_block[BK-1:0]} < (BK + 1)'(NumBlocks);
  assign words_ok = (words_block >> BK) == '0 && {1'b0, words_block[BK-1:0]} < (BK + 1)'(NumBlocks);

  assign aligned_o  = addr_i[BeatW-1:0] == '0;
  assign is_reg_o   = addr_i[AW-1:12] == '0;
  assign reg_o      = addr_i[11:0];
  assign is_plane_o = in_plane && tile_ok;
  assign is_flags_o = in_flags && flags_ok;
  assign is_word_o  = in_words && words_ok && {1'b0, word_bits} < (WOW + 1)'(NumWords);
  assign flag_o     = off_plane[FShift +: FIW];
  assign in_plane_o = in_plane;
  assign in_flags_o = in_flags;

  always_comb begin
    block_o = '0;
    word_o  = '0;
    if (in_plane) block_o = plane_tile[BIW-1:0];
    if (in_flags) block_o = flags_block[BIW-1:0];
    if (in_words) begin
      block_o = words_block[BIW-1:0];
      word_o  = words_word[WOW-1:0];
    end
  end

  logic unused_hi;
  assign unused_hi = ^{plane_tile[31:BIW], flags_block[31:BIW], words_block[31:BIW], words_word[31:WOW],
                       off_plane[AW-1:FShift+FIW], off_flags[BeatW-1:0], off_words[BeatW-1:0]};

endmodule
