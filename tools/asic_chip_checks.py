"""The OpenSTA checks of tools/asic_chip.py: which paths it times in each netlist.

Each check prints `=== label` before its report_checks, and asic_chip_flow.checks reads
them back. A path's figure is PERIOD - slack: for a path that ends at a flip-flop it
includes that flip-flop's setup time, for one that starts at a flip-flop its clock-to-Q.
"""

# A Tcl helper: the flip-flops (the OSU cell) whose Q drives a net matching a pattern.
FLOPS_TCL = """proc flops {pat} {
  set r {}
  foreach n [get_nets -quiet $pat] {
    foreach p [get_pins -quiet -of_objects $n] {
      if {[get_property $p direction] == "output"} {
        set c [get_cells -of_objects $p]
        if {[get_property $c ref_name] == "DFFPOSX1"} { lappend r $c }
      }
    }
  }
  if {[llength $r] == 0} { error "no flip-flop drives a net $pat" }
  return $r
}
"""


PERIOD = 10.0  # asic_chip_flow.PERIOD


def check(label, args, kind="max"):
    return f'puts "=== {label}"\nreport_checks -path_delay {kind} -digits 3 {args}\n'


# fmpp_top's bus constraints, those of tools/asic.sh: inputs arrive 1 ns after the edge from
# a BUFX2, outputs are needed 1 ns before it and drive 0.05 pF.
BUS_CONSTRAINTS = """set data_in [delete_from_list [all_inputs] [get_ports clk_i]]
set_input_delay 1.0 -clock clk $data_in
set_driving_cell -lib_cell BUFX2 -pin Y $data_in
set_output_delay 1.0 -clock clk [all_outputs]
set_load 0.05 [all_outputs]
"""

# The tile's ports by role (the names of fmpp_tile.sv): the broadcast, the host's read request
# and the responder request (inputs); the responders' outputs.
BCAST_PORTS = ("opr_a_en_i", "opr_b_en_i", "a_i", "b_i", "opr_op_i", "opr_imm_i", "opr_shr_i", "fwd_a_i", "exec_i",
               "alu_op_i", "ws_sum_i", "ws_alu_i", "ws_writes_i", "ws_bitcopy_i", "ws_word_i", "kind_i", "op_i",
               "f_i", "f_nx_i", "d_i", "x_i", "imm_i", "mask_i", "wpl_i", "rk_i", "hw_block_i", "hw_lane_sel_i", "hw_strb_i", "hw_data_i")
RD_PORTS = ("rd_en_i", "rd_kind_i", "rd_block_i", "rd_word_i", "rd_flag_i")
RESP_OUT = ("sel_any_o", "sel_count_o", "sel_first_o", "ovf_any_o")

# fmpp_top with tools/asic/tile_stub.sv for every tile: the logic between the tiles, bit by
# bit of the tile's ports. Its registers are the stand-in's (`stub`, u_tile.q_*), the groups'
# (`grp`: the broadcast's stage-2 copies g_bc and the trees' group registers g_*_q), the
# tiles' stage-3 copies (`loc`: g_t3, which sit at their tile) and the rest (`core`: the bus
# slave, the queue, the sequencer, the trees' top). `to:P@S` is the
# worst path from S's registers (or `in`, the bus inputs) into the stand-in's flip-flops of
# port bit P (of any tile), `from:P@S` the worst out of them into S's. Bus inputs arrive 1 ns
# after the edge and outputs are needed 1 ns before it (asic.sh's constraints).
ARRAY_TCL = FLOPS_TCL + BUS_CONSTRAINTS + """set groups [dict create]
foreach n [get_nets -quiet *u_tile.q_*] {
  set key [regsub {^.*u_tile[.]q_} [get_full_name $n] {}]
  foreach p [get_pins -quiet -of_objects $n] {
    if {[get_property $p direction] == "output"} {
      set c [get_cells -of_objects $p]
      if {[get_property $c ref_name] == "DFFPOSX1"} { dict lappend groups $key $c }
    }
  }
}
if {[dict size $groups] == 0} { error "no stand-in flip-flop (u_tile.q_*) in the netlist" }
set stub {}
dict for {key cells} $groups { set stub [concat $stub $cells] }
set grp [flops {*u_array.g_bc* *u_array.g_any_q* *u_array.g_count_q* *u_array.g_first_q* *u_array.g_ovf_q*
                *u_array.g_flag_q*}]
set loc [flops *u_array.g_t3*]
# A stage-3 copy whose only load is one tile's input port loses its name: yosys names its net
# after the port (u_array.g_tile[N].u_tile.<port>). A flip-flop driving such a net whose
# loads are all stand-in flip-flops of that one tile (u_tile.q_*) sits at its tile too.
foreach n [get_nets -quiet *u_array.g_tile*.u_tile.*] {
  if {[string match *u_tile.q_* [get_full_name $n]]} { continue }
  set drv {}
  set tiles [dict create]
  foreach p [get_pins -quiet -of_objects $n] {
    set c [get_cells -of_objects $p]
    if {[get_property $p direction] == "output"} {
      if {[get_property $c ref_name] == "DFFPOSX1"} { set drv $c }
    } else {
      foreach q [get_pins -quiet -of_objects $c -filter "direction == output"] {
        foreach m [get_nets -quiet -of_objects $q] {
          if {[regexp {u_array[.]g_tile.([0-9]+).[.]u_tile[.]q_} [get_full_name $m] -> k]} { dict set tiles $k 1 }
        }
      }
    }
  }
  if {$drv ne "" && [dict size $tiles] == 1} { lappend loc $drv }
}
set core [delete_from_list [delete_from_list [delete_from_list [all_registers] $stub] $grp] $loc]
set rdata [flops *s_axil_rdata_o*]
dict for {key cells} $groups {
  if {[string match *_o $key] || [string match {*_o\\[*} $key]} {
    foreach {tag dst} [list grp $grp core $core] {
      puts "=== from:$key@$tag"
      report_checks -path_delay max -digits 3 -from $cells -to $dst
    }
  } else {
    foreach {tag src} [list loc $loc grp $grp core $core in $data_in] {
      puts "=== to:$key@$tag"
      report_checks -path_delay max -digits 3 -from $src -to $cells
    }
  }
}
""" + "".join([
    check("core_grp", "-from $core -to $grp"),
    check("grp_loc", "-from $grp -to $loc"),
    check("grp_core", "-from $grp -to $core"),
    check("group", "-from $grp -to $grp"),
    check("central", "-from $core -to $core"),
    check("core_rdata", "-from $core -to $rdata"),
    check("io_rdata", "-from $data_in -to $rdata"),
    check("io_in", "-from $data_in"),
    check("io_out", "-to [all_outputs]"),
    check("hold", "-from [concat $core $grp $loc] -to [concat $core $grp $loc]", "min"),
])

# The word clock gates (asic_chip_flow.gating), when the netlist has them: the enables from
# the flip-flops into the gates' latches (a full clock: the latch closes at the rising edge),
# and the hold of the enable into the latch. The latch into the gate's AND is a clock gating
# check of half a clock, timed at the chip's own period (GATING_TCL).
GATE_TCL = """if {[llength $lat]} {
""" + "".join([
    check("gate_en", "-from $regs -to $lat"),
    check("gate_en_hold", "-to $lat", "min"),
]) + "}\n"


# The word clock gates' own check at a chip's period: each gate's latch into its AND (OpenSTA's
# clock gating check, half a clock), setup and hold; nothing without gates.
GATE_CLK_TCL = """set lat [all_registers -level_sensitive]
if {[llength $lat]} {
""" + check("gate_clk", "-from $lat") + check("gate_clk_hold", "-from $lat", "min") + "}\n"


# fmpp_tile alone, bit by bit of its ports, which arrive at the clock edge (from a BUFX2) and
# are needed at the next edge (loaded with a BUFX4's input): `from:P` is the worst path from
# input bit P into the tile's flip-flops, `to:P` the worst from a flip-flop to output bit P,
# `rd:P` and `resp:P` the worst from the read or responder request to output bit P.
TILE_TCL = """set data_in [delete_from_list [all_inputs] [get_ports clk_i]]
set_input_delay 0 -clock clk $data_in
set_driving_cell -lib_cell BUFX2 -pin Y $data_in
set_output_delay 0 -clock clk [all_outputs]
set_load %(load)s [all_outputs]
set regs [all_registers -edge_triggered]
set lat [all_registers -level_sensitive]
set ends [concat $regs [all_outputs]]
set rd_in [get_ports {rd_en_i rd_kind_i* rd_block_i* rd_word_i* rd_flag_i*}]
foreach p [get_ports {%(bcast)s flagop_any_i resp_en_i}] {
  puts "=== from:[get_full_name $p]"
  report_checks -path_delay max -digits 3 -from $p -to $ends
  if {[llength $lat]} {
    puts "=== latch:[get_full_name $p]"
    report_checks -path_delay max -digits 3 -from $p -to $lat
  }
}
# From the flip-flops to each output: with the inputs pushed a period early, no path from
# an input is the worst to an output (a flip-flop's is).
set_input_delay -%(period)s -clock clk $data_in
foreach p [all_outputs] {
  puts "=== to:[get_full_name $p]"
  report_checks -path_delay max -digits 3 -to $p
}
set_input_delay 0 -clock clk $data_in
foreach p [get_ports rd_data_o*] {
  puts "=== rd:[get_full_name $p]"
  report_checks -path_delay max -digits 3 -from $rd_in -to $p
}
foreach p [get_ports {sel_any_o sel_count_o* sel_first_o* ovf_any_o}] {
  puts "=== resp:[get_full_name $p]"
  report_checks -path_delay max -digits 3 -from [get_ports resp_en_i] -to $p
}
""".replace("%(bcast)s", " ".join(p if p.endswith("en_i") or p == "exec_i" else p + "*" for p in BCAST_PORTS)).replace(
    "%(period)s", str(PERIOD)) + "".join([
    check("internal", "-from $regs -to $regs"),
    check("hold", "-from $regs -to $regs", "min"),
]) + GATE_TCL


# fmpp_top as one flat netlist (the check of the composition): the worst path from flip-flop
# to flip-flop (or into a word's clock gate), the worst into the read-data register, and the worst from a bus input into it.
FLAT_TCL = FLOPS_TCL + BUS_CONSTRAINTS + """set regs [all_registers -edge_triggered]
set lat [all_registers -level_sensitive]
set rdata [flops *s_axil_rdata_o*]
""" + GATE_TCL + "".join([
    check("reg", "-from $regs -to $regs"),
    check("into_rdata", "-from $regs -to $rdata"),
    check("bus_into_rdata", "-from $data_in -to $rdata"),
])
