// A flag another thread raises to stop a derivation or a render. Copies share the flag, so
// a program keeps one copy and hands the other to the work it may want to stop.
#pragma once

#include <atomic>
#include <memory>

#include "graftal/core/diagnostics.hpp"

namespace graftal {

class CancellationToken {
  public:
    CancellationToken() : flag_(std::make_shared<std::atomic<bool>>(false)) {}
    void cancel() { flag_->store(true, std::memory_order_relaxed); }
    bool cancelled() const { return flag_->load(std::memory_order_relaxed); }
    // Throws Cancelled when the flag is raised.
    void check() const;

  private:
    std::shared_ptr<std::atomic<bool>> flag_;
};

// Thrown when work stops because its token was cancelled: no output file is left behind.
class Cancelled : public Error {
  public:
    Cancelled();
};

}  // namespace graftal
