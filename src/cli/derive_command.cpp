// graftal derive: the derived string on standard output, as cpfg-style text or as JSON for
// scripts (one object per module, see docs/cli.md). The export registry's string rows
// derive and write it (held or streamed); this file only turns the options into a request.
#include <iostream>

#include "commands.hpp"

namespace graftal::cli {

int runDerive(const InputOptions& in, bool homomorphism, DeriveFormat format) {
    Loaded l = loadInput(in);
    ExportRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    request.steps = l.steps;
    request.format = format == DeriveFormat::Json ? "json" : "text";
    request.homomorphism = homomorphism;
    request.inputName = fileName(in);
    exportModel(l.model, Destination::stream(std::cout, "<stdout>"), request);
    endProgressLine();
    return 0;
}

}  // namespace graftal::cli
