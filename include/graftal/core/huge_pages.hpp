// Asking the kernel to back a big buffer with huge pages before it is first written: a
// mesh of hundreds of megabytes otherwise takes a page fault for every 4 KiB, which costs
// more than writing it. Only an advice: where the kernel or the platform has no huge pages
// nothing changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace graftal {

// Advises huge pages for the 2 MiB-aligned part of [data, data + bytes) (small buffers are
// left alone).
inline void adviseHugePages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
    if (bytes < 4 * kHuge) return;
    const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

// The same for a vector's reserved storage.
template <class T>
void adviseHugePages(const std::vector<T>& v) {
    adviseHugePages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace graftal
