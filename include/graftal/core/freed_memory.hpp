// How a long-running process (the Python module, the studio server) keeps the memory one
// derivation frees for the next. By default the C library hands large freed blocks back to
// the system and the next derivation takes them again, page by page: a sweep of small
// derivations then spends half its time in page faults. The library never calls this; a
// front end does, once, at start.
#pragma once

namespace graftal {

// Blocks below 32 MiB come from the heap, and up to 128 MiB of freed heap is kept, unless
// GLIBC_TUNABLES already sets the C library's malloc. Nothing happens where the C library
// is not glibc.
void keepFreedMemoryForReuse();

}  // namespace graftal
