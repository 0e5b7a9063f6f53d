// Bulk co-simulation harness for nuc_dpc_top, method_dpc_top and the stage tops
// method_drift_top and method_ffc_top (Verilator --cc --exe, no cocotb, no VPI).
//
// Reads the whole stimulus from raw binary files, clocks the Verilated model itself and
// writes every output pixel to a raw binary file; cosim/bulk.py (run_bulk) writes the
// inputs with ndarray.tofile, reads the outputs with np.fromfile and compares them with
// the golden model in numpy. Not part of the design. The top is chosen at build time by
// bulk_top.h in the build folder (written by cosim/bulk.py): it includes the model's
// header, names its class BulkTop and sets BULK_FRAME_WORD when the top has the frame
// word port s_pix_frame_i (method_dpc_top, the stage tops), BULK_BLIND for the s_blind
// stream and the blind_ref_i / drift_gain_i registers (method_drift_top), BULK_FFC for the
// shutter flag, s_foff, s_acc, m_acc and m_foff (method_ffc_top).
//
// Usage: nuc_dpc_bulk PIX COEF OUT N W H PIXBYTES [IDLE_PCT STALL_PCT SEED [FRAMES LIMBS
//                     [KEY=VALUE ...]]]
//   PIX      N raw codes, little-endian unsigned of PIXBYTES (2 or 4) bytes each
//   COEF     coefficient images: M images of W*H words, each word LIMBS little-endian
//            uint64 (bit 0 first; docs/datapath.md, docs/rtl.md "Methods")
//   OUT      written: one little-endian uint32 per output pixel,
//            bit 31 sof, bit 30 eol, bits [OutBits-1:0] the corrected code (out16=1: one
//            uint16, bit 15 sof, bit 14 eol)
//   N        pixels (a whole number of W x H frames, streamed back to back)
//   IDLE_PCT percent of cycles each input source stays idle (0 = always valid)
//   STALL_PCT percent of cycles the output is back-pressured (0 = always ready)
//   SEED     seed of the xorshift generator behind IDLE_PCT and STALL_PCT
//   FRAMES   per frame two little-endian uint64: the image it streams (0..M-1) and its
//            frame word (s_pix_frame_i); without it every frame streams image 0 (M = 1)
//   LIMBS    uint64 words per coefficient word (default 1)
//   KEY=VALUE options of the stage tops:
//     cols=C        uint64 per frame in FRAMES (default 2). method_drift_top: 3, the third
//                   the number of the frame's s_blind items; method_ffc_top: 5, the third
//                   the shutter flag (s_pix_shutter_i), the fourth the m_foff frame whose
//                   words s_foff streams (k + 1: the k-th refresh frame's words, written
//                   back from m_foff; 0: zeros, the corrections after reset), the fifth the
//                   m_acc frame whose words s_acc streams (k + 1; 0: the frame takes none)
//     blind=PATH    method_drift_top: the s_blind items, one uint64 each, frame after frame
//                   (each frame's last one flagged s_blind_last_i)
//     blind_ref=V drift_gain=V   the registers (two's complement bit patterns)
//     skip=F        the first F frames of PIX and FRAMES are another shard's: start at frame F
//                   (the shards of one run read one file each; default 0)
//     eval=public   every eval through the model's public eval() (the previous path, kept
//                   as the baseline of benchmarks/bench_methods_cosim.py); default: see
//                   "Evals" below
//     out16=1       16-bit output words (OutBits <= 14; half the bytes written)
//     outputs=K     m_pix outputs expected (default N; method_ffc_top: held frames have none)
//     acc=PATH acc_n=K foff=PATH foff_n=K   method_ffc_top: m_acc and m_foff written, one
//                   uint64 per word, K words expected of each. The harness is the external
//                   memory: s_foff and s_acc read these outputs back, a word only once the
//                   DUT has written it (the source waits: latency does not matter)
// Prints one JSON line: cycles, outputs, extra outputs (of every output stream),
// first/last output cycle, the items each input took (pixels, words, then blind or
// foff and acc),
// frame_err, stall_cycles (cycles between the first and the last output with the output
// back-pressured: last - first + 1 = outputs + stall_cycles when no cycle is lost).
// Exit status 0 when the run completed (mismatches are judged in numpy).
//
// Evals: the model's public eval() is eval_step(): Verilator's per-call bookkeeping (the
// deleter of class objects under a mutex, the end-of-eval message queue of threaded models)
// around the generated scheduler V<top>___024root___eval. The harness calls the scheduler
// directly (bulk_top.h declares it), once per cycle, on the rising edge: the clock-low
// eval of the previous path only settled what the inputs drive combinationally inside the
// DUT (its "ico" region), which the scheduler evaluates again before the edge anyway, and
// no output port follows an input combinationally (every stream boundary is a register:
// the outputs read before the edge are those the previous edge left). So that the
// scheduler still sees a rising edge without the low eval, BULK_CLOCK_WAS_LOW sets its
// record of the clock's previous value (generated name; the build fails loudly if a
// Verilator renames it). The public eval() runs at reset, as the clock-low eval on every
// 4096th cycle and in the idle tail, so that bookkeeping still runs; this single-threaded
// model queues no messages and creates no class objects in its cycles, so the outputs,
// assertions ($error, $stop) and cycle counts are the same as with two public evals per
// cycle (eval=public, the previous path: about 1.35x the CPU per cycle, measured).
//
// Timing: inputs are set while the clock is low, the handshakes are decided from the
// values present before the edge (as the DUT's flops see them), then the rising edge is
// evaluated. Positions are counters, not divisions: the harness's own work per cycle is
// small next to the model's.

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bulk_top.h"
#include "harness_common.h"
#include "verilated.h"

namespace {

using irnuc_harness::get_word;
using irnuc_harness::set_word;

// The KEY=VALUE options after the positional arguments.
struct Options {
    uint32_t cols = 2;
    const char* blind = nullptr;
    uint64_t blind_ref = 0, drift_gain = 0;
    uint64_t outputs = UINT64_MAX;  // default: N
    const char* acc = nullptr;
    const char* foff = nullptr;
    uint64_t acc_n = 0, foff_n = 0;
    uint64_t skip = 0;
    bool public_eval = false;
    bool out16 = false;
};

Options parse_options(int argc, char** argv, int first);

// Every input stream idle and every output's ready at `ready` (reset, the idle tail).
template <typename T>
void idle_streams(T* top, bool ready) {
    top->s_pix_valid_i = 0;
    top->s_coef_valid_i = 0;
    top->m_pix_ready_i = ready;
#ifdef BULK_BLIND
    top->s_blind_valid_i = 0;
#endif
#ifdef BULK_FFC
    top->s_foff_valid_i = 0;
    top->s_acc_valid_i = 0;
    top->m_acc_ready_i = ready;
    top->m_foff_ready_i = ready;
#endif
}

// xorshift64*: a cheap, seedable generator for idle gaps and backpressure.
struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ULL + 1) {}
    uint32_t percent() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return static_cast<uint32_t>(((s * 0x2545F4914F6CDD1DULL) >> 32) % 100);
    }
};

[[noreturn]] void die(const char* msg, const char* arg) {
    std::fprintf(stderr, "nuc_dpc_bulk: %s %s\n", msg, arg ? arg : "");
    std::exit(2);
}

Options parse_options(int argc, char** argv, int first) {
    Options o;
    for (int i = first; i < argc; ++i) {
        const char* eq = std::strchr(argv[i], '=');
        if (!eq) die("an option is KEY=VALUE, got", argv[i]);
        const std::string key(argv[i], eq - argv[i]);
        const char* v = eq + 1;
        if (key == "cols") o.cols = static_cast<uint32_t>(std::strtoul(v, nullptr, 10));
        else if (key == "blind") o.blind = v;
        else if (key == "blind_ref") o.blind_ref = std::strtoull(v, nullptr, 10);
        else if (key == "drift_gain") o.drift_gain = std::strtoull(v, nullptr, 10);
        else if (key == "outputs") o.outputs = std::strtoull(v, nullptr, 10);
        else if (key == "acc") o.acc = v;
        else if (key == "acc_n") o.acc_n = std::strtoull(v, nullptr, 10);
        else if (key == "foff") o.foff = v;
        else if (key == "foff_n") o.foff_n = std::strtoull(v, nullptr, 10);
        else if (key == "skip") o.skip = std::strtoull(v, nullptr, 10);
        else if (key == "eval" && std::strcmp(v, "public") == 0) o.public_eval = true;
        else if (key == "out16" && std::strcmp(v, "1") == 0) o.out16 = true;
        else die("unknown option", argv[i]);
    }
    return o;
}

// n items of type P from `path`, after the first `skip` items.
template <typename P>
std::vector<P> read_file(const char* path, uint64_t n, uint64_t skip = 0) {
    std::vector<P> v(n);
    if (n == 0) return v;
    FILE* f = std::fopen(path, "rb");
    if (!f) die("cannot open", path);
    if (skip && std::fseek(f, static_cast<long>(skip * sizeof(P)), SEEK_SET) != 0)
        die("cannot seek in", path);
    if (std::fread(v.data(), sizeof(P), n, f) != n) die("short read of", path);
    std::fclose(f);
    return v;
}

// P: a raw code as PIX holds it; O: an output word (uint32 or, out16=1, uint16).
template <typename P, typename O>
int run(int argc, char** argv, const Options& opt, VerilatedContext* ctx) {
    constexpr unsigned sof_bit = 8 * sizeof(O) - 1, eol_bit = 8 * sizeof(O) - 2;
    const uint64_t n = std::strtoull(argv[4], nullptr, 10);
    const uint32_t w = static_cast<uint32_t>(std::strtoul(argv[5], nullptr, 10));
    const uint32_t h = static_cast<uint32_t>(std::strtoul(argv[6], nullptr, 10));
    const uint32_t idle = argc > 8 ? static_cast<uint32_t>(std::atoi(argv[8])) : 0;
    const uint32_t stall = argc > 9 ? static_cast<uint32_t>(std::atoi(argv[9])) : 0;
    const uint64_t seed = argc > 10 ? std::strtoull(argv[10], nullptr, 10) : 1;
    if (w == 0 || h == 0 || n == 0 || n % (uint64_t(w) * h) != 0)
        die("N must be a positive multiple of W*H; got N =", argv[4]);
    if (idle > 99 || stall > 99) die("IDLE_PCT and STALL_PCT must be in 0..99", "");

    const uint64_t frame = uint64_t(w) * h;
    const std::vector<P> pix = read_file<P>(argv[1], n, opt.skip * frame);
    const uint64_t frames = n / frame;
    const uint32_t limbs = argc > 12 ? static_cast<uint32_t>(std::atoi(argv[12])) : 1;
    if (limbs < 1 || limbs > 8) die("LIMBS must be in 1..8, got", argc > 12 ? argv[12] : "");
    const uint32_t cols = opt.cols;
    if (cols < 2 || cols > 8) die("cols must be in 2..8", "");
    // Per frame: the image it streams, its frame word, then the stage's columns.
    std::vector<uint64_t> fwords(cols * frames, 0);
    if (argc > 11) fwords = read_file<uint64_t>(argv[11], cols * frames, cols * opt.skip);
    uint64_t images = 1;
    for (uint64_t f = 0; f < frames; ++f)
        if (fwords[cols * f] + 1 > images) images = fwords[cols * f] + 1;
    const std::vector<uint64_t> coef = read_file<uint64_t>(argv[2], images * frame * limbs);
    const uint64_t n_out = opt.outputs == UINT64_MAX ? n : opt.outputs;
    std::vector<O> out(n_out);

#ifdef BULK_BLIND
    if (cols < 3 || !opt.blind) die("method_drift_top needs cols=3 and blind=PATH", "");
    uint64_t n_blind = 0;
    for (uint64_t f = 0; f < frames; ++f) {
        if (fwords[cols * f + 2] == 0) die("every frame needs a blind item", "");
        n_blind += fwords[cols * f + 2];
    }
    const std::vector<uint64_t> blind = read_file<uint64_t>(opt.blind, n_blind);
    uint64_t bi = 0, bf = 0, bpos = 0;  // blind item, its frame, its index in the frame
    bool bv = false;
#endif
#ifdef BULK_FFC
    if (cols < 5 || !opt.acc || !opt.foff) die("method_ffc_top needs cols=5, acc= and foff=", "");
    // The external memory: every word the DUT wrote, in order (k-th frame at k * frame).
    std::vector<uint64_t> acc_mem(opt.acc_n), foff_mem(opt.foff_n);
    std::vector<uint64_t> acc_frames;  // the frames that read s_acc
    for (uint64_t f = 0; f < frames; ++f) {
        if (fwords[cols * f + 3] * frame > opt.foff_n || fwords[cols * f + 4] * frame > opt.acc_n)
            die("a frame reads a write-back frame that is not expected", "");
        if (fwords[cols * f + 4]) acc_frames.push_back(f);
    }
    const uint64_t n_foff_in = n, n_acc_in = acc_frames.size() * frame;
    uint64_t ai = 0, fi = 0;        // s_acc and s_foff items taken
    uint64_t ao = 0, fo = 0;        // m_acc and m_foff words written
    bool av = false, fv = false;
#endif

    auto top = std::make_unique<BulkTop>(ctx);
    Rng rng(seed);

    // Reset: asserted with the clock low, three edges, released between edges.
    top->clk_i = 0;
    top->rst_ni = 0;
    top->frame_width_i = w;
    top->frame_height_i = h;
    idle_streams(top.get(), false);
#ifdef BULK_BLIND
    set_word(top->blind_ref_i, &opt.blind_ref, 1);
    set_word(top->drift_gain_i, &opt.drift_gain, 1);
#endif
    irnuc_harness::reset_sequence(*top);

    const uint64_t limit = 20 * (n + 100) + 50000;
    uint64_t pi = 0, ci = 0, oi = 0, cycle = 0, first = 0, last = 0;
    uint64_t stalls = 0, stalls_at_last = 0;  // output not ready, counted from the first output
    bool pv = false, cv = false;  // valid held until the transfer (AXI-Stream rule)
    uint64_t ppos = 0, cpos = 0;  // position in the frame of the next pixel and word
    uint64_t pf = 0, cf = 0;      // frame of the next pixel and word
    uint32_t px = 0;              // column of the next pixel
    auto pending = [&]() {
        bool more = oi < n_out;
#ifdef BULK_FFC
        more = more || ao < opt.acc_n || fo < opt.foff_n;
#endif
        return more;
    };
    while (pending()) {
        if (cycle >= limit) {
            std::printf("{\"error\": \"timeout\", \"cycles\": %" PRIu64 ", \"outputs\": %" PRIu64
                        "}\n", cycle, oi);
            return 1;
        }
        if (!pv && pi < n) pv = idle == 0 || rng.percent() >= idle;
        if (!cv && ci < n) cv = idle == 0 || rng.percent() >= idle;
        const bool rdy = stall == 0 || rng.percent() >= stall;
        if (pv) {
            top->s_pix_data_i = pix[pi];
            top->s_pix_sof_i = ppos == 0;
            top->s_pix_eol_i = px == w - 1;
#ifdef BULK_FRAME_WORD
            // The frame word is the same for every pixel of a frame and a port keeps what
            // was written: set at each frame's first pixel.
            if (ppos == 0) set_word(top->s_pix_frame_i, &fwords[cols * pf + 1], 1);
#endif
#ifdef BULK_FFC
            top->s_pix_shutter_i = fwords[cols * pf + 2] != 0;
#endif
        }
        if (cv) set_word(top->s_coef_data_i, &coef[(fwords[cols * cf] * frame + cpos) * limbs], limbs);
        top->s_pix_valid_i = pv;
        top->s_coef_valid_i = cv;
        top->m_pix_ready_i = rdy;
#ifdef BULK_BLIND
        if (!bv && bi < n_blind) bv = idle == 0 || rng.percent() >= idle;
        if (bv) {
            set_word(top->s_blind_data_i, &blind[bi], 1);
            top->s_blind_last_i = bpos + 1 == fwords[cols * bf + 2];
        }
        top->s_blind_valid_i = bv;
#endif
#ifdef BULK_FFC
        // s_foff / s_acc: the word the memory holds once the DUT wrote it (else wait).
        uint64_t fword = 0, aword = 0;
        if (!fv && fi < n_foff_in) {
            const uint64_t src = fwords[cols * (fi / frame) + 3];
            const uint64_t at = src ? (src - 1) * frame + fi % frame : 0;
            if (!src || at < fo) fv = idle == 0 || rng.percent() >= idle;
        }
        if (fv) {
            const uint64_t src = fwords[cols * (fi / frame) + 3];
            fword = src ? foff_mem[(src - 1) * frame + fi % frame] : 0;
            set_word(top->s_foff_data_i, &fword, 1);
        }
        if (!av && ai < n_acc_in) {
            const uint64_t at = (fwords[cols * acc_frames[ai / frame] + 4] - 1) * frame + ai % frame;
            if (at < ao) av = idle == 0 || rng.percent() >= idle;
        }
        if (av) {
            aword = acc_mem[(fwords[cols * acc_frames[ai / frame] + 4] - 1) * frame + ai % frame];
            set_word(top->s_acc_data_i, &aword, 1);
        }
        top->s_foff_valid_i = fv;
        top->s_acc_valid_i = av;
        const bool ardy = stall == 0 || rng.percent() >= stall;
        const bool frdy = stall == 0 || rng.percent() >= stall;
        top->m_acc_ready_i = ardy;
        top->m_foff_ready_i = frdy;
#endif
        // The clock-low eval: on the previous path every cycle, else only with the
        // housekeeping public eval (see "Evals": the fast path reads the outputs as the
        // previous rising edge left them, which is what this eval would give).
        const bool settle = opt.public_eval || (cycle & 4095) == 0;
        if (settle) top->eval();
        const bool pfire = pv && top->s_pix_ready_o;
        const bool cfire = cv && top->s_coef_ready_o;
        if (rdy && top->m_pix_valid_o) {
            if (oi == n_out) {
                std::printf("{\"error\": \"more than %" PRIu64 " outputs\", \"cycles\": %" PRIu64
                            "}\n", n_out, cycle);
                return 1;
            }
            out[oi++] = static_cast<O>((uint32_t(top->m_pix_sof_o) << sof_bit)
                                       | (uint32_t(top->m_pix_eol_o) << eol_bit)
                                       | uint32_t(top->m_pix_data_o));
            if (oi == 1) first = cycle;
            last = cycle;
            stalls_at_last = stalls;
        } else if (!rdy && oi > 0) {
            ++stalls;
        }
#ifdef BULK_BLIND
        const bool bfire = bv && top->s_blind_ready_o;
#endif
#ifdef BULK_FFC
        const bool ffire = fv && top->s_foff_ready_o;
        const bool afire = av && top->s_acc_ready_o;
        // A write-back word into the memory; one more than expected is an error.
        const auto write = [&](std::vector<uint64_t>& mem, uint64_t& count, uint64_t word,
                               const char* what) {
            if (count == mem.size()) {
                std::printf("{\"error\": \"more than %zu %s words\", \"cycles\": %" PRIu64
                            "}\n", mem.size(), what, cycle);
                return false;
            }
            mem[count++] = word;
            return true;
        };
        if (ardy && top->m_acc_valid_o && !write(acc_mem, ao, get_word(top->m_acc_data_o), "m_acc"))
            return 1;
        if (frdy && top->m_foff_valid_o
            && !write(foff_mem, fo, get_word(top->m_foff_data_o), "m_foff"))
            return 1;
#endif
        top->clk_i = 1;
        if (opt.public_eval) {
            top->eval();
        } else {
            if (!settle) BULK_CLOCK_WAS_LOW(top.get());
            BULK_EVAL(top.get());
        }
        top->clk_i = 0;
        ++cycle;
        if (pfire) {
            ++pi;
            pv = false;
            if (++ppos == frame) {
                ppos = 0;
                ++pf;
            }
            if (++px == w) px = 0;
        }
        if (cfire) {
            ++ci;
            cv = false;
            if (++cpos == frame) {
                cpos = 0;
                ++cf;
            }
        }
#ifdef BULK_BLIND
        if (bfire) {
            ++bi;
            bv = false;
            if (++bpos == fwords[cols * bf + 2]) {
                bpos = 0;
                ++bf;
            }
        }
#endif
#ifdef BULK_FFC
        if (ffire) {
            ++fi;
            fv = false;
        }
        if (afire) {
            ++ai;
            av = false;
        }
#endif
    }
    // A few more cycles, inputs idle and outputs ready: nothing more may come out.
    uint64_t extra = 0;
    idle_streams(top.get(), true);
    for (uint32_t i = 0; i < w + 64; ++i) {
        top->eval();
        extra += top->m_pix_valid_o;
#ifdef BULK_FFC
        extra += top->m_acc_valid_o;
        extra += top->m_foff_valid_o;
#endif
        top->clk_i = 1;
        top->eval();
        top->clk_i = 0;
    }
    const bool err = top->frame_err_o;
    top->final();

    FILE* f = std::fopen(argv[3], "wb");
    if (!f) die("cannot write", argv[3]);
    if (n_out && std::fwrite(out.data(), sizeof(O), n_out, f) != n_out)
        die("short write of", argv[3]);
    std::fclose(f);
    uint64_t side[2] = {0, 0};  // the stage's input items taken
#ifdef BULK_BLIND
    side[0] = bi;
#endif
#ifdef BULK_FFC
    side[0] = fi;
    side[1] = ai;
    for (int k = 0; k < 2; ++k) {
        const char* path = k ? opt.foff : opt.acc;
        const std::vector<uint64_t>& mem = k ? foff_mem : acc_mem;
        FILE* g = std::fopen(path, "wb");
        if (!g) die("cannot write", path);
        if (!mem.empty() && std::fwrite(mem.data(), sizeof(uint64_t), mem.size(), g) != mem.size())
            die("short write of", path);
        std::fclose(g);
    }
#endif
    std::printf("{\"cycles\": %" PRIu64 ", \"outputs\": %" PRIu64 ", \"extra\": %" PRIu64
                ", \"first_out_cycle\": %" PRIu64 ", \"last_out_cycle\": %" PRIu64
                ", \"inputs_taken\": [%" PRIu64 ", %" PRIu64 ", %" PRIu64 ", %" PRIu64
                "], \"frame_err\": %d, \"stall_cycles\": %" PRIu64 "}\n",
                cycle, oi, extra, first, last, pi, ci, side[0], side[1], err ? 1 : 0,
                stalls_at_last);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 8) {
        std::fprintf(stderr,
                     "usage: %s PIX COEF OUT N W H PIXBYTES [IDLE_PCT STALL_PCT SEED "
                     "[FRAMES LIMBS [KEY=VALUE ...]]]\n",
                     argv[0]);
        return 2;
    }
    auto ctx = std::make_unique<VerilatedContext>();
    ctx->commandArgs(1, argv);  // no plusargs for the design
    const Options opt = parse_options(argc, argv, 13);
    const int pix_bytes = std::atoi(argv[7]);
    if (pix_bytes == 2) {
        return opt.out16 ? run<uint16_t, uint16_t>(argc, argv, opt, ctx.get())
                         : run<uint16_t, uint32_t>(argc, argv, opt, ctx.get());
    }
    if (pix_bytes == 4) {
        return opt.out16 ? run<uint32_t, uint16_t>(argc, argv, opt, ctx.get())
                         : run<uint32_t, uint32_t>(argc, argv, opt, ctx.get());
    }
    die("PIXBYTES must be 2 or 4, got", argv[7]);
}
