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

// A piece of the final string, in order: its modules, and whatever the workers' `prepare`
// made of them (the text a writer formats in parallel).
struct StreamBlock {
    std::size_t size = 0;  // modules in the block (`modules` may be cleared by `prepare`)
    ModuleString modules;
    std::string text;
};

// Calls consume(block) on the calling thread for every block of the string derived in
// `steps` steps (the file's derivation length when negative), in order. options.threads
// workers (0: one per core) derive, and call prepare(block) (when given) on each block
// before it is handed over; options.cancel is looked at by every worker and
// options.progress is called from the calling thread. Throws Error when
// !streamsInParallel(lsystem).
void streamDerivationParallel(const LSystem& lsystem, int steps,
                              const std::function<void(StreamBlock&)>& prepare,
                              const std::function<void(const StreamBlock&)>& consume,
                              const DerivationOptions& options = {});

// The modules of each symbol (indexed by symbol id) of the string derived in `steps` steps,
// counted as the parallel stream meets them; the last step is not written, only the
// successor each module of the step before takes is counted.
std::vector<std::uint64_t> countStreamedParallel(const LSystem& lsystem, int steps,
                                                 const DerivationOptions& options = {});

}  // namespace graftal
