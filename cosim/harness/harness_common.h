// What the bulk harnesses (bulk_main.cpp, axis_main.cpp) share: words of up to 8 uint64
// limbs onto and out of the Verilated model's ports, and the reset sequence. Not part of
// the design.
#ifndef IRNUC_HARNESS_COMMON_H
#define IRNUC_HARNESS_COMMON_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace irnuc_harness {

// A word of `limbs` uint64 (bit 0 first) onto a port: the port types Verilator uses hold
// up to 64 bits (CData..QData), wider ports are VlWide (32-bit words); bits above the port
// are dropped. A little-endian uint64 is its two 32-bit halves low first, the order of
// VlWide's words: the limbs are copied as bytes (one copy per word instead of a loop with
// a shift per 32-bit word, a few percent of a bulk run with 2-limb coefficient words).
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "set_word copies limbs as bytes");
template <typename T>
inline void set_word(T& port, const uint64_t* w, uint32_t limbs) {
    if constexpr (std::is_integral_v<T>) {
        port = static_cast<T>(w[0]);
    } else {
        constexpr size_t n = sizeof(port.m_storage) / sizeof(port.m_storage[0]);
        static_assert(sizeof(port.m_storage[0]) == 4, "VlWide words are 32 bits");
        const size_t copied = std::min<size_t>(n, 2 * size_t(limbs));
        std::memcpy(port.m_storage, w, 4 * copied);
        for (size_t i = copied; i < n; ++i) port.m_storage[i] = 0;
    }
}

// A port of up to 64 bits as a uint64 (a wider port's low 64 bits).
template <typename T>
inline uint64_t get_word(const T& port) {
    if constexpr (std::is_integral_v<T>) {
        return static_cast<uint64_t>(port);
    } else {
        return uint64_t(port.m_storage[0]) | (uint64_t(port.m_storage[1]) << 32);
    }
}

// The reset: the caller has set the clock low, rst_ni low and every input idle; one eval,
// three rising edges in reset, rst_ni released between edges (with the clock low), then one
// more edge with every input still idle: AXI lets a master raise a valid only after the
// first rising edge that follows the release (irnuc_axis_assert's a_reset_idle).
template <typename T>
inline void reset_sequence(T& top) {
    top.eval();
    for (int i = 0; i < 3; ++i) {
        top.clk_i = 1;
        top.eval();
        top.clk_i = 0;
        top.eval();
    }
    top.rst_ni = 1;
    top.eval();
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
}

}  // namespace irnuc_harness

#endif  // IRNUC_HARNESS_COMMON_H
