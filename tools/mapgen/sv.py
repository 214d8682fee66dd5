"""rtl/fmpp_pkg.sv: the map as a SystemVerilog package (members referred to by
qualified name: yosys 0.23 cannot parse `import`, nor unpacked array parameters)."""
from .model import (BANNER, hexint, illegal_patterns, index_widths, legal_values, op_reserved, reg_layout, register,
                    requirements, reserved_segments)


def _enum(o, name, width, items, comments=None):
    o.append(f"  typedef enum logic [{width - 1}:0] {{")
    for i, (k, v) in enumerate(items):
        sep = "," if i + 1 < len(items) else ""
        tail = f"  // {comments[i]}" if comments else ""
        o.append(f"    {k} = {width}'d{v}{sep}{tail}")
    o.append(f"  }} {name};")


def gen_sv(m):
    o = []
    o.append(f"// {BANNER}")
    o.append("// FMPP package: bus parameters, register map and register layouts, windows, error")
    o.append("// causes and the instruction encoding shared by every RTL file. Refer to members by")
    o.append("// qualified name (fmpp_pkg::OP_ADD): yosys 0.23 cannot parse `import`.")
    o.append("// The package also carries constants only the host software uses, hence the waiver.")
    o.append("/* verilator lint_off UNUSEDPARAM */")
    o.append("package fmpp_pkg;")
    o.append("")
    o.append(f"  parameter int unsigned AddrW = {m['bus']['addr_width']};")
    o.append(f"  parameter int unsigned DataW = {m['bus']['data_width']};")
    for k, v in m["params"].items():
        o.append(f"  parameter int unsigned {k} = {v['value']};  // {v['desc']}")
    for name, width, what in index_widths(m):
        o.append(f"  parameter int unsigned {name} = {width};  // bits of {what}")
    o.append(f"  parameter logic [31:0] Magic = 32'h{hexint(m['magic']):08X};")
    o.append(f"  parameter logic [15:0] VersionMajor = 16'd{m['version']['major']};")
    o.append(f"  parameter logic [15:0] VersionMinor = 16'd{m['version']['minor']};")
    o.append("")
    o.append("  // Flags with a fixed meaning")
    for fl in m["flags"]:
        o.append(f"  parameter int unsigned Flag{fl['name']} = {fl['index']};  // {fl['desc']}")
    o.append("")
    cause_w = next(f["width"] for f in register(m, "ERROR")["fields"] if f["name"] == "CAUSE")
    o.append("  // Error causes (ERROR.CAUSE)")
    errs = sorted(m["errors"], key=lambda e: e["code"])
    _enum(o, "err_e", cause_w, [(f"ERR_{e['name']}", e["code"]) for e in errs])
    o.append("")
    o.append("  // Registers (byte offsets)")
    for r in m["registers"]:
        o.append(f"  parameter logic [AddrW-1:0] REG_{r['name']} = 32'h{hexint(r['offset']):08X};")
    o.append("")
    o.append("  // Register fields: [REG_<REGISTER>_<FIELD>_LSB +: REG_<REGISTER>_<FIELD>_W]")
    for r in m["registers"]:
        for f in r["fields"]:
            o.append(f"  parameter int unsigned REG_{r['name']}_{f['name']}_LSB = {f['lsb']};")
            o.append(f"  parameter int unsigned REG_{r['name']}_{f['name']}_W = {f['width']};")
    o.append("")
    o.append("  // Register layouts, bit 63 first; rsvd<lsb> members are reserved (read as 0)")
    for r in m["registers"]:
        if r["access"] == "wo":
            continue  # never read back: the slave decodes the written value by instruction fields
        o.append("  typedef struct packed {")
        for name, lsb, width, _ in reg_layout(r):
            t = "logic" if width == 1 else f"logic [{width - 1}:0]"
            o.append(f"    {t} {name};")
        o.append(f"  }} {r['name'].lower()}_reg_t;")
    o.append("")
    o.append("  // Windows")
    for w in m["windows"]:
        o.append(f"  parameter logic [AddrW-1:0] WIN_{w['name']}_BASE = 32'h{hexint(w['base']):08X};")
        o.append(f"  parameter logic [AddrW-1:0] WIN_{w['name']}_SIZE = 32'h{hexint(w['size']):08X};")
        if "shift_flag" in w:
            o.append(f"  parameter int unsigned WIN_{w['name']}_FLAG_SHIFT = {w['shift_flag']};")
    o.append("")
    o.append("  // Instruction fields: [lsb +: width] of the 64-bit instruction")
    for f in m["fields"]:
        o.append(f"  parameter int unsigned F_{f['name']}_LSB = {f['lsb']};")
        o.append(f"  parameter int unsigned F_{f['name']}_W = {f['width']};")
    o.append("")
    op_w = next(f["width"] for f in m["fields"] if f["name"] == "OP")
    ops = sorted(m["opcodes"], key=lambda op: op["code"])
    o.append("  // Opcodes")
    _enum(o, "opcode_e", op_w, [(f"OP_{op['name']}", op["code"]) for op in ops], [op["desc"] for op in ops])
    o.append("")
    o.append("  // Sub-fields: [lsb +: width] of the field named in the comment; their values, and")
    o.append("  // <NAME>_LEGAL with bit v set if value v is defined (others make the push ILLEGAL)")
    for s in m["subfields"]:
        o.append(f"  parameter int unsigned {s['name']}_LSB = {s['lsb']};  // within {s['of']}")
        o.append(f"  parameter int unsigned {s['name']}_W = {s['width']};")
        for vn, vv in s.get("values", {}).items():
            o.append(f"  parameter logic [{s['width'] - 1}:0] {s['name']}_{vn} = {s['width']}'d{vv};")
        if "values" in s:
            n = 1 << s["width"]
            o.append(f"  parameter logic [{n - 1}:0] {s['name']}_LEGAL = {n}'b{legal_values(s):0{n}b};")
    o.append("")
    q = m["queue_entry"]
    o.append(f"  // Queue entry ({q['desc']})")
    _enum(o, "qkind_e", 2, [(f"QE_{k}", v) for k, v in q["kinds"].items()])
    o.append("  typedef struct packed {")
    for f in q["fields"]:
        t = "qkind_e" if f["name"] == "kind" else f"logic [{f['width'] - 1}:0]"
        o.append(f"    {t} {f['name']};")
    o.append("  } qentry_t;")
    o.append(f"  parameter int unsigned QEntryW = {sum(f['width'] for f in q['fields'])};  // $bits(qentry_t), spelled out for yosys")
    o.append("")
    rk = m["read_kinds"]
    o.append(f"  // Read port kinds ({rk['desc']})")
    _enum(o, "rkind_e", 2, [(f"RK_{k}", v) for k, v in rk["kinds"].items()])
    o.append("")
    o.append("  // Reserved instruction bits of each opcode: fields it does not use, and bits of a")
    o.append("  // used field that none of its sub-fields covers. A push with one of them set is ILLEGAL;")
    o.append("  // a field is used by the opcode exactly when its bits are not reserved.")
    o.append(f"  parameter int unsigned NumOpcodes = {len(ops)};")
    o.append("  // OpReserved[op*64 +: 64]")
    body = ", ".join(f"64'h{op_reserved(m, op):016X}" for op in reversed(ops))
    o.append(f"  parameter logic [NumOpcodes*64-1:0] OpReserved = {{{body}}};")
    segs = reserved_segments(m)
    o.append("  // The same, grouped for a cheap check: bits reserved for the same opcodes form one")
    o.append("  // segment; RsvSegMask[s*64 +: 64] are its bits, RsvSegOps[op*NumRsvSegs + s] = 1")
    o.append("  // if opcode op reserves segment s.")
    o.append(f"  parameter int unsigned NumRsvSegs = {len(segs)};")
    body = ", ".join(f"64'h{mask:016X}" for mask, _ in reversed(segs))
    o.append(f"  parameter logic [NumRsvSegs*64-1:0] RsvSegMask = {{{body}}};")
    rows = []
    for op in reversed(ops):
        row = "".join("1" if op["code"] in opset else "0" for _, opset in reversed(segs))
        rows.append(f"{len(segs)}'b{row}")
    o.append(f"  parameter logic [NumOpcodes*NumRsvSegs-1:0] RsvSegOps = {{{', '.join(rows)}}};")
    o.append("")
    pats, reqs = illegal_patterns(m), requirements(m)
    o.append("  // The rest of the legality rules, as masks (entry k at [k*64 +: 64]; an empty table")
    o.append("  // holds one entry that never applies): ILLEGAL when (instr & IllegalMask) ==")
    o.append("  // IllegalValue (a sub-field value the map does not name), or when (instr & ReqWhenMask)")
    o.append("  // == ReqWhenValue and (instr & ReqNeedMask) != ReqNeedValue (a sub-field value that")
    o.append("  // requires other fields to hold given values).")
    for what in [w for _, _, w in pats] + [r[4] for r in reqs]:
        o.append(f"  //   {what}")
    o.append(f"  parameter int unsigned NumIllegal = {len(pats)};")
    rows = pats or [(0, 1, "")]
    for i, name in enumerate(["IllegalMask", "IllegalValue"]):
        body = ", ".join("64'h%016X" % r[i] for r in reversed(rows))
        o.append(f"  parameter logic [{len(rows)}*64-1:0] {name} = {{{body}}};")
    o.append(f"  parameter int unsigned NumRequires = {len(reqs)};")
    rows = reqs or [(0, 1, 0, 0, "")]
    for i, name in enumerate(["ReqWhenMask", "ReqWhenValue", "ReqNeedMask", "ReqNeedValue"]):
        body = ", ".join("64'h%016X" % r[i] for r in reversed(rows))
        o.append(f"  parameter logic [{len(rows)}*64-1:0] {name} = {{{body}}};")
    o.append("")
    o.append("endpackage")
    o.append("/* verilator lint_on UNUSEDPARAM */")
    o.append("")
    return "\n".join(o)

