"""The netlist side of tools/asic_activity.py: the Liberty cells' logic functions
compiled to Python, the yosys netlist, its gates in topological order, the clock's nets
(the simulation's trace of register values: tools/asic_trace.py).
"""
import re
import sys


class Fail(Exception):
    pass


# --- Liberty: cell pins, functions, sequential cells -----------------------------------

def braces(text, start):
    """Index just past the block opened by the first '{' at or after start."""
    i = text.index("{", start)
    depth = 0
    for j in range(i, len(text)):
        if text[j] == "{":
            depth += 1
        elif text[j] == "}":
            depth -= 1
            if depth == 0:
                return j + 1
    raise Fail("unbalanced braces in the Liberty file")


def read_liberty(path):
    text = open(path).read()
    cells = {}
    for m in re.finditer(r"\bcell\s*\(\s*\"?(\w+)\"?\s*\)", text):
        body = text[m.end():braces(text, m.end())]
        pins = {}
        for pm in re.finditer(r"\bpin\s*\(\s*\"?(\w+)\"?\s*\)", body):
            pb = body[pm.end():braces(body, pm.end())]
            d = re.search(r"direction\s*:\s*(\w+)", pb)
            f = re.search(r"\bfunction\s*:\s*\"([^\"]*)\"", pb)
            pins[pm.group(1)] = (d.group(1) if d else "", f.group(1) if f else None)
        seq = None
        ff = re.search(r"\bff\s*\(\s*\"?(\w+)\"?\s*,\s*\"?(\w+)\"?\s*\)", body)
        if ff:
            nx = re.search(r"next_state\s*:\s*\"([^\"]*)\"", body)
            ck = re.search(r"clocked_on\s*:\s*\"([^\"]*)\"", body)
            seq = ("ff", ff.group(1), ff.group(2), nx.group(1) if nx else "", ck.group(1) if ck else "")
        if re.search(r"\blatch\s*\(", body):
            di = re.search(r"data_in\s*:\s*\"(\w+)\"", body)
            en = re.search(r"\benable\s*:\s*\"(\w+)\"", body)
            seq = ("latch", di.group(1) if di else "", en.group(1) if en else "")
        cells[m.group(1)] = {"pins": pins, "seq": seq}
    if not cells:
        raise Fail(f"{path}: no cells")
    return cells


def compile_function(expr, pins):
    """A Liberty boolean function as Python source over pin variables (ints) and mask M."""
    toks = re.findall(r"[A-Za-z_]\w*|[()!'^+|&*]|\S", expr)
    pos = 0

    def peek():
        return toks[pos] if pos < len(toks) else None

    def take():
        nonlocal pos
        if pos >= len(toks):
            raise Fail(f"function {expr!r} ends early")
        pos += 1
        return toks[pos - 1]

    def primary():
        t = take()
        if t == "(":
            v = orexpr()
            if take() != ")":
                raise Fail(f"bad function {expr!r}")
        elif t == "!":
            v = f"(M & ~{primary()})"
        elif t in ("0", "1"):
            v = "0" if t == "0" else "M"
        elif re.fullmatch(r"[A-Za-z_]\w*", t):
            if t not in pins:
                raise Fail(f"function {expr!r} names unknown pin {t}")
            v = "p_" + t
        else:
            raise Fail(f"bad token {t!r} in function {expr!r}")
        while peek() == "'":
            take()
            v = f"(M & ~{v})"
        return v

    def andexpr():
        v = primary()
        while peek() is not None and peek() not in (")", "+", "|", "^"):
            if peek() in ("&", "*"):
                take()
            v = f"({v} & {primary()})"
        return v

    def xorexpr():
        v = andexpr()
        while peek() == "^":
            take()
            v = f"({v} ^ {andexpr()})"
        return v

    def orexpr():
        v = xorexpr()
        while peek() in ("+", "|"):
            take()
            v = f"({v} | {xorexpr()})"
        return v

    src = orexpr()
    if pos != len(toks):
        raise Fail(f"bad function {expr!r}")
    return src


# --- the gate-level netlist (yosys write_verilog -noattr -noexpr) -----------------------

NAME = r"(\\\S+\s|[A-Za-z_][\w$]*)"


def norm(name):
    name = name.strip()
    return name[1:] if name.startswith("\\") else name


def read_netlist(path, lib):
    text = open(path).read()
    m = re.search(r"\bmodule\s+(\S+)\s*\(", text)
    if not m:
        raise Fail(f"{path}: no module")
    ports = {}
    for pm in re.finditer(r"^\s*(input|output)\s+(?:\[(\d+):(\d+)\]\s+)?" + NAME + r"\s*;", text, re.M):
        nm = norm(pm.group(4))
        if pm.group(2) is None:
            ports[nm] = (pm.group(1), None)
        else:
            hi, lo = int(pm.group(2)), int(pm.group(3))
            ports[nm] = (pm.group(1), (min(hi, lo), max(hi, lo)))
    # net references: `\esc name [3]`, `name [3]`, `name[3]`, `name`, constants
    ref = re.compile(r"\s*(?:(\d+)'h([0-9a-fA-Fx])|(\\\S+)\s*(\[\d+\])?|([A-Za-z_][\w$]*)\s*(\[\d+\])?)\s*")

    def net_of(s):
        r = ref.fullmatch(s)
        if not r:
            raise Fail(f"{path}: cannot read net reference {s!r}")
        if r.group(1):
            return "1'b" + r.group(2)
        base = norm(r.group(3)) if r.group(3) else r.group(5)
        idx = r.group(4) or r.group(6) or ""
        return base + idx

    alias = {}

    def find(n):
        while alias.get(n, n) != n:
            n = alias[n]
        return n
    for am in re.finditer(r"^\s*assign\s+(.+?)\s*=\s*(.+?)\s*;", text, re.M):
        a, b = net_of(am.group(1)), net_of(am.group(2))
        ra, rb = find(a), find(b)
        if ra != rb:
            # keep a constant or a port as the representative
            if rb.startswith("1'b") or ra.startswith("1'b"):
                alias[rb if ra.startswith("1'b") else ra] = ra if ra.startswith("1'b") else rb
            else:
                alias[ra] = rb
    insts = []
    for im in re.finditer(r"^\s*([A-Z]\w*)\s+(\\\S+\s|[\w$]+)\s*\((.*?)\);", text, re.M | re.S):
        cell = im.group(1)
        if cell not in lib:
            raise Fail(f"{path}: cell {cell} not in the Liberty file")
        conns = {}
        for cm in re.finditer(r"\.(\w+)\s*\(\s*([^()]*?)\s*\)", im.group(3)):
            if cm.group(2):
                conns[cm.group(1)] = find(net_of(cm.group(2)))
        insts.append((norm(im.group(2)), cell, conns))
    if not insts:
        raise Fail(f"{path}: no cell instances")
    portbits = {}
    for nm, (d, rng) in ports.items():
        bits = [nm] if rng is None else [f"{nm}[{i}]" for i in range(rng[0], rng[1] + 1)]
        for b in bits:
            portbits[b] = d
    return m.group(1), portbits, insts, find


# --- evaluation ------------------------------------------------------------------------


def compile_cells(insts, lib):
    """The netlist's cells with each output's Liberty function compiled once per cell type:
    (comb [(instance, cell, output pin, net)], seqs [(instance, cell, D net, Q net)],
    fcache {(cell, pin): (input pins, function)}, drivers {net: (instance, pin)})."""
    comb, seqs, fcache, drivers = [], [], {}, {}
    for name, cell, conns in insts:
        info = lib[cell]
        outs = [p for p, (d, f) in info["pins"].items() if d == "output"]
        if info["seq"] is not None and info["seq"][0] == "latch" and "Q" in conns:
            # A clock gate's latch (tools/asic/clock_gate_map.v), open while the clock is low:
            # its Q in a cycle is its D (the word's enable) of that cycle.
            key = (cell, "Q")
            if not info["seq"][1] or info["seq"][1] not in conns:
                raise Fail(f"{name}: latch without its data input")
            fcache[key] = ([info["seq"][1]], lambda M, d: d)
            comb.append((name, cell, "Q", conns["Q"]))
            drivers[conns["Q"]] = (name, "Q")
            continue
        if info["seq"] is not None:
            if info["seq"][0] != "ff" or info["seq"][4] != "CLK" or info["seq"][3] not in info["pins"]:
                raise Fail(f"{cell}: only positive-edge D flip-flops are simulated (got {info['seq']})")
            q = conns.get("Q")
            d = conns.get(info["seq"][3])
            if q is None or d is None:
                raise Fail(f"{name}: flip-flop without D or Q")
            seqs.append((name, cell, d, q))
            drivers[q] = (name, "Q")
            continue
        for o in outs:
            f = info["pins"][o][1]
            if f is None:
                raise Fail(f"{cell}.{o}: no function")
            key = (cell, o)
            if key not in fcache:
                ins = [p for p, (d, _) in info["pins"].items() if d == "input"]
                src = compile_function(f, ins)
                fcache[key] = (ins, eval("lambda M, " + ", ".join("p_" + p for p in ins) + ": " + src))
            if o in conns:
                comb.append((name, cell, o, conns[o]))
                drivers[conns[o]] = (name, o)
    return comb, seqs, fcache, drivers


def undriven_nets(comb, seqs, fcache, inst_conns, by_net, known, portbits, find):
    """Nets that no cell drives (yosys leaves a few: the pass-through buffers of a kept
    module's unused outputs, e.g. a carry level's p_o after its driver was removed as
    dead): (the nets sorted, how many dead cell outputs they reach). They are held at 0, which is right only if nothing that counts reads
    them: every cell they reach, directly or through other cells, must be dead (no
    flip-flop's D, no output port beyond it); else the netlist is broken and this fails."""
    readers = {}
    for name, cell, o, net in comb:
        for p in fcache[(cell, o)][0]:
            readers.setdefault(inst_conns[name][p], []).append(net)
    undriven = sorted(n for n in readers if n not in by_net and n not in known)
    reach, todo = set(undriven), list(undriven)
    while todo:
        for out in readers.get(todo.pop(), []):
            if out not in reach:
                reach.add(out)
                todo.append(out)
    live = {d for _, _, d, _ in seqs} | {find(p) for p, d in portbits.items() if d == "output"}
    hit = sorted(reach & live)
    if hit:
        raise Fail(f"undriven nets {undriven[:5]} reach flip-flops or outputs ({hit[:5]}): the netlist is broken")
    if undriven:
        print(f"{len(undriven)} undriven nets read only by {len(reach) - len(undriven)} dead cell outputs (held at 0): "
              + ", ".join(undriven[:8]) + (" ..." if len(undriven) > 8 else ""), file=sys.stderr)
    return undriven, len(reach) - len(undriven)


def comb_order(comb, fcache, inst_conns, known):
    """The combinational gates in topological order: [(net, function, input nets)]; known:
    the nets no gate drives (the registers' outputs, the input ports, constants)."""
    by_net = {net: (name, cell, o) for name, cell, o, net in comb}
    order, state, done = [], {}, set(known)
    for net0 in by_net:
        stack = [net0]
        while stack:
            net = stack[-1]
            if net in done:
                stack.pop()
                continue
            if net not in by_net:
                raise Fail(f"net {net} has no driver")
            name, cell, o = by_net[net]
            ins = [inst_conns[name][p] for p in fcache[(cell, o)][0]]
            pend = [n for n in ins if n not in done]
            if pend:
                if state.get(net) == 1:
                    raise Fail(f"combinational loop through {net}")
                state[net] = 1
                stack.extend(pend)
            else:
                done.add(net)
                order.append((net, fcache[(cell, o)][1], ins))
                stack.pop()
    return order


def clock_nets(order, clock):
    """The clock's nets (the clock port's net and every gate output it reaches through
    combinational gates; a latch's enable is not one of its inputs) and the gated clocks:
    [(net, function, inputs)] of the gates that have the clock and another signal (the word
    clock gates' ANDs), whose output carries a pulse only in some cycles; and per clock net
    the index of the gated clock it comes from (-1: the free-running clock)."""
    nets, gated, root = {clock}, [], {clock: -1}
    for net, fn, ins in order:
        ck = [i for i in ins if i in nets]
        if ck:
            nets.add(net)
            root[net] = root[ck[0]]
            if len(ck) < len(ins):
                root[net] = len(gated)
                gated.append((net, fn, ins))
    return nets, gated, root


def gated_pulses(gated, nets, val, M):
    """Per gated clock the cycles (bit t: cycle t) that end in a pulse: those where the gate's
    output follows the clock (differs between the clock at 1 and at 0), the other inputs at
    their values in val."""
    return [fn(M, *[M if i in nets else val[i] for i in ins]) ^ fn(M, *[0 if i in nets else val[i] for i in ins])
            for _, fn, ins in gated]


def gated_clock_tcl(gated, pulses, n_cyc, drivers, period):
    """OpenSTA Tcl that gives each gated clock its own rate: OpenSTA gives every pin of a clock
    network its clock's activity whatever activity is set on it, so the gate's output gets a
    clock of period / (its fraction of cycles with a pulse); one that never pulses, a period
    a billion times the clock's."""
    out = []
    for k, (net, _, _) in enumerate(gated):
        inst, pin = drivers[net]
        f = pulses[k] / n_cyc if n_cyc else 0.0
        out.append(f"create_clock -name gated_{k} -period {period / f if f else period * 1e9:.6g} "
                   f"[get_pins {{{inst}/{pin}}}]\n")
    return "".join(out)

