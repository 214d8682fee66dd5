#!/usr/bin/env python3
"""Runs the FMPP's formal properties with yosys and yosys-smtbmc (make formal).

Each property (an assertion labelled p_* in a harness of formal/ or in an `ifdef FORMAL`
block of rtl/) is checked alone: yosys keeps that one assertion (chformal), then
yosys-smtbmc runs a bounded model check from reset to the job's depth and, if that
passes, k-induction. The result per property is
  proved            BMC and k-induction both passed (holds at every depth),
  bounded to N      BMC passed to depth N, induction did not close at the tried k,
  failed at step S  a counterexample: a VCD trace (open it in GTKWave) is written.
Every job reads the whole RTL of rtl/fmpp.f (tools/rtl_files.py), the reference generated
from the map and its harness; yosys keeps the harness's hierarchy once per job (design.il)
and each property's run starts from that.
Jobs marked joint (the FIFO's scoreboard) need their invariants together: their
k-induction runs once over all of the job's assertions, which proves them all if it
passes. Jobs with engine "sat" (the pipelined array against the single-cycle one) are
bounded checks by yosys's own SAT solver (`sat -seq N`) from the all-zero state, all
assertions at once, and each cover point as an assertion of its negation
(-DSAT_COVER) that must fail. The cover statements (c_*) of each job are run too (each must be reached).

Usage: run_formal.py --root DIR --out DIR [--quick] [--jobs NAME,...]
"""
import argparse
import os
import re
import subprocess
import sys
import time

SOLVER = "z3"
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import rtl_files  # noqa: E402  (tools/rtl_files.py: the one RTL file list)
# Depth of the pipelined array's bounded check (time steps from reset). Step 0 is the
# reset; an entry popped in step 1 shows in the state of step 4, the one behind it (which
# may take an operand forwarded from it) in step 5: 6 steps is the least depth at which a
# forwarded result is compared. Depth 8 did not finish in 15 minutes (one block of 4 words).
PIPE_DEPTH = 6
PIPE_DEPTH_QUICK = 6
# The array against the ISA: (blocks, words, depth) per job.
ISA_SIZES = [(3, 4, 6), (65, 2, 4)]
ISA_SIZES_QUICK = [(2, 2, 6)]


def fpga_text(root):
    """The macros of the FPGA's text of the RTL: tools/fpga.sh's fpga_text line (one list,
    there; the lint and make sim-fpga read it too), with the indexed word reads it builds on."""
    with open(os.path.join(root, "tools", "fpga.sh"), encoding="utf-8") as f:
        m = re.search(r'^fpga_text="(.*)"$', f.read(), re.M)
    if not m:
        sys.exit("run_formal.py: no fpga_text=\"...\" line in tools/fpga.sh")
    return ["FMPP_INDEXED_READ"] + m.group(1).split()


def jobs(root, out, quick):
    frm = lambda n: os.path.join(root, "formal", n)
    rtl = rtl_files.files(root=root) + [os.path.join(out, "fmpp_instr_ref.sv")]
    js = []
    for words in ([10, 32] if quick else [2, 10, 16, 32, 64]):
        js.append(dict(name=f"instr_check_w{words}", top="fmpp_instr_check_formal",
                       src=rtl + [frm("fmpp_instr_check_formal.sv")],
                       params={"NumWords": words}, depth=1, kind=0, comb=True))
    js.append(dict(name="fifo_w8", top="fmpp_fifo_formal", src=rtl + [frm("fmpp_fifo_formal.sv")],
                   params={"Width": 8}, depth=12 if quick else 24, kind=3, joint=True))
    js.append(dict(name="fifo_w95", top="fmpp_fifo_formal", src=rtl + [frm("fmpp_fifo_formal.sv")],
                   params={"Width": 95}, depth=4 if quick else 8, kind=3, joint=True))
    # The ALU's adder, subtracter and compare against `+` and `-` (combinational: a proof).
    # Three times: the adder as standard-cell synthesis reads it (the prefix network, modules
    # per level), as the FPGA flow reads it (a `+` per lane, for the carry chain) and as
    # simulators read it (a ripple in the case; rtl/fmpp_alu_exec.sv says why three texts).
    for name, defines in (("alu_l2", []), ("alu_l2_chain", ["FMPP_CARRY_CHAIN_ADDER"]),
                          ("alu_l2_ripple", ["FMPP_RIPPLE_ADDER"])):
        js.append(dict(name=name, top="fmpp_alu_formal", src=rtl + [frm("fmpp_alu_formal.sv")],
                       params={"Lanes": 2}, depth=1, engine="sat", comb=True, defines=defines))
    # The counters' increment (CYCLES, INSTRET) against `+ 1` (combinational: a proof).
    js.append(dict(name="incr_64", top="fmpp_incr_formal", src=rtl + [frm("fmpp_incr_formal.sv")],
                   params={"W": 64}, depth=1, engine="sat", comb=True))
    # The pipelined array against the single-cycle one: a bounded check with yosys's SAT
    # solver (z3 does not get through the bit-plane ALU's definitions; no induction).
    js.append(dict(name="pipe_1x4", top="fmpp_pipe_formal",
                   src=rtl + [frm("fmpp_array_sc.sv"), frm("fmpp_tile_sc.sv"), frm("fmpp_pipe_formal.sv")], params={"NumBlocks": 1, "NumWords": 4},
                   depth=PIPE_DEPTH_QUICK if quick else PIPE_DEPTH, engine="sat"))
    # The tile's word reads have two texts (rtl/fmpp_tile.sv): the AND-OR of a one-hot select
    # (above) and the indexed one of simulators and the FPGA flow (FMPP_INDEXED_READ).
    if not quick:
        js.append(dict(js[-1], name="pipe_1x4_indexed", defines=["FMPP_INDEXED_READ"]))
        js.append(dict(js[-1], name="pipe_1x4_bram", defines=fpga_text(root)))
    # The pipelined array against the instruction set (fmpp_isa_ref.sv, word by word from
    # docs/isa.md): several lanes of one tile, and two tiles (65 blocks: the 64-lane tile
    # and a partial one), so that the networks between tiles are in the check.
    isa_src = rtl + [frm("fmpp_array_sc.sv"), frm("fmpp_tile_sc.sv"), frm("fmpp_isa_ref.sv"), frm("fmpp_pipe_formal.sv")]
    for blocks, words, depth in ISA_SIZES_QUICK if quick else ISA_SIZES:
        js.append(dict(name=f"isa_{blocks}x{words}", top="fmpp_pipe_formal", src=isa_src,
                       params={"NumBlocks": blocks, "NumWords": words, "IsaRef": 1}, depth=depth, engine="sat"))
        if blocks == 3 and not quick:
            # The FPGA's words in block RAM (rtl/fmpp_tile.sv, FMPP_BRAM_WORDS: reads a clock ahead).
            js.append(dict(js[-1], name=f"isa_{blocks}x{words}_bram", defines=fpga_text(root)))
    for blocks, words in ([(100, 10)] if quick else [(100, 10), (64, 32), (1, 2)]):
        js.append(dict(name=f"axil_slave_{blocks}x{words}", top="fmpp_axil_slave_formal",
                       src=rtl + [frm("fmpp_axil_slave_formal.sv")],
                       params={"NumBlocks": blocks, "NumWords": words}, depth=6 if quick else 12, kind=4))
    return js


def yosys(job, keep, mode, smt2, log):
    """Mode 'list': reads the sources, keeps the job's flattened hierarchy in job['il'] and
    lists its assertions and covers into smt2. The other modes start from job['il'] and
    write smt2 with only assertion `keep` ('assert'), only the covers ('cover') or every
    assertion ('all')."""
    chp = "".join(f"chparam -set {k} {v} {job['top']}; " for k, v in job["params"].items())
    if mode == "assert":
        sel = f"chformal -assert -remove t:$assert n:{keep} %d; chformal -cover -remove; "
    elif mode == "cover":
        sel = "chformal -assert -remove; "
    elif mode == "all":
        sel = "chformal -cover -remove; "
    else:
        sel = ""
    script = f"read_rtlil {job['il']}; {sel}opt -fast; dffunmap; write_smt2 -wires {smt2}"
    if mode == "list":
        script = (f"read_verilog -DSYNTHESIS -sv -formal {' '.join(job['src'])}; {chp}prep -top {job['top']}; setattr -mod -unset keep_hierarchy; "
                  f"flatten; write_rtlil {job['il']}; tee -q -o {smt2} select -list t:$assert t:$cover")
    r = subprocess.run(["yosys", "-q", "-l", log, "-p", script], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"run_formal.py: yosys failed for job {job['name']} (log: {log}):\n{r.stderr[-2000:]}")


def smtbmc(args, timeout):
    t0 = time.time()
    try:
        r = subprocess.run(["yosys-smtbmc", "-s", SOLVER] + args, capture_output=True, text=True, timeout=timeout)
        text = r.stdout.replace("\r", "\n")
        status = "PASSED" if "Status: PASSED" in text else "FAILED" if "Status: FAILED" in text else "ERROR"
    except subprocess.TimeoutExpired:
        text, status = "", "TIMEOUT"
    return status, text, time.time() - t0


def run_joint(job, jdir, props, timeout, counts):
    """All of a job's assertions at once: BMC, then k-induction over them together."""
    smt2 = os.path.join(jdir, "all.smt2")
    yosys(job, None, "all", smt2, os.path.join(jdir, "all.yosys.log"))
    vcd = os.path.join(jdir, "all.vcd")
    st, text, secs = smtbmc(["-t", str(job["depth"]), "--dump-vcd", vcd, smt2], timeout)
    failed = set(re.findall(r"Assert failed in \S+: (\S+)", text))
    step = re.findall(r"Checking assertions in step (\d+)", text)
    proved = False
    if st == "PASSED":
        st2, _, secs2 = smtbmc(["-i", "-t", str(job["kind"]), smt2], timeout)
        proved = st2 == "PASSED"
        secs += secs2
    for p in props:
        if st != "PASSED":
            if p in failed or (not failed and st != "FAILED"):
                res = f"FAILED at step {step[-1] if step else '?'}: counterexample {os.path.relpath(vcd)}"
                counts["failed"] += 1
            else:
                res = f"bounded to depth {int(step[-1]) if step else 0} (the joint run stopped at another failure)"
                counts["bounded"] += 1
        elif proved:
            res = f"proved (joint BMC depth {job['depth']} and k-induction k={job['kind']}; {secs:.1f} s for all)"
            counts["proved"] += 1
        else:
            res = f"bounded to depth {job['depth']} (joint induction k={job['kind']} did not close)"
            counts["bounded"] += 1
        print(f"{job['name']:<22} {p:<22} {res}", flush=True)


def sat_run(job, jdir, name, keep, cover, timeout):
    """yosys sat -seq depth from the all-zero state: (status, seconds); status SUCCESS when no
    assertion (of `keep` only, if given) can fail within the depth, FAIL when one can."""
    chp = "".join(f"chparam -set {k} {v} {job['top']}; " for k, v in job["params"].items())
    sel = f"chformal -assert -remove t:$assert n:{keep} %d; " if keep else ""
    vcd = os.path.join(jdir, f"{name}.vcd")
    defs = "".join(f"-D{d} " for d in job.get("defines", []))
    script = (f"read_verilog -DSYNTHESIS {defs}{'-DSAT_COVER ' if cover else ''}-sv -formal {' '.join(job['src'])}; "
              f"{chp}prep -top {job['top']}; setattr -mod -unset keep_hierarchy; flatten; memory_map; opt -fast; chformal -cover -remove; {sel}"
              f"opt -fast; dffunmap; sat -seq {job['depth']} -prove-asserts -set-assumes -set-init-zero "
              f"-dump_vcd {vcd}")
    log = os.path.join(jdir, f"{name}.sat.log")
    t0 = time.time()
    try:
        subprocess.run(["yosys", "-q", "-l", log, "-p", script], capture_output=True, text=True, timeout=timeout)
        text = open(log).read()
        status = "SUCCESS" if "no model found: SUCCESS" in text else "FAIL" if "model found: FAIL" in text else "ERROR"
    except subprocess.TimeoutExpired:
        status = "TIMEOUT"
    return status, time.time() - t0, vcd


def run_sat(job, jdir, props, covers, timeout, counts):
    st, secs, vcd = sat_run(job, jdir, "all", None, False, timeout)
    for p in props:
        if st == "SUCCESS" and job.get("comb"):
            res = f"proved (combinational: one step covers every input; yosys sat, {secs:.1f} s)"
            counts["proved"] += 1
        elif st == "SUCCESS":
            res = f"bounded to depth {job['depth']} (yosys sat, all assertions together; {secs:.1f} s)"
            counts["bounded"] += 1
        elif st == "FAIL":
            res = f"FAILED within depth {job['depth']}: counterexample {os.path.relpath(vcd)} (all assertions together)"
            counts["failed"] += 1
        else:
            res = f"FAILED: yosys sat {st.lower()} after {secs:.0f} s"
            counts["failed"] += 1
        print(f"{job['name']:<22} {p:<22} {res}", flush=True)
    for c in covers:
        st, secs, _ = sat_run(job, jdir, c, c, True, timeout)
        hit = st == "FAIL"
        counts["covered" if hit else "uncovered"] += 1
        print(f"{job['name']:<22} {c:<22} {'covered' if hit else 'NOT COVERED within depth ' + str(job['depth'])}",
              flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--quick", action="store_true", help="modest depths (CI)")
    ap.add_argument("--jobs", default="", help="comma-separated job names (default: all)")
    ap.add_argument("--timeout", type=int, default=600, help="seconds per solver run")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    r = subprocess.run([sys.executable, os.path.join(a.root, "formal", "gen_instr_ref.py"), "--map",
                        os.path.join(a.root, "rtl", "fmpp_map.json"), "--out", os.path.join(a.out, "fmpp_instr_ref.sv")])
    if r.returncode != 0:
        sys.exit(r.returncode)
    selected = [j for j in jobs(a.root, a.out, a.quick) if not a.jobs or j["name"] in a.jobs.split(",")]
    if not selected:
        sys.exit(f"run_formal.py: no job matches '{a.jobs}'")
    counts = {"proved": 0, "bounded": 0, "failed": 0, "covered": 0, "uncovered": 0}
    t_all = time.time()
    print(f"{'job':<22} {'property':<22} result")
    for job in selected:
        jdir = os.path.join(a.out, job["name"])
        os.makedirs(jdir, exist_ok=True)
        lst = os.path.join(jdir, "list.txt")
        job["il"] = os.path.join(jdir, "design.il")
        yosys(job, None, "list", lst, os.path.join(jdir, "list.log"))
        names = [l.strip().split("/")[-1] for l in open(lst) if l.strip()]
        # Flattened cells keep their instance path (u_fifo.p_level_bound).
        props = [n for n in names if n.split(".")[-1].startswith("p_")]
        covers = [n for n in names if n.split(".")[-1].startswith("c_")]
        if not props:
            sys.exit(f"run_formal.py: job {job['name']} has no p_* assertion")
        if job.get("engine") == "sat":
            run_sat(job, jdir, props, covers, a.timeout, counts)
            continue
        if job.get("joint"):
            run_joint(job, jdir, props, a.timeout, counts)
            props = []
        for p in props:
            smt2 = os.path.join(jdir, f"{p}.smt2")
            yosys(job, p, "assert", smt2, os.path.join(jdir, f"{p}.yosys.log"))
            vcd = os.path.join(jdir, f"{p}.vcd")
            st, text, secs = smtbmc(["-t", str(job["depth"]), "--dump-vcd", vcd, smt2], a.timeout)
            if st == "FAILED":
                step = re.findall(r"Checking assertions in step (\d+)", text)
                res = f"FAILED at step {step[-1] if step else '?'}: counterexample {os.path.relpath(vcd)}"
                counts["failed"] += 1
            elif st != "PASSED":
                res = f"FAILED: solver {st.lower()} in BMC after {secs:.0f} s"
                counts["failed"] += 1
            elif job.get("comb"):
                res = f"proved (combinational: one step covers every input; {secs:.1f} s)"
                counts["proved"] += 1
            else:
                st2, text2, secs2 = smtbmc(["-i", "-t", str(job["kind"]), smt2], a.timeout)
                if st2 == "PASSED":
                    res = f"proved (BMC depth {job['depth']}, k-induction k={job['kind']}; {secs + secs2:.1f} s)"
                    counts["proved"] += 1
                else:
                    res = f"bounded to depth {job['depth']} (induction k={job['kind']} did not close; {secs + secs2:.1f} s)"
                    counts["bounded"] += 1
            print(f"{job['name']:<22} {p:<22} {res}", flush=True)
        if covers:
            smt2 = os.path.join(jdir, "covers.smt2")
            yosys(job, None, "cover", smt2, os.path.join(jdir, "covers.yosys.log"))
            st, text, secs = smtbmc(["-c", "-t", str(max(job["depth"], 2)), smt2], a.timeout)
            reached = set(re.findall(r"Reached cover statement at (\S+)", text))
            for c in covers:
                hit = any(x.rstrip(".").endswith(c) for x in reached)
                counts["covered" if hit else "uncovered"] += 1
                print(f"{job['name']:<22} {c:<22} {'covered' if hit else 'NOT COVERED within depth ' + str(job['depth'])}",
                      flush=True)
    print(f"formal: {counts['proved']} proved, {counts['bounded']} bounded, {counts['failed']} failed; "
          f"covers {counts['covered']} reached, {counts['uncovered']} not; {time.time() - t_all:.0f} s")
    print(f"{counts['proved'] + counts['bounded'] + counts['covered']} passed, {counts['failed'] + counts['uncovered']} failed")
    return 1 if counts["failed"] or counts["uncovered"] else 0


if __name__ == "__main__":
    sys.exit(main())
