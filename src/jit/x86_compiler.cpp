#include "gpfd/jit/x86_compiler.hpp"

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gpfd/expr/ops.hpp"
#include "gpfd/expr/trig_lanes.hpp"
#include "gpfd/jit/trig_avx2.hpp"
#include "gpfd/util/cpu.hpp"

#if GPFD_HAVE_JIT
#include <asmjit/x86.h>
#endif

namespace gpfd::jit {

#if GPFD_HAVE_JIT
namespace {

using expr::Op;
namespace x86 = asmjit::x86;
using InstId = asmjit::InstId;

// The operators that generated code calls. Each applies exactly the function the interpreter
// applies, so results agree bit for bit (the 4-lane sin and cos are expr::trig's, vectorised).
using ScalarHelper = double (*)(double);
using LaneHelper = void (*)(double*);  // Applies the operator to 4 doubles in place.

ScalarHelper scalarHelper(Op op) {
  switch (op) {
    case Op::Sin:
      return [](double x) { return expr::trig::sin(x); };
    case Op::Cos:
      return [](double x) { return expr::trig::cos(x); };
    case Op::Exp:
      return [](double x) { return expr::protect::exp(x); };
    case Op::Log:
      return [](double x) { return expr::protect::log(x); };
    case Op::Tanh:
      return [](double x) { return std::tanh(x); };
    default:
      return nullptr;
  }
}

LaneHelper laneHelper(Op op) {
  switch (op) {
    case Op::Sin:
      return sin4Avx2;
    case Op::Cos:
      return cos4Avx2;
    case Op::Exp:
      return [](double* x) {
        for (int j = 0; j < 4; ++j) x[j] = expr::protect::exp(x[j]);
      };
    case Op::Log:
      return [](double* x) {
        for (int j = 0; j < 4; ++j) x[j] = expr::protect::log(x[j]);
      };
    case Op::Tanh:
      return [](double* x) {
        for (int j = 0; j < 4; ++j) x[j] = std::tanh(x[j]);
      };
    default:
      return nullptr;
  }
}

// sin and cos of the same 4 doubles from one reduction, for a batch program that needs both: x is
// replaced by the value of the instruction met first, `other` receives its partner's.
using PairHelper = void (*)(double* x, double* other);

GPFD_AVX2_KERNEL void sinThenCos4Avx2(double* x, double* other) {
  const auto both = expr::trig::sinCos(lanes::load(x));
  lanes::store(x, both.sin);
  lanes::store(other, both.cos);
}
GPFD_AVX2_KERNEL void cosThenSin4Avx2(double* x, double* other) {
  const auto both = expr::trig::sinCos(lanes::load(x));
  lanes::store(x, both.cos);
  lanes::store(other, both.sin);
}

// The process-wide code runtime, never destroyed (code may be released during static
// destruction). Dual mapping keeps every page either writable or executable, never both.
struct Runtime {
  asmjit::JitRuntime* jit = nullptr;
  bool dualMapping = false;

  Runtime() {
    asmjit::VirtMem::DualMapping probe{};
    const auto rx = asmjit::VirtMem::MemoryFlags::kAccessRX;
    if (asmjit::VirtMem::allocDualMapping(&probe, 4096, rx) == asmjit::kErrorOk) {
      asmjit::VirtMem::releaseDualMapping(&probe, 4096);
      asmjit::JitAllocator::CreateParams params{};
      params.options = asmjit::JitAllocatorOptions::kUseDualMapping;
      jit = new asmjit::JitRuntime(&params);
      dualMapping = true;
    } else {
      jit = new asmjit::JitRuntime();
    }
  }
};

Runtime& runtime() {
  static Runtime* instance = new Runtime();
  return *instance;
}

class RecordingErrorHandler : public asmjit::ErrorHandler {
 public:
  void handleError(asmjit::Error err, const char* message, asmjit::BaseEmitter*) override {
    if (error == asmjit::kErrorOk) {
      error = err;
      text = message;
    }
  }
  asmjit::Error error = asmjit::kErrorOk;
  std::string text;
};

// Thrown inside emission when a frameless function runs out of registers; it is then emitted
// again with a frame.
struct NeedFrame {};

// Where the code reads states and writes features: one state (scalar function), four consecutive
// state rows (StateRows), or lane blocks (LaneBlocks); x86_compiler.hpp.
enum class Layout { Scalar, StateRows, LaneBlocks };

// The fixed entries of the constant pool, before the program's constants.
enum Fixed : int { kPosMax, kNegMax, kAbsMask, kSignMask, kNearZero, kOne, kFixedCount };

constexpr int kValueRegs = 14;  // xmm0..xmm13 hold values.
constexpr int kScratchA = 14;   // xmm14/xmm15: scratch within one instruction.
constexpr int kScratchB = 15;

// lastUse[v]: the last instruction reading value v (0 when none does).
std::vector<std::uint32_t> lastUses(const Program& program) {
  std::vector<std::uint32_t> lastUse(program.code.size(), 0);
  for (std::size_t i = 0; i < program.code.size(); ++i) {
    const Instr& in = program.code[i];
    const int ar = expr::arity(in.op);
    if (ar >= 1) lastUse[in.a] = static_cast<std::uint32_t>(i);
    if (ar == 2) lastUse[in.b] = static_cast<std::uint32_t>(i);
  }
  return lastUse;
}

class Emitter {
 public:
  Emitter(x86::Assembler& a, const Program& program, const std::vector<std::uint32_t>& lastUse,
          Layout layout, bool frame)
      : a_(a),
        p_(program),
        lastUse_(lastUse),
        batch_(layout != Layout::Scalar),
        blocks_(layout == Layout::LaneBlocks),
        frame_(frame),
        width_(batch_ ? 32 : 8) {}

  void emit() {
    const std::size_t n = p_.code.size();
    // Output k is stored right after its value is computed.
    outputsAt_.assign(n, -1);
    nextOutput_.assign(p_.outputs.size(), -1);
    for (std::size_t k = p_.outputs.size(); k-- > 0;) {
      nextOutput_[k] = outputsAt_[p_.outputs[k]];
      outputsAt_[p_.outputs[k]] = static_cast<int>(k);
    }
    findTrigPairs();
    pool_.assign(n, -1);
    int entries = kFixedCount;
    for (std::size_t i = 0; i < n; ++i) {
      if (p_.code[i].op == Op::Const) pool_[i] = entries++;
    }
    poolLabel_ = a_.newLabel();
    entryLabel_ = a_.newLabel();
    calls_ = p_.hasCalls();
    // The constant pool comes first, so that every RIP-relative reference to it points backwards
    // to a bound label (no fix-ups); the function starts after it.
    emitPool(entries);
    a_.bind(entryLabel_);
    if (batch_) {
      emitBatch();
    } else {
      emitScalar();
    }
  }

  asmjit::Label entryLabel() const { return entryLabel_; }

 private:
  struct Value {
    int reg = -1;
    int slot = -1;
  };

  // In the batch kernel, sin(x) and cos(x) of the same value are computed by one call (the lane
  // sine and cosine share their reduction: the same bits as two calls). partner_[v] = w: the call
  // at v also computes w, the other one, later in the program; precomputed_[w] is then true.
  void findTrigPairs() {
    const std::size_t n = p_.code.size();
    partner_.assign(n, -1);
    precomputed_.assign(n, false);
    if (!batch_) return;
    std::vector<int> sinOf(n, -1), cosOf(n, -1);  // By operand: the first sin and cos of it.
    for (std::size_t i = 0; i < n; ++i) {
      const Instr& in = p_.code[i];
      if (in.op != Op::Sin && in.op != Op::Cos) continue;
      int& mine = (in.op == Op::Sin ? sinOf : cosOf)[in.a];
      const int other = (in.op == Op::Sin ? cosOf : sinOf)[in.a];
      if (mine >= 0) continue;  // Lowering shares sub-expressions, so this does not happen.
      mine = static_cast<int>(i);
      if (other >= 0 && partner_[static_cast<std::size_t>(other)] < 0 &&
          !precomputed_[static_cast<std::size_t>(other)]) {
        partner_[static_cast<std::size_t>(other)] = static_cast<int>(i);
        precomputed_[i] = true;
      }
    }
  }

  // ---- Function shells ----

  void emitScalar() {
    const int pushes = calls_ ? 2 : 0;
    if (calls_) {
      a_.push(x86::rbx);
      a_.push(x86::r12);
      a_.mov(x86::rbx, x86::rdi);
      a_.mov(x86::r12, x86::rsi);
    }
    state_ = calls_ ? x86::rbx : x86::rdi;
    out_ = calls_ ? x86::r12 : x86::rsi;
    const int adjust = frameAdjust(pushes);
    if (frame_) a_.sub(x86::rsp, adjust);
    body();
    if (frame_) a_.add(x86::rsp, adjust);
    if (calls_) {
      a_.pop(x86::r12);
      a_.pop(x86::rbx);
    }
    a_.ret();
  }

  void emitBatch() {
    a_.push(x86::rbx);
    a_.push(x86::r12);
    a_.push(x86::r13);
    a_.mov(x86::rbx, x86::rdi);
    a_.mov(x86::r13, x86::rsi);
    a_.mov(x86::r12, x86::rdx);
    state_ = x86::rbx;
    out_ = x86::r12;
    const int adjust = frameAdjust(3);
    a_.sub(x86::rsp, adjust);
    asmjit::Label loop = a_.newLabel(), done = a_.newLabel();
    a_.test(x86::r13, x86::r13);
    a_.jz(done);
    a_.bind(loop);
    body();
    a_.add(x86::rbx, static_cast<std::int32_t>(4 * 8 * p_.inputDim));
    a_.add(x86::r12, static_cast<std::int32_t>(4 * 8 * p_.outputs.size()));
    a_.dec(x86::r13);
    a_.jnz(loop);
    a_.bind(done);
    a_.add(x86::rsp, adjust);
    a_.vzeroupper();
    a_.pop(x86::r13);
    a_.pop(x86::r12);
    a_.pop(x86::rbx);
    a_.ret();
  }

  // Bytes to subtract from rsp so that it is 16-byte aligned at calls, with `pushes` registers
  // pushed after the return address.
  static int frameAdjust(int pushes) {
    int adjust = static_cast<int>(kFrameBytes);
    if ((8 + 8 * pushes + adjust) % 16 != 0) adjust += 8;
    return adjust;
  }

  void emitPool(int entries) {
    const std::size_t entryBytes = batch_ ? 32 : 16;
    std::vector<std::uint64_t> data(static_cast<std::size_t>(entries) * entryBytes / 8);
    auto put = [&](int entry, std::uint64_t bits) {
      for (std::size_t j = 0; j < entryBytes / 8; ++j) data[entry * entryBytes / 8 + j] = bits;
    };
    put(kPosMax, std::bit_cast<std::uint64_t>(expr::protect::kMax));
    put(kNegMax, std::bit_cast<std::uint64_t>(-expr::protect::kMax));
    put(kAbsMask, 0x7fffffffffffffffULL);
    put(kSignMask, 0x8000000000000000ULL);
    put(kNearZero, std::bit_cast<std::uint64_t>(expr::protect::kNearZero));
    put(kOne, std::bit_cast<std::uint64_t>(1.0));
    for (std::size_t i = 0; i < p_.code.size(); ++i) {
      if (pool_[i] >= 0) put(pool_[i], std::bit_cast<std::uint64_t>(p_.code[i].value));
    }
    a_.bind(poolLabel_);
    a_.embed(data.data(), data.size() * 8);
  }

  // ---- Operands ----

  x86::Vec vec(int r) const {
    return batch_ ? static_cast<x86::Vec>(x86::ymm(r)) : static_cast<x86::Vec>(x86::xmm(r));
  }
  x86::Mem pool(int entry) const { return x86::ptr(poolLabel_, entry * (batch_ ? 32 : 16)); }
  // The lane buffer for helper calls sits at the bottom of the batch frame, slots above it.
  x86::Mem slotMem(int slot) const { return x86::ptr(x86::rsp, (batch_ ? 32 : 0) + slot * width_); }

  void load(int r, const x86::Mem& m) {
    if (batch_) {
      a_.vmovupd(x86::ymm(r), m);
    } else {
      a_.movsd(x86::xmm(r), m);
    }
  }
  void store(const x86::Mem& m, int r) {
    if (batch_) {
      a_.vmovupd(m, x86::ymm(r));
    } else {
      a_.movsd(m, x86::xmm(r));
    }
  }

  // dst = op(src1, src2): SSE two-operand form (copying src1 first) or AVX three-operand form.
  void op2(InstId scalarId, InstId vectorId, int dst, int src1, const asmjit::Operand_& src2) {
    if (batch_) {
      a_.emit(vectorId, vec(dst), vec(src1), src2);
    } else {
      if (dst != src1) a_.movapd(x86::xmm(dst), x86::xmm(src1));
      a_.emit(scalarId, vec(dst), src2);
    }
  }
  void op2(InstId scalarId, InstId vectorId, int dst, const asmjit::Operand_& src2) {
    op2(scalarId, vectorId, dst, dst, src2);
  }

  // Clamps register r to [-DBL_MAX, DBL_MAX] (protect::saturate); `nonNegative` skips the max.
  void saturate(int r, bool nonNegative = false) {
    if (!nonNegative) op2(x86::Inst::kIdMaxsd, x86::Inst::kIdVmaxpd, r, pool(kNegMax));
    op2(x86::Inst::kIdMinsd, x86::Inst::kIdVminpd, r, pool(kPosMax));
  }

  // ---- Register allocation ----

  bool isConst(std::uint32_t v) const { return pool_[v] >= 0; }

  void release(std::uint32_t v) {
    Value& val = values_[v];
    if (val.reg >= 0 && owner_[val.reg] == static_cast<int>(v)) owner_[val.reg] = -1;
    val.reg = -1;
  }

  // Values die after their last use: their register and slot are freed.
  void retire(std::uint32_t v, std::size_t at) {
    if (lastUse_[v] != at) return;
    release(v);
    if (values_[v].slot >= 0) {
      freeSlots_.push_back(values_[v].slot);
      values_[v].slot = -1;
    }
  }

  // A slot of the frame for value v.
  void takeSlot(std::uint32_t v) {
    if (!frame_) throw NeedFrame{};
    Value& val = values_[v];
    if (!freeSlots_.empty()) {
      val.slot = freeSlots_.back();
      freeSlots_.pop_back();
    } else {
      const std::size_t limit = batch_ ? kMaxBatchSpills : kMaxScalarSpills;
      if (static_cast<std::size_t>(slotCount_) >= limit) {
        throw CompileError("program needs more than " + std::to_string(limit) +
                           " spilled values at once");
      }
      val.slot = slotCount_++;
    }
  }

  void spillToMemory(std::uint32_t v) {
    Value& val = values_[v];
    if (val.slot >= 0 || isConst(v)) return;
    takeSlot(v);
    store(slotMem(val.slot), val.reg);
  }

  // A free value register, evicting the live value used furthest ahead when none is free.
  // `avoid` is a bit mask of registers that must keep their values.
  int allocate(unsigned avoid) {
    int victim = -1;
    for (int r = 0; r < kValueRegs; ++r) {
      if (avoid & (1u << r)) continue;
      if (owner_[r] < 0) return r;
      if (victim < 0 || lastUse_[owner_[r]] > lastUse_[owner_[victim]]) victim = r;
    }
    const auto v = static_cast<std::uint32_t>(owner_[victim]);
    spillToMemory(v);
    release(v);
    return victim;
  }

  void assign(std::uint32_t v, int r) {
    owner_[r] = static_cast<int>(v);
    values_[v].reg = r;
  }

  int inRegister(std::uint32_t v, unsigned avoid) {
    if (values_[v].reg >= 0) return values_[v].reg;
    const int r = allocate(avoid);
    load(r, isConst(v) ? pool(pool_[v]) : slotMem(values_[v].slot));
    assign(v, r);
    return r;
  }

  asmjit::Operand operand(std::uint32_t v) const {
    if (values_[v].reg >= 0) return vec(values_[v].reg);
    if (isConst(v)) return pool(pool_[v]);
    return slotMem(values_[v].slot);
  }

  unsigned maskOf(std::uint32_t v) const { return values_[v].reg >= 0 ? 1u << values_[v].reg : 0u; }

  // ---- The body: one pass over the program ----

  void body() {
    const std::size_t n = p_.code.size();
    values_.assign(n, Value{});
    for (int& o : owner_) o = -1;
    freeSlots_.clear();
    slotCount_ = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Instr& in = p_.code[i];
      const auto v = static_cast<std::uint32_t>(i);
      switch (in.op) {
        case Op::Const:
          storeConstOutputs(v);
          continue;
        case Op::Var:
          variable(v, in.var);
          break;
        default:
          if (precomputed_[i]) {
            takePrecomputed(v, in);
          } else if (expr::isCall(in.op)) {
            call(v, in);
          } else if (expr::arity(in.op) == 1) {
            unary(v, in);
          } else {
            binary(v, in);
          }
      }
      storeOutputs(v);
    }
  }

  void variable(std::uint32_t v, std::uint16_t var) {
    const int d = allocate(0);
    const auto disp = static_cast<std::int32_t>(8 * var);
    if (batch_) {
      if (blocks_) {
        a_.vmovupd(x86::ymm(d), x86::ptr(state_, 4 * disp));  // The variable's four lanes.
      } else {
        const auto row = static_cast<std::int32_t>(8 * p_.inputDim);
        const x86::Xmm dx = x86::xmm(d), s = x86::xmm(kScratchB);
        a_.vmovsd(dx, x86::ptr(state_, disp));
        a_.vmovhpd(dx, dx, x86::ptr(state_, disp + row));
        a_.vmovsd(s, x86::ptr(state_, disp + 2 * row));
        a_.vmovhpd(s, s, x86::ptr(state_, disp + 3 * row));
        a_.vinsertf128(x86::ymm(d), x86::ymm(d), s, 1);
      }
      a_.vcmppd(x86::ymm(kScratchB), x86::ymm(d), x86::ymm(d), 7);  // Ordered: not NaN.
    } else {
      a_.movsd(x86::xmm(d), x86::ptr(state_, disp));
      a_.movapd(x86::xmm(kScratchB), x86::xmm(d));
      a_.cmpsd(x86::xmm(kScratchB), x86::xmm(kScratchB), 7);
    }
    // protect::input: saturate, then NaN -> +0 through the ordered mask.
    saturate(d);
    op2(x86::Inst::kIdAndpd, x86::Inst::kIdVandpd, d, vec(kScratchB));
    assign(v, d);
  }

  // The destination of an instruction whose first operand is in register ra: ra itself when the
  // operand dies here or is a constant (reloaded from the pool when needed again, so constants
  // never hold registers that live values need), else a fresh register.
  int destination(std::uint32_t v, std::uint32_t a, int ra, unsigned avoid, std::size_t at) {
    if (lastUse_[a] == at || isConst(a)) {
      release(a);
      if (values_[a].slot >= 0) {
        freeSlots_.push_back(values_[a].slot);
        values_[a].slot = -1;
      }
      assign(v, ra);
      return ra;
    }
    const int d = allocate(avoid | (1u << ra));
    assign(v, d);
    return d;
  }

  void unary(std::uint32_t v, const Instr& in) {
    const int ra = inRegister(in.a, 0);
    const int d = destination(v, in.a, ra, 0, v);
    namespace I = x86::Inst;
    switch (in.op) {
      case Op::Sqrt:
        op2(I::kIdAndpd, I::kIdVandpd, d, ra, pool(kAbsMask));
        if (batch_) {
          a_.vsqrtpd(x86::ymm(d), x86::ymm(d));
        } else {
          a_.sqrtsd(x86::xmm(d), x86::xmm(d));
        }
        break;
      case Op::Neg:
        op2(I::kIdXorpd, I::kIdVxorpd, d, ra, pool(kSignMask));
        break;
      case Op::Abs:
        op2(I::kIdAndpd, I::kIdVandpd, d, ra, pool(kAbsMask));
        break;
      case Op::Square:
        op2(I::kIdMulsd, I::kIdVmulpd, d, ra, vec(ra));
        saturate(d, true);
        break;
      default:
        throw CompileError("unexpected unary operator");
    }
  }

  void binary(std::uint32_t v, const Instr& in) {
    std::uint32_t a = in.a, b = in.b;
    // For a commutative operator whose first operand lives on but second dies, swap them so the
    // result can take the dying operand's register.
    // A constant first operand of a commutative operator becomes the memory operand.
    const bool commutative = in.op == Op::Add || in.op == Op::Mul || in.op == Op::AbsDiff;
    if (commutative && ((lastUse_[a] != v && lastUse_[b] == v && values_[b].reg >= 0) ||
                        (isConst(a) && !isConst(b)))) {
      std::swap(a, b);
    }
    const int ra = inRegister(a, maskOf(b));
    const unsigned keep = maskOf(b) | (1u << ra);
    namespace I = x86::Inst;
    if (in.op == Op::Div) {
      divide(v, a, b, ra, keep);
      retire(b, v);
      return;
    }
    const asmjit::Operand src = operand(b);
    const int d = destination(v, a, ra, keep, v);
    switch (in.op) {
      case Op::Add:
        op2(I::kIdAddsd, I::kIdVaddpd, d, ra, src);
        saturate(d);
        break;
      case Op::Sub:
        op2(I::kIdSubsd, I::kIdVsubpd, d, ra, src);
        saturate(d);
        break;
      case Op::Mul:
        op2(I::kIdMulsd, I::kIdVmulpd, d, ra, src);
        // |a * c| <= |a| <= DBL_MAX when |c| <= 1: nothing to saturate.
        if (!(isConst(b) && std::fabs(p_.code[b].value) <= 1.0)) saturate(d);
        break;
      case Op::Min:
        op2(I::kIdMinsd, I::kIdVminpd, d, ra, src);
        break;
      case Op::Max:
        op2(I::kIdMaxsd, I::kIdVmaxpd, d, ra, src);
        break;
      case Op::AbsDiff:
        op2(I::kIdSubsd, I::kIdVsubpd, d, ra, src);
        op2(I::kIdAndpd, I::kIdVandpd, d, pool(kAbsMask));
        saturate(d, true);
        break;
      default:
        throw CompileError("unexpected binary operator");
    }
    if (b != a) retire(b, v);
  }

  // protect::div: |b| > kNearZero ? saturate(a / b) : 1, branch-free through a mask.
  void divide(std::uint32_t v, std::uint32_t a, std::uint32_t b, int ra, unsigned keep) {
    namespace I = x86::Inst;
    const asmjit::Operand src = operand(b);
    const bool safeConstant = isConst(b);  // Lowering folded near-zero constant denominators.
    if (!safeConstant && (batch_ || vex_)) {
      // AVX: mask = !(|b| > kNearZero) (NaN included), then one vblendvpd picks 1 under it.
      const x86::Vec mask = vec(kScratchA);
      if (values_[b].reg >= 0) {
        a_.vandpd(mask, vec(values_[b].reg), pool(kAbsMask));
      } else {
        load(kScratchA, slotMem(values_[b].slot));
        a_.vandpd(mask, mask, pool(kAbsMask));
      }
      if (batch_) {
        a_.vcmppd(mask, mask, pool(kNearZero), 0x1a);  // NGT_UQ.
      } else {
        a_.vcmpsd(x86::xmm(kScratchA), x86::xmm(kScratchA), pool(kNearZero), 0x1a);
      }
    } else if (!safeConstant) {
      if (batch_) {
        if (values_[b].reg >= 0) {
          a_.vandpd(x86::ymm(kScratchA), x86::ymm(values_[b].reg), pool(kAbsMask));
        } else {
          a_.vmovupd(x86::ymm(kScratchA), slotMem(values_[b].slot));
          a_.vandpd(x86::ymm(kScratchA), x86::ymm(kScratchA), pool(kAbsMask));
        }
        a_.vcmppd(x86::ymm(kScratchA), x86::ymm(kScratchA), pool(kNearZero), 0x1e);  // GT_OQ.
      } else {
        if (values_[b].reg >= 0) {
          a_.movapd(x86::xmm(kScratchB), x86::xmm(values_[b].reg));
        } else {
          a_.movsd(x86::xmm(kScratchB), slotMem(values_[b].slot));
        }
        a_.andpd(x86::xmm(kScratchB), pool(kAbsMask));
        a_.movsd(x86::xmm(kScratchA), pool(kNearZero));
        a_.cmpsd(x86::xmm(kScratchA), x86::xmm(kScratchB), 1);  // kNearZero < |b|.
      }
    }
    const int d = destination(v, a, ra, keep, v);
    op2(I::kIdDivsd, I::kIdVdivpd, d, ra, src);
    // |a / c| <= |a| <= DBL_MAX when |c| >= 1: nothing to saturate.
    if (!(safeConstant && std::fabs(p_.code[b].value) >= 1.0)) saturate(d);
    if (!safeConstant && (batch_ || vex_)) {
      a_.vblendvpd(vec(d), vec(d), pool(kOne), vec(kScratchA));
    } else if (!safeConstant) {
      op2(I::kIdAndpd, I::kIdVandpd, d, vec(kScratchA));
      op2(I::kIdAndnpd, I::kIdVandnpd, kScratchA, pool(kOne));
      op2(I::kIdOrpd, I::kIdVorpd, d, vec(kScratchA));
    }
  }

  // sin, cos, exp, log, tanh: every live register is caller-saved, so all live values go to
  // memory first; the result comes back in register 0.
  void call(std::uint32_t v, const Instr& in) {
    if (!frame_) throw NeedFrame{};
    const std::uint32_t a = in.a;
    const int ra = inRegister(a, 0);
    for (int r = 0; r < kValueRegs; ++r) {
      if (owner_[r] < 0) continue;
      const auto u = static_cast<std::uint32_t>(owner_[r]);
      if (lastUse_[u] > v) spillToMemory(u);
      release(u);
    }
    retire(a, v);
    // Registers keep their contents after release, so the operand is still in ra.
    if (batch_) {
      a_.vmovupd(x86::ptr(x86::rsp, 0), x86::ymm(ra));
    } else if (ra != 0) {
      a_.movapd(x86::xmm(0), x86::xmm(ra));
    }
    if (batch_) {
      a_.vzeroupper();
      a_.lea(x86::rdi, x86::ptr(x86::rsp, 0));
      const int partner = partner_[v];
      if (partner >= 0) {  // The partner's value goes straight into its slot.
        takeSlot(static_cast<std::uint32_t>(partner));
        a_.lea(x86::rsi, slotMem(values_[static_cast<std::size_t>(partner)].slot));
        const PairHelper pair = in.op == Op::Sin ? sinThenCos4Avx2 : cosThenSin4Avx2;
        a_.mov(x86::rax, reinterpret_cast<std::uint64_t>(pair));
      } else {
        a_.mov(x86::rax, reinterpret_cast<std::uint64_t>(laneHelper(in.op)));
      }
      a_.call(x86::rax);
      a_.vmovupd(x86::ymm(0), x86::ptr(x86::rsp, 0));
    } else {
      a_.mov(x86::rax, reinterpret_cast<std::uint64_t>(scalarHelper(in.op)));
      a_.call(x86::rax);
    }
    assign(v, 0);
  }

  // A sin or cos that its partner's call computed: its value waits in its slot.
  void takePrecomputed(std::uint32_t v, const Instr& in) {
    retire(in.a, v);
    if (outputsAt_[v] >= 0) inRegister(v, 0);  // storeOutputs reads it from a register.
  }

  void storeOutputs(std::uint32_t v) {
    const int r = values_[v].reg;
    for (int k = outputsAt_[v]; k >= 0; k = nextOutput_[k]) {
      const auto disp = static_cast<std::int32_t>(8 * k);
      if (blocks_) {
        a_.vmovupd(x86::ptr(out_, 4 * disp), x86::ymm(r));
      } else if (batch_) {
        const auto row = static_cast<std::int32_t>(8 * p_.outputs.size());
        a_.vmovlpd(x86::ptr(out_, disp), x86::xmm(r));
        a_.vmovhpd(x86::ptr(out_, disp + row), x86::xmm(r));
        a_.vextractf128(x86::xmm(kScratchB), x86::ymm(r), 1);
        a_.vmovlpd(x86::ptr(out_, disp + 2 * row), x86::xmm(kScratchB));
        a_.vmovhpd(x86::ptr(out_, disp + 3 * row), x86::xmm(kScratchB));
      } else {
        a_.movsd(x86::ptr(out_, disp), x86::xmm(r));
      }
    }
    if (lastUse_[v] == 0 && outputsAt_[v] >= 0) retire(v, 0);  // Output only: free now.
  }

  void storeConstOutputs(std::uint32_t v) {
    if (outputsAt_[v] < 0) return;
    a_.mov(x86::rax, std::bit_cast<std::uint64_t>(p_.code[v].value));
    const int rows = batch_ ? 4 : 1;
    for (int k = outputsAt_[v]; k >= 0; k = nextOutput_[k]) {
      for (int j = 0; j < rows; ++j) {
        const auto disp = static_cast<std::int32_t>(
            8 * (blocks_ ? 4 * k + j : k + j * static_cast<int>(p_.outputs.size())));
        a_.mov(x86::qword_ptr(out_, disp), x86::rax);
      }
    }
  }

  x86::Assembler& a_;
  const Program& p_;
  const std::vector<std::uint32_t>& lastUse_;
  const bool batch_;
  const bool blocks_;  // Batch kernel reading and writing lane blocks (x86_compiler.hpp).
  const bool vex_ = hostHasAvx();  // AVX encodings allowed in the scalar function too.
  const bool frame_;
  const int width_;
  bool calls_ = false;
  x86::Gp state_, out_;
  asmjit::Label poolLabel_, entryLabel_;
  std::vector<int> outputsAt_, nextOutput_, pool_, partner_;
  std::vector<bool> precomputed_;
  std::vector<Value> values_;
  int owner_[kValueRegs] = {};
  std::vector<int> freeSlots_;
  int slotCount_ = 0;
};

// Whether more values than there are registers may be live at once (constants included: a
// constant loaded into a register stays there until its last use), i.e. whether the code may
// spill and so needs a frame. Deciding this up front saves emitting large programs twice.
bool mayNeedSpills(const Program& program, const std::vector<std::uint32_t>& lastUse) {
  const std::size_t n = program.code.size();
  std::vector<int> dying(n, 0);  // Values whose last use is instruction i.
  int live = 0;
  for (std::size_t i = 0; i < n; ++i) {
    live -= dying[i];
    if (lastUse[i] <= i) continue;             // Never held past instruction i.
    if (++live > kValueRegs - 1) return true;  // Keep one register for the result.
    ++dying[lastUse[i]];
  }
  return false;
}

NativeCode compile(const Program& program, Layout layout) {
  const bool batch = layout != Layout::Scalar;
  if (batch && !hostHasAvx2()) throw CompileError("the CPU has no AVX2");
  Runtime& rt = runtime();
  const auto lastUse = lastUses(program);
  bool frame = batch || program.hasCalls() || mayNeedSpills(program, lastUse);
  for (;;) {
    asmjit::CodeHolder code;
    RecordingErrorHandler errors;
    code.init(rt.jit->environment());
    code.setErrorHandler(&errors);
    x86::Assembler assembler(&code);
    Emitter emitter(assembler, program, lastUse, layout, frame);
    try {
      emitter.emit();
    } catch (const NeedFrame&) {
      frame = true;
      continue;
    }
    if (errors.error != asmjit::kErrorOk) {
      throw CompileError(std::string("asmjit: ") + errors.text);
    }
    void* base = nullptr;
    const asmjit::Error err = rt.jit->add(&base, &code);
    if (err != asmjit::kErrorOk) {
      throw CompileError(std::string("asmjit: ") + asmjit::DebugUtils::errorAsString(err));
    }
    void* entry = static_cast<char*>(base) + code.labelOffset(emitter.entryLabel());
    return NativeCode(base, entry, code.codeSize());
  }
}

}  // namespace

NativeCode::~NativeCode() {
  if (base_) runtime().jit->release(base_);
}

bool jitAvailable() { return true; }

bool hostHasAvx() {
  static const bool has =
      !sse2OnlyRequested() && asmjit::CpuInfo::host().hasFeature(asmjit::CpuFeatures::X86::kAVX);
  return has;
}

bool hostHasAvx2() {
  static const bool has =
      !sse2OnlyRequested() && asmjit::CpuInfo::host().hasFeature(asmjit::CpuFeatures::X86::kAVX2);
  return has;
}

bool jitUsesDualMapping() { return runtime().dualMapping; }

NativeCode compileScalar(const Program& program) { return compile(program, Layout::Scalar); }
NativeCode compileBatch(const Program& program) { return compile(program, Layout::StateRows); }
NativeCode compileLaneBlocks(const Program& program) {
  return compile(program, Layout::LaneBlocks);
}

#else  // No JIT in this build (GPFD_WITH_JIT=OFF, or not x86-64): the interpreter runs everything.

NativeCode::~NativeCode() = default;
bool jitAvailable() { return false; }
// Without the JIT nothing runs AVX code, so the host's features do not matter.
bool hostHasAvx() { return false; }
bool hostHasAvx2() { return false; }
bool jitUsesDualMapping() { return false; }
NativeCode compileScalar(const Program&) { throw CompileError("built without the JIT"); }
NativeCode compileBatch(const Program&) { throw CompileError("built without the JIT"); }
NativeCode compileLaneBlocks(const Program&) { throw CompileError("built without the JIT"); }

#endif

}  // namespace gpfd::jit
