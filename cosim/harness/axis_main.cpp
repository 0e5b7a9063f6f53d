// Bulk co-simulation harness for irnuc_axis_top (Verilator --cc --exe, no cocotb, no VPI):
// the sign-off's recommendation through the top it is synthesized with. Not part of the
// design. cosim/axis_bulk.py writes the stimulus from the golden model, builds this file
// against the Verilated top (axis_top.h in the build folder names the model's class) and
// compares every output word in numpy.
//
//   axis_bulk DIR
//
// DIR holds (little-endian, written by cosim/axis_bulk.py):
//   meta.txt      "beats coef_words coef_limbs foff_words acc_words writes out_video
//                  out_acc out_foff seed stall_percent idle_percent"
//   video.bin     uint32 per s_axis_video beat: bits 15:0 tdata, bit 16 tuser[0] (start
//                 of frame), bit 17 tlast (end of line)
//   coef.bin      coef_limbs uint64 per s_axis_coef word (bit 0 first); coef_last.bin one
//                 uint8 tlast per word
//   foff.bin, acc.bin  uint64 per s_axis_foff / s_axis_acc word; foff_last.bin,
//                 acc_last.bin one uint8 tlast per word
//   writes.bin    (uint64 beat, uint32 address, uint32 data) per AXI4-Lite write, in
//                 order: the write is made, and its response taken, before the video
//                 stream offers beat `beat` (a frame's registers land before it starts)
// and the harness writes out_video.bin (uint32 per m_axis_video beat, as video.bin),
// out_acc.bin / out_foff.bin (uint64 per m_axis_acc / m_axis_foff word, bit 63 its tlast)
// and prints one JSON line: cycles, outputs, write responses not OKAY, irq_o at the end.
//
// Timing (as bulk_main.cpp): inputs set with the clock low, one eval settles the readies,
// handshakes decided from the values before the edge, then the rising edge. The stream
// sources go idle `idle_percent` of the cycles and m_axis_video is back-pressured
// `stall_percent` of them (a seeded xorshift), so the run is not only the full-rate path.

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "axis_top.h"
#include "harness_common.h"
#include "verilated.h"

namespace {

[[noreturn]] void die(const std::string& what) {
    std::printf("{\"error\": \"%s\"}\n", what.c_str());
    std::exit(2);
}

template <typename T>
std::vector<T> load(const std::string& path, uint64_t n) {
    std::vector<T> v(n);
    if (n == 0) return v;
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) die("cannot open " + path);
    if (std::fread(v.data(), sizeof(T), n, f) != n) die("short file " + path);
    std::fclose(f);
    return v;
}

template <typename T>
void save(const std::string& path, const std::vector<T>& v) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) die("cannot write " + path);
    if (!v.empty() && std::fwrite(v.data(), sizeof(T), v.size(), f) != v.size())
        die("short write " + path);
    std::fclose(f);
}

using irnuc_harness::get_word;
using irnuc_harness::set_word;

struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
    uint32_t percent() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        return static_cast<uint32_t>(s % 100);
    }
};

struct Write {
    uint64_t beat;
    uint32_t addr;
    uint32_t data;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) die("usage: axis_bulk DIR");
    const std::string dir = argv[1];
    uint64_t beats, cw, limbs, fw, aw, nw, n_out, n_acc, n_foff, seed, stall, idle;
    {
        FILE* f = std::fopen((dir + "/meta.txt").c_str(), "r");
        if (!f) die("no meta.txt");
        if (std::fscanf(f, "%" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64
                           " %" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64 " %" SCNu64,
                        &beats, &cw, &limbs, &fw, &aw, &nw, &n_out, &n_acc, &n_foff, &seed,
                        &stall, &idle) != 12)
            die("bad meta.txt");
        std::fclose(f);
    }
    const auto video = load<uint32_t>(dir + "/video.bin", beats);
    const auto coef = load<uint64_t>(dir + "/coef.bin", cw * limbs);
    const auto coef_last = load<uint8_t>(dir + "/coef_last.bin", cw);
    const auto foff = load<uint64_t>(dir + "/foff.bin", fw);
    const auto foff_last = load<uint8_t>(dir + "/foff_last.bin", fw);
    const auto acc = load<uint64_t>(dir + "/acc.bin", aw);
    const auto acc_last = load<uint8_t>(dir + "/acc_last.bin", aw);
    const auto wraw = load<uint64_t>(dir + "/writes.bin", 2 * nw);
    std::vector<Write> writes(nw);
    for (uint64_t i = 0; i < nw; ++i)
        writes[i] = {wraw[2 * i], static_cast<uint32_t>(wraw[2 * i + 1]),
                     static_cast<uint32_t>(wraw[2 * i + 1] >> 32)};

    auto ctx = std::make_unique<VerilatedContext>();
    ctx->commandArgs(argc, argv);
    auto top = std::make_unique<AxisTop>(ctx.get());
    Rng rng(seed);

    auto idle_all = [&]() {
        top->s_axis_video_tvalid = 0;
        top->s_axis_coef_tvalid = 0;
        top->s_axis_foff_tvalid = 0;
        top->s_axis_acc_tvalid = 0;
        top->m_axis_video_tready = 0;
        top->m_axis_acc_tready = 0;
        top->m_axis_foff_tready = 0;
        top->s_axil_awvalid = 0;
        top->s_axil_wvalid = 0;
        top->s_axil_bready = 0;
        top->s_axil_arvalid = 0;
        top->s_axil_rready = 0;
        top->s_axil_awprot = 0;
        top->s_axil_arprot = 0;
        top->s_axil_wstrb = 0xF;
    };
    top->clk_i = 0;
    top->rst_ni = 0;
    idle_all();
    irnuc_harness::reset_sequence(*top);

    std::vector<uint32_t> out_video;
    out_video.reserve(n_out);
    std::vector<uint64_t> out_acc, out_foff;
    out_acc.reserve(n_acc);
    out_foff.reserve(n_foff);
    uint64_t vi = 0, ci = 0, fi = 0, ai = 0, wi = 0, cycle = 0, bad_resp = 0;
    bool vv = false, cv = false, fv = false, av = false;
    // AXI4-Lite write in flight: address and data offered until each is taken, then the
    // response awaited.
    bool w_active = false, aw_done = false, w_done = false;
    const uint64_t limit = 40 * (beats + n_out + 100) + 200000 + 400 * nw;
    auto pending = [&]() {
        return out_video.size() < n_out || out_acc.size() < n_acc || out_foff.size() < n_foff ||
               wi < nw || vi < beats;
    };
    while (pending()) {
        if (cycle >= limit) {
            std::printf("{\"error\": \"timeout\", \"cycles\": %" PRIu64 ", \"outputs\": %zu, "
                        "\"beats_in\": %" PRIu64 ", \"writes\": %" PRIu64 "}\n",
                        cycle, out_video.size(), vi, wi);
            return 1;
        }
        // The register writes due before the next video beat.
        if (!w_active && wi < nw && writes[wi].beat <= vi && !vv) {
            w_active = true;
            aw_done = w_done = false;
        }
        if (w_active) {
            top->s_axil_awaddr = writes[wi].addr;
            top->s_axil_wdata = writes[wi].data;
            top->s_axil_awvalid = !aw_done;
            top->s_axil_wvalid = !w_done;
            top->s_axil_bready = 1;
        } else {
            top->s_axil_awvalid = 0;
            top->s_axil_wvalid = 0;
            top->s_axil_bready = 0;
        }
        // The video waits for the writes of its beat (a frame's registers first).
        const bool blocked = wi < nw && writes[wi].beat <= vi;
        if (!vv && vi < beats && !blocked) vv = idle == 0 || rng.percent() >= idle;
        if (!cv && ci < cw) cv = idle == 0 || rng.percent() >= idle;
        if (!fv && fi < fw) fv = idle == 0 || rng.percent() >= idle;
        if (!av && ai < aw) av = idle == 0 || rng.percent() >= idle;
        if (vv) {
            top->s_axis_video_tdata = video[vi] & 0xFFFF;
            top->s_axis_video_tuser = (video[vi] >> 16) & 1;
            top->s_axis_video_tlast = (video[vi] >> 17) & 1;
        }
        if (cv) {
            set_word(top->s_axis_coef_tdata, &coef[ci * limbs], static_cast<uint32_t>(limbs));
            top->s_axis_coef_tlast = coef_last[ci];
        }
        if (fv) {
            set_word(top->s_axis_foff_tdata, &foff[fi], 1);
            top->s_axis_foff_tlast = foff_last[fi];
        }
        if (av) {
            set_word(top->s_axis_acc_tdata, &acc[ai], 1);
            top->s_axis_acc_tlast = acc_last[ai];
        }
        top->s_axis_video_tvalid = vv;
        top->s_axis_coef_tvalid = cv;
        top->s_axis_foff_tvalid = fv;
        top->s_axis_acc_tvalid = av;
        const bool rdy = stall == 0 || rng.percent() >= stall;
        top->m_axis_video_tready = rdy;
        top->m_axis_acc_tready = 1;
        top->m_axis_foff_tready = 1;
        top->eval();
        // Handshakes seen by the flops at this edge.
        const bool v_go = vv && top->s_axis_video_tready;
        const bool c_go = cv && top->s_axis_coef_tready;
        const bool f_go = fv && top->s_axis_foff_tready;
        const bool a_go = av && top->s_axis_acc_tready;
        if (top->m_axis_video_tvalid && rdy)
            out_video.push_back(static_cast<uint32_t>(get_word(top->m_axis_video_tdata) & 0xFFFF) |
                                (uint32_t(top->m_axis_video_tuser & 1) << 16) |
                                (uint32_t(top->m_axis_video_tlast & 1) << 17));
        if (top->m_axis_acc_tvalid)
            out_acc.push_back((get_word(top->m_axis_acc_tdata) & ~(1ull << 63)) |
                              (uint64_t(top->m_axis_acc_tlast & 1) << 63));
        if (top->m_axis_foff_tvalid)
            out_foff.push_back((get_word(top->m_axis_foff_tdata) & ~(1ull << 63)) |
                               (uint64_t(top->m_axis_foff_tlast & 1) << 63));
        bool w_end = false;
        if (w_active) {
            if (top->s_axil_awvalid && top->s_axil_awready) aw_done = true;
            if (top->s_axil_wvalid && top->s_axil_wready) w_done = true;
            if (top->s_axil_bvalid) {
                if (top->s_axil_bresp != 0) ++bad_resp;
                w_end = true;
            }
        }
        top->clk_i = 1;
        top->eval();
        top->clk_i = 0;
        ++cycle;
        if (v_go) { ++vi; vv = false; }
        if (c_go) { ++ci; cv = false; }
        if (f_go) { ++fi; fv = false; }
        if (a_go) { ++ai; av = false; }
        if (w_end) { w_active = false; ++wi; }
    }
    // Quiet tail: nothing more may come out.
    uint64_t extra = 0;
    idle_all();
    top->m_axis_video_tready = 1;
    top->m_axis_acc_tready = 1;
    top->m_axis_foff_tready = 1;
    for (int i = 0; i < 4096; ++i) {
        top->eval();
        extra += top->m_axis_video_tvalid + top->m_axis_acc_tvalid + top->m_axis_foff_tvalid;
        top->clk_i = 1;
        top->eval();
        top->clk_i = 0;
    }
    top->eval();
    save(dir + "/out_video.bin", out_video);
    save(dir + "/out_acc.bin", out_acc);
    save(dir + "/out_foff.bin", out_foff);
    std::printf("{\"cycles\": %" PRIu64 ", \"outputs\": %zu, \"acc_out\": %zu, \"foff_out\": %zu, "
                "\"inputs\": [%" PRIu64 ", %" PRIu64 ", %" PRIu64 ", %" PRIu64 "], \"writes\": %" PRIu64
                ", \"bad_responses\": %" PRIu64 ", \"extra\": %" PRIu64 ", \"irq\": %d}\n",
                cycle, out_video.size(), out_acc.size(), out_foff.size(), vi, ci, fi, ai, wi,
                bad_resp, extra, int(top->irq_o));
    top->final();
    return 0;
}
