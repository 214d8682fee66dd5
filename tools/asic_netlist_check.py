"""The checks of tools/asic_netlist.py's simulation helpers on made-up cells (run by
tools/asic_activity.py --self-test, a ctest): each returns its errors, none when it works."""
from asic_netlist import Fail, clock_nets, compile_function, gated_clock_tcl, gated_pulses


def functions_errors():
    """The Liberty function compiler against truth tables (every OSU018 function form)."""
    errs = []
    cases = {
        "(A B)": lambda a, b, c, d: a & b,
        "(!((A B)+C))": lambda a, b, c, d: 1 - ((a & b) | c),
        "(!((A B)+(C D)))": lambda a, b, c, d: 1 - ((a & b) | (c & d)),
        "(!((A+B) C))": lambda a, b, c, d: 1 - ((a | b) & c),
        "(A^B)": lambda a, b, c, d: a ^ b,
        "(!(A^B))": lambda a, b, c, d: 1 - (a ^ b),
        "A'": lambda a, b, c, d: 1 - a,
        "(!A)": lambda a, b, c, d: 1 - a,
        "((A & !B) | (B * C))": lambda a, b, c, d: (a & (1 - b)) | (b & c),
        "(!(A B C))": lambda a, b, c, d: 1 - (a & b & c),
        "(!((A+B)+C))": lambda a, b, c, d: 1 - (a | b | c),
    }
    # all 16 input combinations at once: bit t of each pin's integer is row t
    pins = {p: sum(((t >> i) & 1) << t for t in range(16)) for i, p in enumerate("ABCD")}
    for expr, ref in cases.items():
        fn = eval("lambda M, p_A, p_B, p_C, p_D: " + compile_function(expr, "ABCD"))
        got = fn(0xFFFF, pins["A"], pins["B"], pins["C"], pins["D"])
        want = sum(ref((t >> 0) & 1, (t >> 1) & 1, (t >> 2) & 1, (t >> 3) & 1) << t for t in range(16))
        if got != want:
            errs.append(f"{expr!r} gives {got:#06x}, not {want:#06x}")
    for bad in ("(A B", "A +", "(A $ B)"):
        try:
            compile_function(bad, "AB")
        except Fail:
            continue
        errs.append(f"{bad!r} was accepted")
    return errs


def gating_errors():
    """Errors of clock_nets, gated_pulses and gated_clock_tcl on a made-up clock gate."""
    order = [("ckn", lambda M, a: ~a & M, ["clk"]), ("g", lambda M, a, b: a & b, ["clk", "en"]),
             ("g2", lambda M, a: a, ["g"]), ("x", lambda M, a, b: a | b, ["en", "d"])]
    nets, gated, root = clock_nets(order, "clk")
    errs = []
    if nets != {"clk", "ckn", "g", "g2"} or [g[0] for g in gated] != ["g"] or root != {"clk": -1, "ckn": -1, "g": 0, "g2": 0}:
        errs.append(f"clock_nets: {sorted(nets)} {gated} {root}")
    if gated_pulses(gated, nets, {"en": 0b1010, "clk": 0}, 0b1111) != [0b1010]:
        errs.append("gated_pulses")
    tcl = gated_clock_tcl(gated, [2], 4, {"g": ("u1", "Y")}, 10.0)
    if tcl != "create_clock -name gated_0 -period 20 [get_pins {u1/Y}]\n" or "1e+10" not in gated_clock_tcl(
            gated, [0], 4, {"g": ("u1", "Y")}, 10.0):
        errs.append("gated_clock_tcl: " + tcl)
    return errs


def classify_errors(classify, res, unnamed, per_tile):
    """How tools/asic_activity.py finds the pipelined RTL's flip-flops (as yosys names them)
    in the trace: (its classify(register, *res) against the expected class of each name,
    the names checked)."""
    regs = {
        "u_array.g_tile[0].u_tile.mem_q[7]": "lane", "u_array.g_tile[0].u_tile.flag_q": "lane",
        "u_array.g_tile[0].u_tile.opa": "lane", "u_array.g_tile[0].u_tile.opb_q": "lane",
        "u_array.g_tile[0].u_tile.a_i": "name", "u_array.g_tile[0].u_tile.exec_i": "name",
        "u_array.g_tile[0].u_tile.cin_q": "name", "u_array.g_tile[0].u_tile.fa_idx": "name",
        "u_array.s2_x_q": "name", "u_queue.mem_q[3]": "name", "u_slave.u_err.ev_w_q": "name",
        "u_array.g_tile[0].u_tile.ovf_any_o": per_tile, "u_array.g_tile[0].u_tile.rd_data_o": per_tile,
        "_000216_": unnamed, "$auto$dff.cc:1": unnamed,
    }
    errs = [f"register {reg} is classed {classify(reg, *res)!r}, not {want!r}" for reg, want in regs.items()
            if classify(reg, *res) != want]
    return errs, len(regs)
