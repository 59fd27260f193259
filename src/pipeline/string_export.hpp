// The export registry's writer of the derived string (text and JSON, `graftal derive`).
#pragma once

#include "graftal/pipeline/export.hpp"

namespace graftal {

// Derives the model (held, or streamed when the string need not or cannot be held) and
// writes its string in the row's format ("text" or "json") to the destination.
ExportResult writeDerivedString(const ExportFormat& format, const Model& model,
                                const ExportRequest& request, const Destination& destination);

}  // namespace graftal
