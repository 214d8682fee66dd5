"""tools/asic_chip.py's runs of the standard-cell tools: yosys onto the OSU 0.18 um cells,
qflow's blifFanout until it settles, and OpenSTA with a script of the caller's checks.

The synthesis and buffering are tools/asic.sh's (the same yosys mapping, the same
blifFanout options and rounds); the top and its parameters and the RTL files are the
caller's, so that a tile alone and the array with stand-in tiles go through one flow.
"""
import os
import re
import subprocess

TECH = os.environ.get("ASIC_TECH", "/usr/share/qflow/tech/osu018")
LIB = os.path.join(TECH, "osu018_stdcells.lib")
LEF = os.path.join(TECH, "osu018_stdcells.lef")
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


def synth(out, name, top, params, sources):
    """yosys: sources onto the library, flattened; writes out/name.blif and name.stat."""
    chparam = " ".join(f"-set {k} {v}" for k, v in params.items())
    ys = os.path.join(out, name + ".ys")
    with open(ys, "w") as f:
        f.write(f"""read_liberty -lib {LIB}
read_verilog -sv {' '.join(sources)}
chparam {chparam} {top}
synth -top {top} -flatten
dfflegalize -cell $_DFF_P_ x
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


def sta(out, name, top, body, verilog=None, clock_port="clk_i"):
    """OpenSTA on out/name.v (or verilog) with a PERIOD clock on clock_port (virtual if None)
    and `body` after it."""
    tcl = os.path.join(out, f"{name}.chip.tcl")
    log = os.path.join(out, f"{name}.chip.log")
    with open(tcl, "w") as f:
        f.write(f"read_liberty {LIB}\nread_verilog {verilog or os.path.join(out, name + '.v')}\nlink_design {top}\n"
                f"create_clock -name clk -period {PERIOD} {f'[get_ports {clock_port}]' if clock_port else ''}\n{body}\n")
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
    type min, the hold slack), start and end (OpenSTA's names), start_port (the path starts
    at an input port), clk_q (the launching flip-flop's clock-to-Q, 0 from a port) and
    setup (the capturing flip-flop's setup time, 0 at a port)."""
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
        res[label] = {"ns": float(m.group(1)) if hold else PERIOD - float(m.group(1)),
                      "start": sp.group(1), "end": ep.group(1), "start_port": "input port" in sp.group(2),
                      "clk_q": float(cq.group(1)) if cq else 0.0, "setup": -float(su.group(1)) if su else 0.0}
    return res
