// The streamed derivation on several threads: the first steps are derived as held strings
// until there is work for every thread, that string is cut into chunks, and each chunk is
// expanded depth-first through the remaining steps by a worker into bounded blocks, which
// the caller receives in string order. The string, the text and the counts are those of
// streamDerivation() and of a held derivation, whatever the thread count; memory is a
// window of blocks ahead of the caller.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "graftal/core/byte_buffer.hpp"
#include "graftal/rewrite/derivation.hpp"

namespace graftal {

// Whether the parallel stream applies: the L-system can be streamed (streamingObstacle())
// and draws no random numbers (those need each module's position in its string, which only
// the one-thread stream keeps).
bool streamsInParallel(const LSystem& lsystem);

// The threads a thread count asks for (0: one per core).
unsigned parallelThreads(unsigned threads);

// Whether the parallel stream is expected to be at least as fast as a held derivation, for
// the string of `steps` steps on `threads` threads: it applies, there are two threads or
// more, the L-system is parametric (a held parametric string costs its parameters' memory
// at every step) and its last string is predicted to hold a million modules or more.
bool parallelStreamPays(const LSystem& lsystem, int steps, unsigned threads);

// A piece of the final string, in order: `size` modules, held in `modules` or written as the
// caller's writer wrote them (the text a writer formats in parallel).
struct StreamBlock {
    std::size_t size = 0;
    ModuleString modules;
    ByteBuffer text;
};

// Writes modules [begin, end) of a string into a block (on a worker's thread).
using StreamBlockWriter = std::function<void(const ModuleString& string, std::size_t begin,
                                             std::size_t end, StreamBlock& block)>;

// Calls consume(block) on the calling thread for every block of the string derived in
// `steps` steps (the file's derivation length when negative), in order. options.threads
// workers (0: one per core) derive, and write the final modules into the blocks with
// `write` (when empty: copied into block.modules); options.cancel is looked at by every
// worker and options.progress is called from the calling thread. Throws Error when
// !streamsInParallel(lsystem).
void streamDerivationParallel(const LSystem& lsystem, int steps, const StreamBlockWriter& write,
                              const std::function<void(const StreamBlock&)>& consume,
                              const DerivationOptions& options = {});

// The modules of each symbol (indexed by symbol id) of the string derived in `steps` steps,
// counted as the parallel stream meets them; the last step is not written, only the
// successor each module of the step before takes is counted.
std::vector<std::uint64_t> countStreamedParallel(const LSystem& lsystem, int steps,
                                                 const DerivationOptions& options = {});

}  // namespace graftal
