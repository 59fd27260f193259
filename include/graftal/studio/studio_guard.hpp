// What keeps the studio safe from the pages a user visits and from bursts of requests: the
// per-run secret token, the Origin check, range-checked JSON numbers, and the gate that
// bounds how many derivations run at once and the memory they may hold between them.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "graftal/core/cancellation.hpp"

namespace graftal::studio {

// A request the page should not have sent (bad JSON, a missing field, a number out of
// range): answered 400 with its message.
class BadRequest : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The server cannot take the request now (every derivation slot or the memory budget is
// in use): answered 503 with its message; the server goes on.
class Busy : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// 32 hexadecimal digits from the system's random source: the secret of one studio run.
std::string randomToken();

// Equal strings, compared in a time that does not tell how much of a guess was right.
bool sameSecret(std::string_view given, std::string_view secret);

// The value of cookie `name` in a Cookie header ("a=1; b=2"), empty when absent.
std::string cookieValue(std::string_view header, std::string_view name);

// True when `origin` (an Origin header) is the studio's own page on `port`; an absent
// Origin (same-origin GETs, programs such as curl) is the caller's to decide.
bool isOwnOrigin(std::string_view origin, int port);

// `body[name]` as a whole number from `low` to `high`; throws BadRequest naming the field
// and the range when it is another type or outside it (never narrowed or wrapped).
std::int64_t integerField(const nlohmann::json& body, const char* name, std::int64_t low,
                          std::int64_t high);

// A finite number (JSON cannot hold NaN, but a huge literal may be read as infinity)
// from `low` to `high`; throws BadRequest otherwise.
double numberField(const nlohmann::json& value, const std::string& name, double low, double high);

// Bounds the derivations under way: at most `slots` at once, and their memory limits
// together within `budgetBytes`. A derivation waits a while for room (giving up at once
// when its own request is cancelled by a newer one), then is refused with Busy.
class DerivationGate {
  public:
    DerivationGate(int slots, std::size_t budgetBytes) : free_(slots), budget_(budgetBytes) {}

    // Holds a slot and `bytes` of the budget until destroyed.
    class Pass {
      public:
        Pass(DerivationGate& gate, std::size_t bytes) : gate_(&gate), bytes_(bytes) {}
        Pass(Pass&& other) noexcept : gate_(other.gate_), bytes_(other.bytes_) {
            other.gate_ = nullptr;
        }
        Pass(const Pass&) = delete;
        Pass& operator=(const Pass&) = delete;
        Pass& operator=(Pass&&) = delete;
        ~Pass() {
            if (gate_) gate_->leave(bytes_);
        }
        // The memory this derivation may use: its share of the budget.
        std::size_t bytes() const { return bytes_; }

      private:
        DerivationGate* gate_;
        std::size_t bytes_;
    };

    // A slot and up to `wanted` bytes (at least `least`, or the whole budget when it is
    // smaller). Waits at most `wait`; throws Cancelled when `cancel` is raised meanwhile and
    // Busy when no room came.
    Pass enter(std::size_t wanted, std::size_t least, const CancellationToken& cancel,
               std::chrono::milliseconds wait);

    int running() const;

  private:
    void leave(std::size_t bytes);

    mutable std::mutex mutex_;
    std::condition_variable changed_;
    int free_;
    int running_ = 0;
    std::size_t budget_;
    std::size_t used_ = 0;
};

}  // namespace graftal::studio
