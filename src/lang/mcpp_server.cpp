// The preprocessor's process (mcpp_server.hpp). It is written without the C++ library's
// containers, so that graftal-cpp maps libmcpp and libc alone and starts in a millisecond.
#include "mcpp_server.hpp"

extern "C" {
#include <mcpp_lib.h>
}
#include <elf.h>
#include <link.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace graftal::mcpp_server {

namespace {

// libmcpp's macro lookup (look_prev) compares the stored names of a hash chain with the name
// looked up by memcmp(stored, name, strlen(name) + 1): a stored name shorter than the one
// looked up is read past its end, past its allocation when the macro's text is short too
// (AddressSanitizer reports it; glibc's vectorised memcmp really reads those bytes). mcpp
// only needs the sign of the first difference, and the stored name ends with its NUL, so
// a comparison that stops at the first difference answers the same without reading past.
// It is put in libmcpp's own PLT slot for memcmp: nothing else in the program changes.
extern "C" int graftalMcppCompare(const void* a, const void* b, std::size_t n) {
    const auto* x = static_cast<const unsigned char*>(a);
    const auto* y = static_cast<const unsigned char*>(b);
    for (std::size_t i = 0; i < n; ++i)
        if (x[i] != y[i]) return x[i] < y[i] ? -1 : 1;
    return 0;
}

bool gCompareShielded = false;

// Finds libmcpp's relocation of memcmp in its PLT and points it at graftalMcppCompare.
int shieldInLibrary(dl_phdr_info* info, std::size_t, void*) {
    if (!info->dlpi_name || !std::strstr(info->dlpi_name, "libmcpp")) return 0;
    const ElfW(Dyn)* dynamic = nullptr;
    for (int i = 0; i < info->dlpi_phnum; ++i)
        if (info->dlpi_phdr[i].p_type == PT_DYNAMIC)
            dynamic =
                reinterpret_cast<const ElfW(Dyn)*>(info->dlpi_addr + info->dlpi_phdr[i].p_vaddr);
    if (!dynamic) return 1;
    ElfW(Addr) relocations = 0, symbols = 0, names = 0;
    std::size_t size = 0;
    for (const ElfW(Dyn)* d = dynamic; d->d_tag != DT_NULL; ++d) {
        if (d->d_tag == DT_JMPREL) relocations = d->d_un.d_ptr;
        if (d->d_tag == DT_PLTRELSZ) size = d->d_un.d_val;
        if (d->d_tag == DT_SYMTAB) symbols = d->d_un.d_ptr;
        if (d->d_tag == DT_STRTAB) names = d->d_un.d_ptr;
    }
    // glibc stores these relocated; another loader may leave them relative to the base.
    auto absolute = [&](ElfW(Addr) a) { return a < info->dlpi_addr ? a + info->dlpi_addr : a; };
    if (!relocations || !symbols || !names) return 1;
    const auto* rela = reinterpret_cast<const ElfW(Rela)*>(absolute(relocations));
    const auto* symbol = reinterpret_cast<const ElfW(Sym)*>(absolute(symbols));
    const char* name = reinterpret_cast<const char*>(absolute(names));
    for (std::size_t i = 0; i < size / sizeof(ElfW(Rela)); ++i) {
        if (std::strcmp(name + symbol[ELF64_R_SYM(rela[i].r_info)].st_name, "memcmp") != 0)
            continue;
        auto* slot = reinterpret_cast<void**>(info->dlpi_addr + rela[i].r_offset);
        // Writable under lazy binding; read-only after relocation with RELRO and BIND_NOW.
        const long page = ::sysconf(_SC_PAGESIZE);
        void* start = reinterpret_cast<void*>(reinterpret_cast<std::uintptr_t>(slot) &
                                              ~static_cast<std::uintptr_t>(page - 1));
        if (::mprotect(start, static_cast<std::size_t>(page), PROT_READ | PROT_WRITE) != 0)
            return 1;
        *slot = reinterpret_cast<void*>(&graftalMcppCompare);
        gCompareShielded = true;
        return 1;
    }
    return 1;
}

// Where mcpp's output and messages go, and how much of each this run wrote. mcpp writes a
// line or a character at a time; each written straight to its pipe was a system call and a
// wake-up of the parent. So both are gathered in 64 KiB buffers, written when full and at
// the end of the run: the parent still sees an output past its size limit grow, a block at
// a time.
int gFd[2] = {-1, -1};
std::uint64_t gWritten[2] = {0, 0};
constexpr std::size_t kBufferBytes = 64u << 10;
char gBuffer[2][kBufferBytes];
std::size_t gBuffered[2] = {0, 0};

void writeAll(int fd, const char* p, std::size_t n) {
    while (n > 0) {
        ssize_t w = ::write(fd, p, n);
        if (w < 0) {
            if (errno == EINTR) continue;
            ::_exit(3);  // the parent stopped listening
        }
        p += w;
        n -= static_cast<std::size_t>(w);
    }
}

void flush(int k) {
    writeAll(gFd[k], gBuffer[k], gBuffered[k]);
    gBuffered[k] = 0;
}

// mcpp may end its process with exit(): what it wrote before still reaches the parent.
extern "C" void flushAtExit() {
    flush(0);
    flush(1);
}

void put(OUTDEST od, const char* p, std::size_t n) {
    const int k = od == OUT ? 0 : 1;
    gWritten[k] += n;
    if (gBuffered[k] + n > kBufferBytes) {
        flush(k);
        if (n >= kBufferBytes) {
            writeAll(gFd[k], p, n);
            return;
        }
    }
    std::memcpy(gBuffer[k] + gBuffered[k], p, n);
    gBuffered[k] += n;
}

extern "C" int putCharacter(int c, OUTDEST od) {
    char ch = static_cast<char>(c);
    put(od, &ch, 1);
    return c;
}

extern "C" int putString(const char* s, OUTDEST od) {
    put(od, s, std::strlen(s));
    return 0;
}

extern "C" int putFormatted(OUTDEST od, const char* format, ...) {
    char small[1024];
    va_list args;
    va_start(args, format);
    int n = std::vsnprintf(small, sizeof small, format, args);
    va_end(args);
    if (n < 0) return n;
    if (static_cast<std::size_t>(n) < sizeof small) {
        put(od, small, static_cast<std::size_t>(n));
        return n;
    }
    char* big = static_cast<char*>(std::malloc(static_cast<std::size_t>(n) + 1));
    if (!big) ::_exit(4);
    va_start(args, format);
    std::vsnprintf(big, static_cast<std::size_t>(n) + 1, format, args);
    va_end(args);
    put(od, big, static_cast<std::size_t>(n));
    std::free(big);
    return n;
}

constexpr std::uint32_t kMaxArguments = 4096;
constexpr std::uint32_t kMaxArgumentBytes = 1u << 20;

// One request's arguments as argv (each argument malloc'd, NUL-terminated); false when the
// parent has closed the socket or sent what no parent sends.
bool readRequest(int control, char** argv, std::uint32_t& count) {
    count = 0;
    std::uint32_t wanted = 0;
    if (!readExactly(control, &wanted, sizeof wanted) || wanted == 0 || wanted > kMaxArguments)
        return false;
    for (; count < wanted; ++count) {
        std::uint32_t size = 0;
        if (!readExactly(control, &size, sizeof size) || size > kMaxArgumentBytes) return false;
        argv[count] = static_cast<char*>(std::malloc(size + 1));
        if (!argv[count] || !readExactly(control, argv[count], size)) return false;
        argv[count][size] = '\0';
    }
    argv[count] = nullptr;
    return true;
}

}  // namespace

bool shieldCompare() {
    if (!gCompareShielded) ::dl_iterate_phdr(shieldInLibrary, nullptr);
    return gCompareShielded;
}

bool readExactly(int fd, void* into, std::size_t n) {
    auto* p = static_cast<char*>(into);
    while (n > 0) {
        ssize_t r = ::read(fd, p, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= static_cast<std::size_t>(r);
    }
    return true;
}

bool sendAll(int fd, const void* data, std::size_t n) {
    const auto* p = static_cast<const char*>(data);
    while (n > 0) {
        ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);  // a dead peer is an error, not SIGPIPE
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= static_cast<std::size_t>(w);
    }
    return true;
}

void serve(int control, int output, int messages) {
    gFd[0] = output;
    gFd[1] = messages;
    std::atexit(flushAtExit);
    static char* argv[kMaxArguments + 1];
    for (;;) {
        std::uint32_t count = 0;
        const bool ok = readRequest(control, argv, count);
        if (ok) {
            gWritten[0] = gWritten[1] = 0;
            mcpp_set_out_func(putCharacter, putString, putFormatted);
            mcpp_lib_main(static_cast<int>(count), argv);
            flush(0);
            flush(1);
        }
        for (std::uint32_t i = 0; i < count; ++i) std::free(argv[i]);
        if (!ok) ::_exit(0);
        const std::uint64_t written[2] = {gWritten[0], gWritten[1]};
        if (!sendAll(control, written, sizeof written)) ::_exit(0);
    }
}

}  // namespace graftal::mcpp_server
