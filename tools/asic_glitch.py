#!/usr/bin/env python3
"""Glitches: the transitions a zero-delay evaluation of a netlist does not count.

tools/asic_activity.py evaluates every gate once per clock from the registers' and ports'
new values (zero delay): a net changes at most once a clock. In silicon a gate's output
can change several times before it settles, as its inputs arrive at different times; each
extra pair of transitions costs energy like any other. This module estimates them with a
unit-delay model: every gate (buffers and inverters too) takes one time step. In each
clock the registers and input ports take their new values at step 0, every gate's output
at step k is its function of its inputs at step k - 1, and the steps go on until no net
changes. Every change of a net is counted; the nets settle on the zero-delay values, which
is checked. All clocks of a chunk are evaluated at once (one Python integer per net, bit t
= clock t), and only the gates whose inputs changed in the step before.

A unit delay is a coarse stand-in for real delays (a short path through fast gates and a
long one through slow gates can glitch where equal delays do not, and the reverse), the
usual first estimate of the glitch share.

Usage: asic_glitch.py --self-test
"""
import sys


def unit_delay(order, val, mask, skip=()):
    """Per net (not in skip) its transitions under unit delay and under zero delay, over the
    clocks of `mask` (bit t: clock t), and the steps taken. order: [(net, function, input
    nets)] of the combinational gates; val: {net: value bits} of the zero-delay evaluation
    (the registers', ports' and gates' values of each clock, settled). A net's value before
    clock t is its value in clock t - 1 (clock 0's own for the first)."""
    gates = {net: (fn, ins) for net, fn, ins in order if net not in skip}
    readers = {}
    for net, (_, ins) in gates.items():
        for i in ins:
            readers.setdefault(i, []).append(net)
    cur = {}
    for net in gates:
        v = val[net] & mask
        cur[net] = ((v << 1) | (v & 1)) & mask
    changed = set()
    for n, v in val.items():
        if n not in gates:
            before = ((v << 1) | (v & 1)) & mask
            cur[n] = v & mask
            if before != cur[n]:
                changed.add(n)
    unit = {net: 0 for net in gates}
    zero = {net: ((val[net] & mask) ^ cur[net]).bit_count() for net in gates}
    # the registers' and ports' own changes at step 0
    for n in changed:
        if n in unit:
            unit[n] += 1
    steps = 0
    dirty = {g for n in changed for g in readers.get(n, ())}
    while dirty:
        steps += 1
        new = {}
        for g in dirty:
            fn, ins = gates[g]
            v = fn(mask, *[cur[i] for i in ins])
            if v != cur[g]:
                new[g] = v
        dirty = set()
        for g, v in new.items():
            unit[g] += (v ^ cur[g]).bit_count()
            cur[g] = v
            dirty.update(readers.get(g, ()))
        if steps > 10 * len(gates) + 10:
            raise RuntimeError("unit-delay evaluation does not settle (a loop?)")
    bad = [g for g in gates if cur[g] != val[g] & mask]
    if bad:
        raise RuntimeError(f"unit delay settles on other values than zero delay at {len(bad)} nets, e.g. {bad[:3]}")
    return unit, zero, steps


def self_test():
    """A XOR of a signal and its inverted, delayed copy: zero delay never moves y, unit
    delay pulses it on every change of a (two transitions), a and its inverter counted
    too; and a gate whose inputs change together in step 1 does not glitch."""
    errs = []
    xor = lambda m, a, b: a ^ b  # noqa: E731
    inv = lambda m, a: ~a & m  # noqa: E731
    order = [("na", inv, ["a"]), ("y", xor, ["a", "na"])]
    # a over 4 clocks: 0, 1, 1, 0 (bit t = clock t); na its inverse; y always 1
    a = 0b0110
    val = {"a": a, "na": ~a & 0xF, "y": 0xF}
    unit, zero, steps = unit_delay(order, val, 0xF)
    # a changes in clocks 1 and 3: each time y drops and rises again (2 transitions)
    if unit != {"na": 2, "y": 4} or zero != {"na": 2, "y": 0} or steps != 2:
        errs.append(f"xor glitch: unit {unit}, zero {zero}, steps {steps}")
    order = [("y", xor, ["a", "b"])]
    unit, zero, _ = unit_delay(order, {"a": a, "b": a, "y": 0}, 0xF)
    if unit != {"y": 0} or zero != {"y": 0}:
        errs.append(f"no glitch when inputs change together: {unit} {zero}")
    try:
        unit_delay([("y", xor, ["a", "b"])], {"a": a, "b": 0, "y": 0}, 0xF)
        errs.append("a wrong zero-delay value was not caught")
    except RuntimeError:
        pass
    for e in errs:
        print("asic_glitch.py self-test: " + e, file=sys.stderr)
    if not errs:
        print("asic_glitch.py self-test: a glitch is counted, simultaneous inputs do not glitch, and the settled "
              "values are checked")
    return 1 if errs else 0


if __name__ == "__main__":
    sys.exit(self_test())
