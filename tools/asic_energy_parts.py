"""The parts of a gate-level tile netlist, for its power by part (tools/asic_chip_energy.py).

A flattened netlist keeps the names of its registers (the flip-flops' Q nets) but not
which module a gate came from, so a gate is put in a part by where its signals go:

  - a flip-flop by its register: the words (mem_q), the flags (flag_q), the operand
    registers (opa, opb, cin: stage 3's A, addend and carry-in), or another register;
  - a gate of the clock's buffer tree (the tree blifFanout builds from the clock port, with
    the inverted clock that opens the gates' latches), a word's clock gate (its latch and
    AND: tools/asic/clock_gate_map.v) or a buffer of a gated clock's tree (the tree after a
    gate, which toggles only when its word is written);
  - a gate that no flip-flop reaches (its inputs come only from the tile's ports): the
    decoding and the fanout buffers of the broadcast instruction inside the tile;
  - every other gate by the registers and ports its output reaches: into the words only
    (the word write), into the flags only, into the operand registers only (the word
    read and the shifter), to the tile's output ports only (responders, read port, the
    "if any" OR), or into several of these (the ALU, whose result goes to a word and to
    C and V, and the write data forwarded into the operand registers).
"""
import os
import re

from asic_netlist import compile_cells, read_liberty, read_netlist

REGISTERS = (("words", r"^mem_q\b"), ("flags", r"^flag_q\b"), ("operand registers", r"^(opa|opb|cin)"))
SINKS = ("words", "flags", "operand registers", "ports")
CLOCK = "clock buffers"
GATES = "word clock gates"
GATED = "gated clock buffers"
BROADCAST = "broadcast decode and fanout"
OTHER_REG = "other registers"
SHARED = "logic into several of these (words/flags/operands/ports)"


def sink_part(mask):
    """The part of a gate whose output reaches the sinks of bit mask `mask`."""
    hit = [s for i, s in enumerate(SINKS) if mask >> i & 1]
    if len(hit) != 1:
        return SHARED
    return "logic to the tile's outputs" if hit[0] == "ports" else "logic into the " + hit[0]


def register_part(qnet):
    for part, pat in REGISTERS:
        if re.search(pat, qnet):
            return part + " (flip-flops)"
    return OTHER_REG


class Graph:
    """A gate-level netlist as a graph: its cells (instance, cell, {pin: net}) and their
    connections by instance, its flip-flops (instance, cell, D net, Q net), per net its
    driving gate and readers, per gate its input and output nets."""

    def __init__(self, netlist, liberty):
        lib = read_liberty(liberty)
        _, self.portbits, self.insts, self.find = read_netlist(netlist, lib)
        comb, self.seqs, fcache, _ = compile_cells(self.insts, lib)
        self.conns = conns = {name: c for name, _, c in self.insts}
        self.driver, self.readers, self.ins, self.outs = {}, {}, {}, {}
        for name, cell, o, net in comb:
            self.driver[net] = name
            self.outs.setdefault(name, []).append(net)
            self.ins[name] = [conns[name][p] for p in fcache[(cell, o)][0] if p in conns[name]]
            for n in self.ins[name]:
                self.readers.setdefault(n, set()).add(name)

    def forward(self, starts):
        """Gates reached from the nets `starts` through combinational gates."""
        seen, todo = set(), list(starts)
        while todo:
            for g in self.readers.get(todo.pop(), ()):
                if g not in seen:
                    seen.add(g)
                    todo.extend(self.outs[g])
        return seen

    def masks(self, sink_nets):
        """Per gate the bit mask of the groups of sink_nets (bit i: group i) its output reaches."""
        mask = {}
        for i, nets in enumerate(sink_nets):
            todo = [self.driver[n] for n in nets if n in self.driver]
            while todo:
                g = todo.pop()
                if mask.get(g, 0) >> i & 1:
                    continue
                mask[g] = mask.get(g, 0) | (1 << i)
                todo.extend(self.driver[n] for n in self.ins[g] if n in self.driver)
        return mask


def parts(netlist, liberty, clock="clk_i", gr=None):
    """{instance name: part} for every cell of the netlist (gr: its Graph, when made already)."""
    gr = gr or Graph(netlist, liberty)
    clock_gates = gr.forward([gr.find(clock)])
    # a gate with the clock and another input (a word's AND) and the latch before it; the
    # inverted clock that opens the latches runs every clock and stays with the clock buffers
    ands = {g for g in clock_gates if any(gr.driver.get(n) not in clock_gates and n != gr.find(clock) for n in gr.ins[g])}
    latches = {gr.driver[n] for g in ands for n in gr.ins[g] if gr.driver.get(n) not in clock_gates and n in gr.driver}
    gated = gr.forward([n for g in ands for n in gr.outs[g]])
    state_gates = gr.forward([q for _, _, _, q in gr.seqs])
    sink_nets = [[], [], [], [gr.find(p) for p, d in gr.portbits.items() if d == "output"]]
    part = {}
    for name, _, d, q in gr.seqs:
        part[name] = register_part(q)
        for i, s in enumerate(SINKS[:3]):
            if part[name].startswith(s):
                sink_nets[i].append(d)
    mask = gr.masks(sink_nets)
    for name in gr.outs:
        if name in ands or name in latches:
            part[name] = GATES
        elif name in gated:
            part[name] = GATED
        elif name in clock_gates:
            part[name] = CLOCK
        elif name not in state_gates:
            part[name] = BROADCAST
        else:
            part[name] = sink_part(mask.get(name, 0))
    return part


def island(gr, qpat):
    """The flip-flops whose Q net matches the regex qpat, and the gates that only join them to
    one another (fed by them and reaching no other flip-flop): a stand-in's cells (gr: the
    netlist's Graph)."""
    pat = re.compile(qpat)
    flops = {name for name, _, _, q in gr.seqs if pat.match(q)}
    fwd = gr.forward([q for name, _, _, q in gr.seqs if name in flops])
    masks = gr.masks([[d for name, _, d, _ in gr.seqs if name in flops],
                      [d for name, _, d, _ in gr.seqs if name not in flops]])
    return flops | {g for g in fwd if masks.get(g, 0) == 1}


def by_part(part, power):
    """{part: [internal, switching, leakage, total, cells]} summed over the instances."""
    sums = {}
    for inst, p in power.items():
        s = sums.setdefault(part.get(inst, "unattributed"), [0.0, 0.0, 0.0, 0.0, 0])
        for i in range(4):
            s[i] += p[i]
        s[4] += 1
    return sums


# A made-up library and netlist with a gate of every kind of part, for self_test.
LIB_TEXT = """library (t) {
cell (BUFX2) { pin (A) { direction : input; } pin (Y) { direction : output; function : "A"; } }
cell (AND2X2) { pin (A) { direction : input; } pin (B) { direction : input; }
  pin (Y) { direction : output; function : "(A B)"; } }
cell (DFFPOSX1) { ff (DS0000,P0000) { next_state : "D"; clocked_on : "CLK"; }
  pin (CLK) { direction : input; } pin (D) { direction : input; } pin (Q) { direction : output; function : "DS0000"; } }
cell (INVX1) { pin (A) { direction : input; } pin (Y) { direction : output; function : "!A"; } }
cell (LATCH) { latch (DS0000,P0000) { data_in : "D"; enable : "CLK"; }
  pin (CLK) { direction : input; } pin (D) { direction : input; } pin (Q) { direction : output; function : "DS0000"; } }
}
"""
NETLIST_TEXT = """module t (clk_i, a_i, y_o);
input clk_i;
input a_i;
output y_o;
BUFX2 g_clk (.A(clk_i), .Y(ck));
BUFX2 g_in (.A(a_i), .Y(ad));
DFFPOSX1 r_w (.CLK(ck), .D(m), .Q(mem_q));
DFFPOSX1 r_f (.CLK(ck), .D(f), .Q(flag_q));
AND2X2 g_w (.A(ad), .B(flag_q), .Y(m));
AND2X2 g_x (.A(mem_q), .B(ad), .Y(x));
BUFX2 g_f (.A(x), .Y(f));
AND2X2 g_o (.A(x), .B(mem_q), .Y(y_o));
INVX1 g_ckn (.A(clk_i), .Y(ckn));
LATCH g_lat (.CLK(ckn), .D(ad), .Q(en));
AND2X2 g_gate (.A(clk_i), .B(en), .Y(gck));
BUFX2 g_gbuf (.A(gck), .Y(gck2));
DFFPOSX1 r_g (.CLK(gck2), .D(m), .Q(held));
endmodule
"""


def self_test():
    """Errors of parts() on a made-up netlist with one gate of each kind (none when it works)."""
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        lib, net = os.path.join(d, "t.lib"), os.path.join(d, "t.v")
        with open(lib, "w") as f:
            f.write(LIB_TEXT)
        with open(net, "w") as f:
            f.write(NETLIST_TEXT)
        got = parts(net, lib)
    want = {"g_clk": CLOCK, "g_in": BROADCAST, "r_w": "words (flip-flops)", "r_f": "flags (flip-flops)",
            "g_w": "logic into the words", "g_x": SHARED, "g_f": "logic into the flags",
            "g_o": "logic to the tile's outputs", "g_ckn": CLOCK, "g_lat": GATES, "g_gate": GATES, "g_gbuf": GATED,
            "r_g": OTHER_REG}
    return [f"part of {k}: {got.get(k)!r}" for k, v in want.items() if got.get(k) != v]
