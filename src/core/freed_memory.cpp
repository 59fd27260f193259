#include "graftal/core/freed_memory.hpp"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace graftal {

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
    // The user's own settings win.
    if (const char* tunables = std::getenv("GLIBC_TUNABLES"))
        if (std::strstr(tunables, "glibc.malloc.")) return;
    // A fixed mmap threshold also stops glibc from raising it as blocks are freed, which is
    // what lets the heap's top be trimmed after every derivation.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
}

}  // namespace graftal
