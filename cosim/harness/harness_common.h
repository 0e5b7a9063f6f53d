// What the bulk harnesses (bulk_main.cpp, axis_main.cpp) share: words of up to 8 uint64
// limbs onto and out of the Verilated model's ports, and the reset sequence. Not part of
// the design.
#ifndef IRNUC_HARNESS_COMMON_H
#define IRNUC_HARNESS_COMMON_H

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace irnuc_harness {

// A word of `limbs` uint64 (bit 0 first) onto a port: the port types Verilator uses hold
// up to 64 bits (CData..QData), wider ports are VlWide (32-bit words); bits above the port
// are dropped.
template <typename T>
inline void set_word(T& port, const uint64_t* w, uint32_t limbs) {
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
