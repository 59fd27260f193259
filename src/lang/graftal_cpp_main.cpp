// graftal-cpp: the preprocessor's process as a program of its own (mcpp_server.hpp).
//
// A fork of the host would do the same work, but a fork marks every page of the host
// copy-on-write: a Python interpreter or a Dask worker of 100 MB then faults page by page
// back into its own memory, 10-20 ms a run on a small model, more than the model's
// derivation. posix_spawn starts this program without copying anything.
#include <signal.h>

#include <cstring>

#include "mcpp_server.hpp"

int main(int argc, char** argv) {
    namespace server = graftal::mcpp_server;
    if (argc != 2 || std::strcmp(argv[1], server::kProtocol) != 0) return 2;
    // Ctrl-C reaches the whole process group: the host decides what it stops (an
    // interpreter goes on, and so does its preprocessor); a host that ends closes the
    // socket, and this process ends with it.
    ::signal(SIGINT, SIG_IGN);
    server::shieldCompare();
    server::serve(server::kControlFd, server::kOutputFd, server::kMessagesFd);
}
