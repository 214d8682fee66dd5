"""tools/asic_chip.py's runs of the standard-cell tools: yosys onto the OSU 0.18 um cells,
qflow's blifFanout until it settles, and OpenSTA with a script of the caller's checks.

The synthesis and buffering are tools/asic.sh's (the same yosys mapping, the same
blifFanout options and rounds); the top and its parameters and the RTL files are the
caller's, so that a tile alone and the array with stand-in tiles go through one flow.
"""
import os
import re
import subprocess

from asic_common import LEF, LIB, TECH  # noqa: F401 (the flow's library, for its callers too)
QBIN = os.environ.get("QFLOW_BIN", "/usr/lib/qflow/bin")
FANOUT_OPTS = os.environ.get("ASIC_FANOUT_OPTS", "-l 100 -c 20").split()
FANOUT_MAX = 20
PERIOD = 10.0  # ns: every check reports its path as PERIOD - slack


class FlowError(Exception):
    pass


def run(cmd, log):
    """Runs cmd (nice 10) with its output in log; FlowError with the log's end on failure."""
    with open(log, "w") as f:
        r = subprocess.run(["nice", "-n", "10"] + cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        with open(log) as f:
            tail = "".join(f.readlines()[-20:])
        raise FlowError(f"{' '.join(cmd[:2])} failed (exit {r.returncode}); end of {log}:\n{tail}")


GATE_MAP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "asic", "clock_gate_map.v")


def gating(out, name, storage):
    """The yosys lines that clock-gate the word storage: the enabled flip-flops whose Q drives
    a wire of the pattern `storage` get one clock gate per enable (tools/asic/clock_gate_map.v);
    their number goes to out/name.storage.count (storage_count reads it)."""
    if not storage:
        return ""
    return (f"select -set storage w:{storage} %ci1:+$_DFFE_PP_[Q] t:$_DFFE_PP_ %i\n"
            f"tee -o {out}/{name}.storage.count select -count @storage\n"
            f"techmap -map {GATE_MAP} @storage\nopt_merge -share_all\n")


def storage_count(out, name):
    """The number of storage flip-flops that synth() clock-gated (0 without gating)."""
    path = os.path.join(out, name + ".storage.count")
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        m = re.search(r"(\d+) objects", f.read())
    if not m:
        raise FlowError(f"{path}: no count of the storage flip-flops")
    return int(m.group(1))


def synth(out, name, top, params, sources, storage=None):
    """yosys: sources onto the library, flattened; writes out/name.blif and name.stat. With
    `storage` (a wire pattern) the word storage is clock-gated (gating())."""
    chparam = " ".join(f"-set {k} {v}" for k, v in params.items())
    ys = os.path.join(out, name + ".ys")
    count = os.path.join(out, name + ".storage.count")
    if os.path.exists(count):
        os.remove(count)
    with open(ys, "w") as f:
        f.write(f"""read_liberty -lib {LIB}
read_verilog -sv {' '.join(sources)}
chparam {chparam} {top}
synth -top {top} -flatten
{gating(out, name, storage)}dfflegalize -cell $_DFF_P_ x
dfflibmap -liberty {LIB}
abc -liberty {LIB}
setattr -mod -unset keep_hierarchy
flatten
setundef -zero
clean -purge
rename -top {top}
tee -o {out}/{name}.synth.stat stat -liberty {LIB}
write_blif -gates -buf BUFX2 A Y {out}/{name}.blif
""")
    run(["yosys", "-q", "-l", os.path.join(out, name + ".log"), "-s", ys], os.path.join(out, name + ".yosys.out"))


def fanout(out, name, top):
    """blifFanout until a round changes no gate, then the netlist as Verilog (out/name.v)."""
    base = os.path.join(out, name)
    with open(base + ".nofanout", "w") as f:
        f.write("gnd\nvdd\n")
    cur = base + ".blif"
    for i in range(1, FANOUT_MAX + 1):
        nxt = f"{base}.fanout{i % 2}.blif"
        log = f"{base}.fanout{i}.log"
        run([os.path.join(QBIN, "blifFanout")] + FANOUT_OPTS + ["-I", base + ".nofanout", "-p", LIB, "-b", "BUFX2,CLKBUF1",
                                                             "-i", "A,A", "-o", "Y,Y", cur, nxt], log)
        with open(log) as f:
            m = re.findall(r"^Number of gates changed: (\d+)$", f.read(), re.M)
        if not m:
            raise FlowError(f"{log}: blifFanout printed no 'Number of gates changed'")
        cur = nxt
        if int(m[-1]) == 0:
            break
    else:
        raise FlowError(f"blifFanout on {name} did not settle in {FANOUT_MAX} rounds")
    run(["yosys", "-q", "-p", f"read_liberty -lib {LIB}; read_blif -wideports {cur}; hierarchy -top {top}; "
         f"tee -o {base}.stat stat -liberty {LIB}; write_verilog -noattr -noexpr {base}.v"], base + ".netlist.log")
    return i


def sta(out, name, top, body, verilog=None, clock_port="clk_i", period=PERIOD):
    """OpenSTA on out/name.v (or verilog) with a clock of `period` ns on clock_port (virtual
    if None) and `body` after it."""
    tcl = os.path.join(out, f"{name}.chip.tcl")
    log = os.path.join(out, f"{name}.chip.log")
    with open(tcl, "w") as f:
        f.write(f"read_liberty {LIB}\nread_verilog {verilog or os.path.join(out, name + '.v')}\nlink_design {top}\n"
                f"create_clock -name clk -period {period} {f'[get_ports {clock_port}]' if clock_port else ''}\n{body}\n")
    run(["sta", "-no_init", "-no_splash", "-exit", tcl], log)
    with open(log) as f:
        text = f.read()
    if re.search(r"^Error", text, re.M):
        raise FlowError(f"{log}: OpenSTA reported an error")
    if 'puts "===' in body and "=== " not in text:
        raise FlowError(f"{log}: OpenSTA printed none of the script's reports (a Tcl error it did not report?)")
    return text


# --- reading OpenSTA's reports -------------------------------------------------------

def checks(text):
    """{label: path} of the reports that a script prints after `puts "=== label"` (a path
    per label, or none). A path is a dict: ns = PERIOD - slack (for a hold check, path
    type min, the hold slack; into a latch, its arrival plus the latch's setup), start and
    end (OpenSTA's names), start_port (the path starts at an input port), clk_q (the
    launching flip-flop's clock-to-Q, 0 from a port) and setup (the capturing flip-flop's
    setup time, 0 at a port)."""
    res = {}
    parts = re.split(r"^=== (\S+)\n", text, flags=re.M)
    for label, rep in zip(parts[1::2], parts[2::2]):
        m = re.search(r"^\s+(-?[\d.]+)\s+slack \((?:MET|VIOLATED)\)", rep, re.M)
        if not m:
            continue
        sp = re.search(r"^Startpoint: (\S+)(.*)$", rep, re.M)
        ep = re.search(r"^Endpoint: (\S+)", rep, re.M)
        cq = re.search(r"^\s+([\d.]+)\s+[\d.]+ [\^v] \S+/Q \(DFFPOSX1\)", rep, re.M)
        su = re.search(r"^\s+(-?[\d.]+)\s+[\d.]+\s+library setup time", rep, re.M)
        hold = re.search(r"^Path Type: min", rep, re.M) is not None
        ns = float(m.group(1)) if hold else PERIOD - float(m.group(1))
        if not hold and re.search(r"^Endpoint: \S+ \(positive level-sensitive latch", rep, re.M):
            # A latch open while the clock is low (a clock gate's) is checked against its
            # opening edge, with time borrowed up to its closing edge, the rising edge: the
            # path's figure is its arrival plus the latch's setup, as for a flip-flop.
            arr = re.search(r"^\s+(-?[\d.]+)\s+data arrival time", rep, re.M)
            ls = re.search(r"^library setup time\s+(-?[\d.]+)", rep, re.M)
            if not (arr and ls):
                raise FlowError(f"label {label}: a latch check without its arrival or setup time")
            ns = float(arr.group(1)) - float(ls.group(1))
        res[label] = {"ns": ns,
                      "start": sp.group(1), "end": ep.group(1), "start_port": "input port" in sp.group(2),
                      "clk_q": float(cq.group(1)) if cq else 0.0, "setup": -float(su.group(1)) if su else 0.0}
    return res
