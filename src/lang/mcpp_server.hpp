// The preprocessor's process: the loop that runs mcpp for each request of the parent
// (preprocessor.cpp), in a process of its own. The parent starts it as the small program
// graftal-cpp (graftal_cpp_main.cpp) when one is installed beside the plugins, or else as a
// fork of itself; both run serveMcpp.
//
// The protocol, on a stream socket: a request is the argument count and each argument as
// its length and bytes (32-bit counts in the host's order); the answer is the bytes written
// to the output and to the messages (two 64-bit counts), which arrive on their own pipes.
#pragma once

#include <cstddef>

namespace graftal::mcpp_server {

// The descriptors of the program's process: the socket of requests and answers, mcpp's
// output and its messages. 0-2 are /dev/null.
inline constexpr int kControlFd = 3;
inline constexpr int kOutputFd = 4;
inline constexpr int kMessagesFd = 5;

// graftal-cpp's only argument. It names this protocol, so that a program of another build
// that speaks another one refuses to start instead of answering wrongly.
inline constexpr const char* kProtocol = "--graftal-mcpp-protocol-1";

// Points libmcpp's calls of memcmp at a comparison that stops at the first difference (see
// the .cpp); true when done, in this call or an earlier one.
bool shieldCompare();

// Runs mcpp for each request on `control` until the parent closes it; never returns.
[[noreturn]] void serve(int control, int output, int messages);

// Reads exactly n bytes; false at the end of the stream or on an error.
bool readExactly(int fd, void* into, std::size_t n);

// Sends all n bytes; false when the peer is gone (no SIGPIPE).
bool sendAll(int fd, const void* data, std::size_t n);

}  // namespace graftal::mcpp_server
