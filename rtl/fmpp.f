// The FMPP's RTL: one source file a line, in compile order (the package first), each
// path relative to this file. It is the only list of the RTL: the Verilated models
// (rtl/CMakeLists.txt), the per-module tests (tests/rtl_units), the lint, synthesis,
// the iCE40 and standard-cell flows, formal, coverage and the moved-map test all read it
// through tools/rtl_files.py. It is also a Verilator -F file (verilator -F rtl/fmpp.f).
//
// Directives, written as comments so that the file stays a plain list:
//   // top: MODULE       the top module of the synthesizable FMPP
//   // storage: PATTERN  a yosys wire pattern matching the registers that hold the blocks'
//                        words (the standard-cell flow maps them to latches in its storage
//                        variant)
//   FILE // sim          a simulation-only file (a checker, bound assertions, a
//                        composition only tests instantiate): Verilated, linted and read
//                        by formal, left out of synthesis (yosys, iCE40, standard cells)
// A new .sv file in rtl/ goes here; the lint fails while one is missing.
//
// top: fmpp_top
// storage: *.u_tile.mem_q*
fmpp_pkg.sv
fmpp_carry_level.sv
fmpp_and_level.sv
fmpp_incr.sv
fmpp_alu_addend.sv
fmpp_alu_exec.sv
fmpp_alu.sv // sim
fmpp_tile.sv
fmpp_fifo.sv
fmpp_instr_check.sv
fmpp_entry_use.sv
fmpp_window.sv
fmpp_addr_decode.sv
fmpp_err_reg.sv
fmpp_reg_read.sv
fmpp_axil_slave.sv
fmpp_array.sv
fmpp_top.sv
