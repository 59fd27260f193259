#include "graftal/core/cancellation.hpp"

namespace graftal {

void CancellationToken::check() const {
    if (cancelled()) throw Cancelled();
}

Cancelled::Cancelled() : Error(SourceLocation{}, "cancelled") {}

}  // namespace graftal
