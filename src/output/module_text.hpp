// What the derived string's text and JSON writers share: a growing byte buffer written
// through a pointer, each symbol's name ready to copy, a cache of formatted parameters,
// and the loop that formats chunks of a held string on several threads and writes them in
// order. A string has up to billions of modules: nothing here allocates or calls a stream
// per module.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/byte_buffer.hpp"
#include "graftal/core/module_string.hpp"
#include "graftal/core/parallel.hpp"

namespace graftal::module_text {

// Bytes appended through a pointer (graftal/core/byte_buffer.hpp).
using TextBuffer = ByteBuffer;

// The texts of parameters seen recently, by their bits: the parameters of a plant take few
// distinct values (lengths and widths scaled by the same ratios), and copying a text is
// several times faster than finding the shortest digits again. The text is always what
// formatSingleTo/formatNumberTo give.
class NumberCache {
  public:
    NumberCache() : slots_(kSlots) {}

    char* put(char* out, float v) {
        std::uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        Slot& slot = slots_[indexOf(bits)];
        if (slot.length == 0 || slot.key != bits) {
            slot.key = bits;
            slot.length = static_cast<std::uint8_t>(formatSingleTo(slot.text, v) - slot.text);
        }
        std::memcpy(out, slot.text, sizeof slot.text);
        return out + slot.length;
    }
    char* put(char* out, double v) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        Slot& slot = slots_[indexOf(bits)];
        if (slot.length == 0 || slot.key != bits) {
            slot.key = bits;
            slot.length = static_cast<std::uint8_t>(formatNumberTo(slot.text, v) - slot.text);
        }
        std::memcpy(out, slot.text, sizeof slot.text);
        return out + slot.length;
    }

  private:
    static constexpr std::size_t kBits = 12, kSlots = std::size_t(1) << kBits;
    static std::size_t indexOf(std::uint64_t key) {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - kBits));
    }
    struct Slot {
        std::uint64_t key = 0;
        std::uint8_t length = 0;  // 0: empty (no text is empty)
        char text[kNumberTextCapacity];
    };
    std::vector<Slot> slots_;
};

// Room one formatted parameter takes at most, with its separator.
inline constexpr std::size_t kParameterRoom = kNumberTextCapacity + 2;

// Every symbol's name, and whether the text of a run of symbols is the run itself (every
// symbol below 128 is the one character of its name).
struct SymbolNames {
    explicit SymbolNames(const SymbolTable& table) {
        names.resize(kMaxSymbols);
        shortNames.resize(kMaxSymbols);
        for (std::size_t s = 0; s < table.size(); ++s) {
            names[s] = table.name(static_cast<Symbol>(s));
            if (names[s].size() <= kShort)
                std::memcpy(shortNames[s].data(), names[s].data(), names[s].size());
        }
    }
    // Room the name of `s` takes when written by put().
    std::size_t roomFor(Symbol s) const { return std::max(kShort, names[s].size()); }
    // The name of `s` at `p`, which has roomFor(s) bytes; a short name is copied with a
    // fixed-length copy (a few instructions, not a call).
    char* put(char* p, Symbol s) const {
        const std::string& name = names[s];
        if (name.size() <= kShort)
            std::memcpy(p, shortNames[s].data(), kShort);
        else
            std::memcpy(p, name.data(), name.size());
        return p + name.size();
    }
    static bool isOwnText(std::span<const Symbol> run) {
        unsigned high = 0;
        for (Symbol s : run) high |= s;
        return high < kFirstNamedSymbol;
    }
    static constexpr std::size_t kShort = 16;
    std::vector<std::string> names;
    std::vector<std::array<char, kShort>> shortNames;
};

// The parameters of a held string, read without a ParamView per module.
struct HeldParameters {
    explicit HeldParameters(const ModuleString& s)
        : starts(s.hasParameters() ? s.paramStarts().data() : nullptr),
          floats(s.precision() == Precision::Single ? s.floatParams().data() : nullptr),
          doubles(s.precision() == Precision::Double ? s.doubleParams().data() : nullptr) {}
    const std::uint32_t* starts;
    const float* floats;
    const double* doubles;
};

// Formats the held string `n` modules long in chunks of about `modulesPerChunk` modules,
// `threads` chunks at a time (0: one per core), each by format(begin, end, buffer) into its
// own buffer, and writes the buffers in order; a chunk whose format() returns false instead
// is written by writeRaw(begin, end) (a run that is its own text). The bytes never depend on
// the thread count.
template <class Format, class WriteRaw>
void writeChunksInOrder(std::size_t n, unsigned threads, std::size_t modulesPerChunk,
                        std::ostream& out, Format&& format, WriteRaw&& writeRaw) {
    const std::size_t team = threads ? threads : defaultThreadCount();
    const std::size_t chunks = (n + modulesPerChunk - 1) / modulesPerChunk;
    std::vector<TextBuffer> buffers(std::min(team, std::max<std::size_t>(chunks, 1)));
    std::vector<char> formatted(buffers.size());
    for (std::size_t first = 0; first < chunks; first += buffers.size()) {
        const std::size_t batch = std::min(buffers.size(), chunks - first);
        forEachChunk(batch, batch, [&](std::size_t c, std::size_t, std::size_t) {
            const std::size_t b = (first + c) * modulesPerChunk;
            const std::size_t e = std::min(n, b + modulesPerChunk);
            buffers[c].clear();
            formatted[c] = format(b, e, buffers[c]);
        });
        for (std::size_t c = 0; c < batch; ++c) {
            const std::size_t b = (first + c) * modulesPerChunk;
            if (formatted[c])
                buffers[c].writeTo(out);
            else
                writeRaw(b, std::min(n, b + modulesPerChunk));
        }
    }
}

}  // namespace graftal::module_text
