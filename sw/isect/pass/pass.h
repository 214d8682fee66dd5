// The one pass loop of the intersection kernels, shared by every form and both
// mappings (docs/intersection.md, "Passes"). A mapping keeps up to NumBlocks items in
// the blocks (rays in the ray-parallel mapping, triangles in the object-parallel one)
// and broadcasts the other side; items beyond NumBlocks run in further passes. Each
// pass: choose the broadcasts (culling), load the blocks, broadcast, read back, and let
// the host redo what the FMPP could not answer. The loop counts every step's clocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// What the pass loop needs of a broadcast's program besides its code.
//   test_steps: its instructions up to the inside test (the paper's step count);
//   mark: an instruction the form patches per pass (the arbitrary-origin form's exclusion);
//   gate: 0 for none; else code[gate] restores SEL after code[0, gate) left SEL = the
//   blocks the rest of the program can change (emit_gate). The loop pushes code[0, gate),
//   reads RESP.ANY and, when no block is selected, pushes code[gate] alone: the rest
//   would change no word and no flag that outlives the broadcast;
//   skip_gate: set by the plan where some block will almost surely pass the gate (a
//   guess: it changes clocks, never a result): the loop then leaves the gate's three
//   instructions code[gate - 2, gate] out and reads nothing;
//   gate_rows: where the form can say it, which blocks pass the gate, as a function of
//   their direction words alone (GateRows): the host then knows, ray by ray, whether the
//   broadcast's gate would let it through, without sending it (box_test.h).
// GateRows: a block passes the gate exactly where, for every row i, the exact sum
// x[3i] V_0 + x[3i + 1] V_1 + x[3i + 2] V_2 of its direction words (layout::ray::kV) is
// at least -2^floor_bits.
struct GateRows {
  int64_t x[9];
  int floor_bits;
  bool passes(const int64_t v[3]) const;
};
struct ProgramMarks {
  size_t test_steps = 0, mark = 0, gate = 0;
  bool skip_gate = false;
  std::optional<GateRows> gate_rows;
};

// Ends a program's head with a gate (ProgramMarks::gate): `save` <- SEL, SEL <- `flag`,
// and the instruction that restores SEL, which begins the tail. Returns the gate's
// position. The tail must act only in blocks of `flag` (or on per-broadcast scratch),
// and must write flag `save` before it reads it (so that the three instructions can be
// left out: skip_gate).
size_t emit_gate(Program& p, unsigned flag, unsigned save);

// What a mapping tells the pass loop. Blocks [0, count) of a pass hold items
// [base, base + count); broadcasts are numbered 1, 2, ... in the order select() returns.
class PassPlan {
 public:
  virtual ~PassPlan() = default;
  // Items held in blocks, NumBlocks per pass.
  virtual size_t items() const = 0;
  // The broadcasts of this pass, in order (the culled ones left out and counted).
  virtual std::vector<size_t> select(size_t base, unsigned count) = 0;
  // Writes the pass's items into the blocks and runs its initialisation.
  virtual void load(Device& dev, size_t base, unsigned count) = 0;
  // A plan that decides its broadcasts as it goes (culling on the FMPP) sends them itself
  // with send_broadcast after load, puts them in *sent in order and returns true; the
  // loop then goes on with refine. False: the loop sends select()'s list.
  virtual bool walk(Device& /*dev*/, size_t /*base*/, unsigned /*count*/, std::vector<size_t>* /*sent*/) {
    return false;
  }
  // The code of broadcast k, sent as number `number` of the pass, and its marks.
  virtual const std::vector<uint64_t>& code(size_t k, uint32_t number, ProgramMarks* marks) = 0;
  // After each broadcast (object-parallel: the responders name the nearest triangle).
  virtual void after_broadcast(Device& /*dev*/, size_t /*k*/) {}
  // After the broadcasts `done` of a pass: may read the blocks and return further
  // broadcasts. Either the blocks keep what they hold and the new broadcasts continue
  // after `done` (numbered on from done.size() + 1; *appended = true; the list read back
  // is done followed by them), or the plan prepared the blocks again and they are
  // numbered from 1 (*appended = false; the last list is the one read back).
  // Empty: the pass is complete.
  virtual std::vector<size_t> refine(Device& /*dev*/, size_t /*base*/, unsigned /*count*/,
                                     const std::vector<size_t>& /*done*/, bool* /*appended*/) {
    return {};
  }
  // After the pass's broadcasts: results and overflow flags.
  virtual void read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>& order) = 0;
  // Host work of the pass (overflowed items, triangles the FMPP does not take).
  virtual void host(size_t /*base*/, unsigned /*count*/) {}
  // Several FMPPs (PassShare): the order in which the passes are handed out, costliest
  // first where the plan can tell (so that no long pass is left for the end of a call);
  // empty: in order. A permutation of 0 .. passes - 1.
  virtual std::vector<size_t> pass_order(unsigned /*blocks*/) { return {}; }
  // Several FMPPs (PassShare): a plan whose passes each decide only their own items'
  // results, which results(base, count) lists as (ray index, hit) and set_result stores.
  virtual bool shareable() const { return false; }
  virtual void results(size_t /*base*/, unsigned /*count*/, std::vector<std::pair<size_t, Hit>>* /*out*/) const {}
  virtual void set_result(size_t /*index*/, const Hit& /*h*/) {}
};

// Several FMPPs, one per process (sw/mpi/, docs/multichip.md): every process runs the
// same host code and the same calls of run_passes; each call's passes are handed out
// among the devices on demand, and finish() gives every process all the results.
class PassShare {
 public:
  virtual ~PassShare() = default;
  // Whether the pass run at `turn` (of `passes`, asked in increasing turn), pass number
  // `pass` of the plan, is this device's.
  virtual bool take(uint64_t turn, uint64_t pass, uint64_t passes) = 0;
  // After the call's last pass: exchanges the results of the shareable `plan`, whose
  // passes hold `blocks` items each.
  virtual void finish(PassPlan& plan, unsigned blocks) = 0;
  // How many devices take passes (1: the passes run in order, as without sharing).
  virtual unsigned devices() const = 0;
};

// Runs every pass of `plan` on `dev`, adding clocks, instructions, broadcasts and passes
// to *st and calling opt.progress after each pass.
void run_passes(Device& dev, PassPlan& plan, const KernelOptions& opt, KernelStats* st);

// Pushes `code`, counting its instructions.
void push_counted(Device& dev, const std::vector<uint64_t>& code, KernelStats* st);

// Sends broadcast k of the current pass as number `number` (1, 2, ...), counting its
// clocks, steps and the broadcast; at a gate (ProgramMarks), the tail only when
// some block needs it (unless opt.gates is off).
void send_broadcast(Device& dev, PassPlan& plan, size_t k, uint32_t number, const KernelOptions& opt,
                    KernelStats* st);

// Merges the host's results for triangles `host` into *hit (nearest wins, an exact tie
// goes to the lower index), counting the host's tests. certain_current: *hit is known to
// be a hit of its triangle (a certified form, or none); it is evaluated again with the
// exact comparisons and its t comes back exact. Otherwise it is compared by its t.
void merge_host(const Ray& r, const std::vector<Triangle>& tris, const std::vector<int>& host, Hit* hit,
                KernelStats* st, bool certain_current = false);

// Every triangle index of `tris` (a ray the FMPP could not answer is redone against all).
std::vector<int> all_triangles(const std::vector<Triangle>& tris);

// The ray-parallel read-back of `count` blocks: the overflow flags, then the best word of
// every block without overflow and, when it is not `none`, the 1-based number of the
// broadcast that set it (idx_word). Calls on_hit(block, best, position in the pass);
// returns the overflow flag of each block. With `only`, the blocks b with (*only)[b]
// unset are not read (as if they had no best).
struct BestWords {
  unsigned best_word, idx_word;
  uint32_t none;
};
template <class OnHit>
std::vector<bool> read_best(Device& dev, unsigned count, const BestWords& w, size_t broadcasts, OnHit&& on_hit,
                            const std::vector<char>* only = nullptr);

std::vector<bool> read_overflow(Device& dev, unsigned count);
[[noreturn]] void bad_broadcast_number(unsigned block, uint32_t number, size_t broadcasts);

template <class OnHit>
std::vector<bool> read_best(Device& dev, unsigned count, const BestWords& w, size_t broadcasts, OnHit&& on_hit,
                            const std::vector<char>* only) {
  const std::vector<bool> ovf = read_overflow(dev, count);
  for (unsigned b = 0; b < count; ++b) {
    if (ovf[b] || (only && !(*only)[b])) continue;
    const uint32_t best = dev.read_word(b, w.best_word);
    if (best == w.none) continue;
    const uint32_t number = dev.read_word(b, w.idx_word);
    if (number < 1 || number > broadcasts) bad_broadcast_number(b, number, broadcasts);
    on_hit(b, best, number - 1);
  }
  return ovf;
}

}  // namespace fmpp::isect
