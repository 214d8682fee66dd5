"""The RTL trace for tools/asic_activity.py: the values of the wanted signals at the end of
every clock cycle of an FST (read through fst2vcd).
"""
import subprocess

from asic_netlist import Fail


def vcd_stream(fst):
    p = subprocess.Popen(["fst2vcd", fst], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, bufsize=1 << 20)
    return p


class Trace:
    """Values at the end of every cycle of the wanted signals (full names, '.'-joined)."""

    def __init__(self, fst, wanted, clock="TOP.clk_i"):
        self.proc = vcd_stream(fst)
        f = self.proc.stdout
        scope, ids, widths = [], {}, {}
        clk_id = None
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "$scope":
                scope.append(t[2])
            elif t[0] == "$upscope":
                scope.pop()
            elif t[0] == "$var":
                full = ".".join(scope + [t[4]])
                if full == clock:
                    clk_id = t[3]
                if full in wanted:
                    ids.setdefault(t[3], []).append(full)
                    widths[full] = int(t[2])
            elif t[0] == "$enddefinitions":
                break
        missing = sorted(set(wanted) - set(widths))
        if clk_id is None:
            raise Fail(f"{fst}: no clock {clock}")
        self.missing, self.widths, self.ids, self.clk = missing, widths, ids, clk_id
        self.f = f
        self.cur = {i: 0 for i in ids}
        self.clkv = 0

    def cycles(self):
        """Yields {signal: int value} at the end of each cycle (before each rising edge)."""
        pending = []
        rose = False

        def flush():
            nonlocal rose
            if rose:
                yield {s: self.cur[i] for i, names in self.ids.items() for s in names}
            for i, v in pending:
                self.cur[i] = v
            pending.clear()
            rose = False
        for line in self.f:
            c = line[0]
            if c == "#":
                yield from flush()
            elif c == "b":
                val, ident = line[1:].split()
                if ident == self.clk:
                    continue
                if ident in self.cur:
                    pending.append((ident, int(val.replace("x", "0").replace("z", "0"), 2)))
            elif c in "01xz":
                ident = line[1:].strip()
                if ident == self.clk:
                    if c == "1" and self.clkv == 0:
                        rose = True
                    self.clkv = 1 if c == "1" else 0
                elif ident in self.cur:
                    pending.append((ident, 1 if c == "1" else 0))
        yield from flush()
        self.proc.wait()
