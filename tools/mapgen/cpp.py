"""cmodel/include/fmpp/map.h: the map as C++17 constants in namespace fmpp::map."""
from .model import (BANNER, camel, hexint, illegal_patterns, index_widths, legal_values, lut_value, op_reserved,
                    requirements)

_BITFIELD = """\
// Bits [lsb, lsb + width) of a 64-bit value: a register, an instruction, or a field
// that holds sub-fields. Every field below is one of these, so code reads and builds
// values through the map instead of shifting by numbers of its own.
struct BitField {
  unsigned lsb;
  unsigned width;
  constexpr uint64_t max() const { return width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1; }
  constexpr uint64_t mask() const { return max() << lsb; }
  constexpr uint64_t get(uint64_t v) const { return (v >> lsb) & max(); }
  constexpr bool fits(uint64_t x) const { return x <= max(); }
  // x in place (bits of x beyond the width are dropped: check fits() first where that matters).
  constexpr uint64_t put(uint64_t x) const { return (x & max()) << lsb; }
  // v with this field replaced by x.
  constexpr uint64_t set(uint64_t v, uint64_t x) const { return (v & ~mask()) | put(x); }
};"""


def gen_h(m):
    o = []
    o.append(f"// {BANNER}")
    o.append("// FMPP host interface constants: the register map and register fields, windows, error")
    o.append("// causes and the instruction encoding, shared by the golden model, the RTL drivers and")
    o.append("// host software.")
    o.append("#pragma once")
    o.append("")
    o.append("#include <cstdint>")
    o.append("")
    o.append("namespace fmpp::map {")
    o.append("")
    o.extend(_BITFIELD.split("\n"))
    o.append("")
    o.append(f"inline constexpr unsigned kAddrW = {m['bus']['addr_width']};")
    o.append(f"inline constexpr unsigned kDataW = {m['bus']['data_width']};")
    for k, v in m["params"].items():
        o.append(f"inline constexpr unsigned k{k} = {v['value']};  // {v['desc']}")
    for name, width, what in index_widths(m):
        o.append(f"inline constexpr unsigned k{name} = {width};  // bits of {what}")
    o.append(f"inline constexpr uint32_t kMagic = 0x{hexint(m['magic']):08X}u;")
    o.append(f"inline constexpr uint16_t kVersionMajor = {m['version']['major']};")
    o.append(f"inline constexpr uint16_t kVersionMinor = {m['version']['minor']};")
    o.append("")
    for fl in m["flags"]:
        o.append(f"inline constexpr unsigned kFlag{fl['name']} = {fl['index']};  // {fl['desc']}")
    o.append("")
    errs = sorted(m["errors"], key=lambda e: e["code"])
    o.append("// Error causes (ERROR.CAUSE)")
    o.append("enum class Err : uint8_t {")
    for e in errs:
        o.append(f"  k{camel(e['name'])} = {e['code']},  // {e['desc']}")
    o.append("};")
    o.append(f"inline constexpr unsigned kNumErrs = {len(errs)};")
    o.append("inline constexpr const char* kErrNames[kNumErrs] = {")
    for e in errs:
        o.append(f"    \"{e['name']}\",")
    o.append("};")
    o.append("")
    o.append("// Registers: byte offsets and fields (bits outside the fields are reserved, read as 0)")
    for r in m["registers"]:
        n = camel(r["name"])
        o.append(f"inline constexpr uint32_t kReg{n} = 0x{hexint(r['offset']):03X};  // {r['access']}: {r['desc']}")
        for f in r["fields"]:
            o.append(f"inline constexpr BitField k{n}{camel(f['name'])}{{{f['lsb']}, {f['width']}}};")
    o.append("")
    o.append("// Windows")
    for w in m["windows"]:
        n = camel(w["name"])
        o.append(f"inline constexpr uint32_t kWin{n}Base = 0x{hexint(w['base']):08X}u;")
        o.append(f"inline constexpr uint32_t kWin{n}Size = 0x{hexint(w['size']):08X}u;")
        if "shift_flag" in w:
            o.append(f"inline constexpr unsigned kWin{n}FlagShift = {w['shift_flag']};")
    o.append("")
    o.append("// Instruction fields")
    for f in m["fields"]:
        o.append(f"inline constexpr BitField kField{camel(f['name'])}{{{f['lsb']}, {f['width']}}};  // {f['desc']}")
    o.append("")
    ops = sorted(m["opcodes"], key=lambda op: op["code"])
    o.append("enum class Op : uint8_t {")
    for op in ops:
        o.append(f"  k{camel(op['name'])} = {op['code']},  // {op['desc']}")
    o.append("};")
    o.append(f"inline constexpr unsigned kNumOpcodes = {len(ops)};")
    o.append("inline constexpr const char* kOpNames[kNumOpcodes] = {")
    for op in ops:
        o.append(f"    \"{op['name']}\",")
    o.append("};")
    o.append("// Reserved instruction bits of each opcode: fields it does not use, and bits of a used")
    o.append("// field that none of its sub-fields covers. A push with one of them set is ILLEGAL; a")
    o.append("// field is used by the opcode exactly when its bits are not reserved.")
    o.append("inline constexpr uint64_t kOpReserved[kNumOpcodes] = {")
    for op in ops:
        o.append(f"    0x{op_reserved(m, op):016X}ull,  // {op['name']}")
    o.append("};")
    pats, reqs = illegal_patterns(m), requirements(m)
    o.append("// The rest of the legality rules besides reserved bits and word ranges, as masks: an")
    o.append("// instruction is ILLEGAL when (raw & mask) == value for an IllegalPattern (an opcode's")
    o.append("// sub-field holding a value the map does not name), or when (raw & when_mask) ==")
    o.append("// when_value and (raw & need_mask) != need_value for a Requirement (a sub-field value")
    o.append("// that requires other fields to hold given values).")
    o.append("struct IllegalPattern {")
    o.append("  uint64_t mask, value;")
    o.append("};")
    o.append(f"inline constexpr unsigned kNumIllegalPatterns = {len(pats)};")
    o.append("inline constexpr IllegalPattern kIllegalPatterns[kNumIllegalPatterns > 0 ? kNumIllegalPatterns : 1] = {")
    for mask, value, what in pats or [(0, 1, "none (never matches)")]:
        o.append(f"    {{0x{mask:016X}ull, 0x{value:016X}ull}},  // {what}")
    o.append("};")
    o.append("struct Requirement {")
    o.append("  uint64_t when_mask, when_value, need_mask, need_value;")
    o.append("};")
    o.append(f"inline constexpr unsigned kNumRequirements = {len(reqs)};")
    o.append("inline constexpr Requirement kRequirements[kNumRequirements > 0 ? kNumRequirements : 1] = {")
    for wm, wv, nm, nv, what in reqs or [(0, 1, 0, 0, "none (never applies)")]:
        o.append(f"    {{0x{wm:016X}ull, 0x{wv:016X}ull, 0x{nm:016X}ull, 0x{nv:016X}ull}},  // {what}")
    o.append("};")
    o.append("")
    o.append("// Sub-fields: bit positions inside the field named in the comment (get/put apply to that")
    o.append("// field's value); the values of those that name them, and k<Name>Legal with bit v set")
    o.append("// if value v is defined (the others make the push ILLEGAL)")
    for s in m["subfields"]:
        n = camel(s["name"])
        o.append(f"inline constexpr BitField k{n}{{{s['lsb']}, {s['width']}}};  // within {s['of']}: {s['desc']}")
        if "values" in s:
            vals = ", ".join(f"k{camel(vn)} = {vv}" for vn, vv in s["values"].items())
            o.append(f"enum class {n} : uint8_t {{ {vals} }};")
            o.append(f"inline constexpr uint32_t k{n}Legal = 0x{legal_values(s):X};")
        if "functions" in s:
            o.append(f"// {s['name']} truth tables of named functions of a = flag FLAG_FA, b = flag FLAG_FB")
            o.append("namespace lut {")
            for fn, expr in s["functions"].items():
                o.append(f"inline constexpr uint8_t k{camel(fn)} = 0x{lut_value(expr, fn):X};  // {expr}")
            o.append("}  // namespace lut")
    o.append("")
    o.append("struct NamedConfig {")
    o.append("  const char* name;")
    o.append("  unsigned blocks;")
    o.append("  unsigned words;")
    o.append("  const char* desc;")
    o.append("};")
    o.append(f"inline constexpr unsigned kNumConfigs = {len(m['configs'])};")
    o.append("inline constexpr NamedConfig kConfigs[kNumConfigs] = {")
    for c in m["configs"]:
        o.append(f"    {{\"{c['name']}\", {c['blocks']}, {c['words']}, \"{c['desc']}\"}},")
    o.append("};")
    o.append("")
    o.append("}  // namespace fmpp::map")
    o.append("")
    return "\n".join(o)

