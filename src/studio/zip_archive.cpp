// The ZIP format's stored entries (APPNOTE 4.3: local headers, the data, the central
// directory, its end record), little-endian, no compression, no ZIP64 (the studio's exports
// stay far below 4 GiB).
#include "graftal/studio/zip_archive.hpp"

#include <array>
#include <cstdint>

namespace graftal::studio {

namespace {

std::uint32_t crc32(const std::string& bytes) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

void put16(std::string& out, std::uint32_t v) {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>((v >> 8) & 0xFF);
}

void put32(std::string& out, std::uint32_t v) {
    put16(out, v & 0xFFFF);
    put16(out, v >> 16);
}

}  // namespace

std::string storedZip(const std::vector<std::pair<std::string, std::string>>& files) {
    constexpr std::uint32_t kDosDate = (1980 - 1980) << 9 | 1 << 5 | 1;  // 1 January 1980
    std::string out, directory;
    // Not a structured binding: clang 14 (the web build's) cannot capture one in a lambda.
    for (const auto& file : files) {
        const std::string& name = file.first;
        const std::string& bytes = file.second;
        const std::uint32_t crc = crc32(bytes);
        const auto size = static_cast<std::uint32_t>(bytes.size());
        const auto offset = static_cast<std::uint32_t>(out.size());
        // Version 2.0, no flags, stored, time 0, the date, CRC, sizes, name, no extra.
        auto common = [&](std::string& o) {
            put16(o, 20);
            put16(o, 0);
            put16(o, 0);
            put16(o, 0);
            put16(o, kDosDate);
            put32(o, crc);
            put32(o, size);
            put32(o, size);
            put16(o, static_cast<std::uint32_t>(name.size()));
            put16(o, 0);
        };
        put32(out, 0x04034B50u);
        common(out);
        out += name;
        out += bytes;
        put32(directory, 0x02014B50u);
        put16(directory, 20);  // made by: version 2.0
        common(directory);
        put16(directory, 0);  // comment length
        put16(directory, 0);  // disk
        put16(directory, 0);  // internal attributes
        put32(directory, 0);  // external attributes
        put32(directory, offset);
        directory += name;
    }
    const auto directoryOffset = static_cast<std::uint32_t>(out.size());
    const auto count = static_cast<std::uint32_t>(files.size());
    out += directory;
    put32(out, 0x06054B50u);
    put16(out, 0);
    put16(out, 0);
    put16(out, count);
    put16(out, count);
    put32(out, static_cast<std::uint32_t>(directory.size()));
    put32(out, directoryOffset);
    put16(out, 0);
    return out;
}

}  // namespace graftal::studio
