// Bulk co-simulation harness for nuc_dpc_top and method_dpc_top (Verilator --cc --exe, no
// cocotb, no VPI).
//
// Reads the whole stimulus from raw binary files, clocks the Verilated model itself and
// writes every output pixel to a raw binary file; cosim/bulk.py (run_bulk) writes the
// inputs with ndarray.tofile, reads the outputs with np.fromfile and compares them with
// the golden model in numpy. Not part of the design. The top is chosen at build time by
// bulk_top.h in the build folder (written by cosim/bulk.py): it includes the model's
// header, names its class BulkTop and sets BULK_FRAME_WORD when the top has the frame
// word port s_pix_frame_i (method_dpc_top).
//
// Usage: nuc_dpc_bulk PIX COEF OUT N W H PIXBYTES [IDLE_PCT STALL_PCT SEED [FRAMES LIMBS]]
//   PIX      N raw codes, little-endian unsigned of PIXBYTES (2 or 4) bytes each
//   COEF     coefficient images: M images of W*H words, each word LIMBS little-endian
//            uint64 (bit 0 first; docs/datapath.md, docs/rtl.md "Methods")
//   OUT      written: one little-endian uint32 per output pixel,
//            bit 31 sof, bit 30 eol, bits [OutBits-1:0] the corrected code
//   N        pixels (a whole number of W x H frames, streamed back to back)
//   IDLE_PCT percent of cycles each input source stays idle (0 = always valid)
//   STALL_PCT percent of cycles the output is back-pressured (0 = always ready)
//   SEED     seed of the xorshift generator behind IDLE_PCT and STALL_PCT
//   FRAMES   per frame two little-endian uint64: the image it streams (0..M-1) and its
//            frame word (s_pix_frame_i); without it every frame streams image 0 (M = 1)
//   LIMBS    uint64 words per coefficient word (default 1)
// Prints one JSON line: cycles, outputs, extra outputs, first/last output cycle,
// frame_err, stall_cycles (cycles between the first and the last output with the output
// back-pressured: last - first + 1 = outputs + stall_cycles when no cycle is lost).
// Exit status 0 when the run completed (mismatches are judged in numpy).
//
// Timing: inputs are set while the clock is low, one eval settles the combinational
// readies, the handshakes are decided from the values present before the edge (as the
// DUT's flops see them), then the rising edge is evaluated. Two evals per cycle (Verilator
// sees an edge only between two evals). Positions are counters, not divisions: the
// harness's own work per cycle is small next to the model's.

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <type_traits>
#include <vector>

#include "bulk_top.h"
#include "verilated.h"

namespace {

// A word of `limbs` uint64 (bit 0 first) onto a port: the port types Verilator uses hold
// up to 64 bits (CData..QData), wider ports are VlWide (32-bit words); bits above the port
// are dropped.
template <typename T>
void set_word(T& port, const uint64_t* w, uint32_t limbs) {
    if constexpr (std::is_integral_v<T>) {
        port = static_cast<T>(w[0]);
    } else {
        constexpr size_t n = sizeof(port.m_storage) / sizeof(port.m_storage[0]);
        for (size_t i = 0; i < n; ++i) {
            const size_t k = i / 2;
            port.m_storage[i] = k < limbs ? static_cast<uint32_t>(w[k] >> (32 * (i % 2))) : 0;
        }
    }
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

template <typename P>
std::vector<P> read_file(const char* path, uint64_t n) {
    std::vector<P> v(n);
    FILE* f = std::fopen(path, "rb");
    if (!f) die("cannot open", path);
    if (std::fread(v.data(), sizeof(P), n, f) != n) die("short read of", path);
    std::fclose(f);
    return v;
}

template <typename P>
int run(int argc, char** argv, VerilatedContext* ctx) {
    const uint64_t n = std::strtoull(argv[4], nullptr, 10);
    const uint32_t w = static_cast<uint32_t>(std::strtoul(argv[5], nullptr, 10));
    const uint32_t h = static_cast<uint32_t>(std::strtoul(argv[6], nullptr, 10));
    const uint32_t idle = argc > 8 ? static_cast<uint32_t>(std::atoi(argv[8])) : 0;
    const uint32_t stall = argc > 9 ? static_cast<uint32_t>(std::atoi(argv[9])) : 0;
    const uint64_t seed = argc > 10 ? std::strtoull(argv[10], nullptr, 10) : 1;
    if (w == 0 || h == 0 || n == 0 || n % (uint64_t(w) * h) != 0)
        die("N must be a positive multiple of W*H; got N =", argv[4]);
    if (idle > 99 || stall > 99) die("IDLE_PCT and STALL_PCT must be in 0..99", "");

    const std::vector<P> pix = read_file<P>(argv[1], n);
    const uint64_t frame = uint64_t(w) * h;
    const uint64_t frames = n / frame;
    const uint32_t limbs = argc > 12 ? static_cast<uint32_t>(std::atoi(argv[12])) : 1;
    if (limbs < 1 || limbs > 8) die("LIMBS must be in 1..8, got", argc > 12 ? argv[12] : "");
    // Per frame: the image it streams and its frame word.
    std::vector<uint64_t> fwords(2 * frames, 0);
    if (argc > 11) fwords = read_file<uint64_t>(argv[11], 2 * frames);
    uint64_t images = 1;
    for (uint64_t f = 0; f < frames; ++f)
        if (fwords[2 * f] + 1 > images) images = fwords[2 * f] + 1;
    const std::vector<uint64_t> coef = read_file<uint64_t>(argv[2], images * frame * limbs);
    std::vector<uint32_t> out(n);

    auto top = std::make_unique<BulkTop>(ctx);
    Rng rng(seed);

    // Reset: asserted with the clock low, three edges, released between edges.
    top->clk_i = 0;
    top->rst_ni = 0;
    top->frame_width_i = w;
    top->frame_height_i = h;
    top->s_pix_valid_i = 0;
    top->s_coef_valid_i = 0;
    top->m_pix_ready_i = 0;
    top->eval();
    for (int i = 0; i < 3; ++i) {
        top->clk_i = 1;
        top->eval();
        top->clk_i = 0;
        top->eval();
    }
    top->rst_ni = 1;
    top->eval();

    const uint64_t limit = 20 * (n + 100) + 50000;
    uint64_t pi = 0, ci = 0, oi = 0, cycle = 0, first = 0, last = 0;
    uint64_t stalls = 0, stalls_at_last = 0;  // output not ready, counted from the first output
    bool pv = false, cv = false;  // valid held until the transfer (AXI-Stream rule)
    uint64_t ppos = 0, cpos = 0;  // position in the frame of the next pixel and word
    uint64_t pf = 0, cf = 0;      // frame of the next pixel and word
    uint32_t px = 0;              // column of the next pixel
    while (oi < n) {
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
            set_word(top->s_pix_frame_i, &fwords[2 * pf + 1], 1);
#endif
        }
        if (cv) set_word(top->s_coef_data_i, &coef[(fwords[2 * cf] * frame + cpos) * limbs], limbs);
        top->s_pix_valid_i = pv;
        top->s_coef_valid_i = cv;
        top->m_pix_ready_i = rdy;
        top->eval();
        const bool pfire = pv && top->s_pix_ready_o;
        const bool cfire = cv && top->s_coef_ready_o;
        if (rdy && top->m_pix_valid_o) {
            out[oi++] = (uint32_t(top->m_pix_sof_o) << 31) | (uint32_t(top->m_pix_eol_o) << 30)
                        | uint32_t(top->m_pix_data_o);
            if (oi == 1) first = cycle;
            last = cycle;
            stalls_at_last = stalls;
        } else if (!rdy && oi > 0) {
            ++stalls;
        }
        top->clk_i = 1;
        top->eval();
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
    }
    // A few more cycles, inputs idle and output ready: nothing more may come out.
    uint64_t extra = 0;
    top->s_pix_valid_i = 0;
    top->s_coef_valid_i = 0;
    top->m_pix_ready_i = 1;
    for (uint32_t i = 0; i < w + 64; ++i) {
        top->eval();
        extra += top->m_pix_valid_o;
        top->clk_i = 1;
        top->eval();
        top->clk_i = 0;
    }
    const bool err = top->frame_err_o;
    top->final();

    FILE* f = std::fopen(argv[3], "wb");
    if (!f) die("cannot write", argv[3]);
    if (std::fwrite(out.data(), sizeof(uint32_t), n, f) != n) die("short write of", argv[3]);
    std::fclose(f);
    std::printf("{\"cycles\": %" PRIu64 ", \"outputs\": %" PRIu64 ", \"extra\": %" PRIu64
                ", \"first_out_cycle\": %" PRIu64 ", \"last_out_cycle\": %" PRIu64
                ", \"inputs_taken\": [%" PRIu64 ", %" PRIu64 "], \"frame_err\": %d"
                ", \"stall_cycles\": %" PRIu64 "}\n",
                cycle, oi, extra, first, last, pi, ci, err ? 1 : 0, stalls_at_last);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 8) {
        std::fprintf(stderr,
                     "usage: %s PIX COEF OUT N W H PIXBYTES [IDLE_PCT STALL_PCT SEED "
                     "[FRAMES LIMBS]]\n",
                     argv[0]);
        return 2;
    }
    auto ctx = std::make_unique<VerilatedContext>();
    ctx->commandArgs(1, argv);  // no plusargs for the design
    const int pix_bytes = std::atoi(argv[7]);
    if (pix_bytes == 2) return run<uint16_t>(argc, argv, ctx.get());
    if (pix_bytes == 4) return run<uint32_t>(argc, argv, ctx.get());
    die("PIXBYTES must be 2 or 4, got", argv[7]);
}
