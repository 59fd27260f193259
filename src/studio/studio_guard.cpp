// The studio's guards (studio_guard.hpp).
#include "graftal/studio/studio_guard.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace graftal::studio {

std::string randomToken() {
    std::random_device random;  // /dev/urandom on Linux
    static const char digits[] = "0123456789abcdef";
    std::string token;
    for (int i = 0; i < 4; ++i) {
        std::uint32_t bits = random();
        for (int k = 0; k < 8; ++k, bits >>= 4) token += digits[bits & 15];
    }
    return token;
}

bool sameSecret(std::string_view given, std::string_view secret) {
    if (given.size() != secret.size() || secret.empty()) return false;
    unsigned char difference = 0;
    for (std::size_t i = 0; i < secret.size(); ++i)
        difference |= static_cast<unsigned char>(given[i] ^ secret[i]);
    return difference == 0;
}

std::string cookieValue(std::string_view header, std::string_view name) {
    std::size_t at = 0;
    while (at < header.size()) {
        std::size_t end = header.find(';', at);
        if (end == std::string_view::npos) end = header.size();
        std::string_view pair = header.substr(at, end - at);
        while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
        if (pair.size() > name.size() && pair.substr(0, name.size()) == name &&
            pair[name.size()] == '=')
            return std::string(pair.substr(name.size() + 1));
        at = end + 1;
    }
    return {};
}

bool isOwnOrigin(std::string_view origin, int port) {
    const std::string p = ":" + std::to_string(port);
    return origin == "http://127.0.0.1" + p || origin == "http://localhost" + p;
}

std::int64_t integerField(const nlohmann::json& body, const char* name, std::int64_t low,
                          std::int64_t high) {
    const nlohmann::json& v = body.at(name);
    const std::string range = " from " + std::to_string(low) + " to " + std::to_string(high);
    if (!v.is_number_integer())
        throw BadRequest(std::string("\"") + name + "\" must be a whole number" + range);
    // An unsigned JSON number may not fit an int64: compare it as what it is.
    if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(high)
                               : v.get<std::int64_t>() > high || v.get<std::int64_t>() < low)
        throw BadRequest(std::string("\"") + name + "\" is " + v.dump() + ": it must be" + range);
    return v.get<std::int64_t>();
}

double numberField(const nlohmann::json& value, const std::string& name, double low, double high) {
    if (!value.is_number()) throw BadRequest("\"" + name + "\" must be a number");
    const double x = value.get<double>();
    if (!std::isfinite(x) || x < low || x > high)
        throw BadRequest("\"" + name + "\" is " + value.dump() + ": it must be a finite number " +
                         "from " + nlohmann::json(low).dump() + " to " +
                         nlohmann::json(high).dump());
    return x;
}

DerivationGate::Pass DerivationGate::enter(std::size_t wanted, std::size_t least,
                                           const CancellationToken& cancel,
                                           std::chrono::milliseconds wait) {
    least = std::min({least, wanted, budget_});
    const auto until = std::chrono::steady_clock::now() + wait;
    std::unique_lock lock(mutex_);
    while (true) {
        cancel.check();
        const std::size_t room = budget_ - used_;
        if (free_ > 0 && room >= least) {
            const std::size_t granted = std::min(wanted, room);
            --free_;
            ++running_;
            used_ += granted;
            return Pass(*this, granted);
        }
        if (std::chrono::steady_clock::now() >= until)
            throw Busy("the studio is busy: " + std::to_string(running_) +
                       " derivations are under way and hold " + std::to_string(used_ >> 20) +
                       " MiB of its " + std::to_string(budget_ >> 20) +
                       " MiB memory budget; try again when one has finished (or lower the "
                       "steps)");
        // Woken by a leave(); the timeout lets a cancelled request stop waiting.
        changed_.wait_for(lock, std::chrono::milliseconds(20));
    }
}

int DerivationGate::running() const {
    std::lock_guard lock(mutex_);
    return running_;
}

void DerivationGate::leave(std::size_t bytes) {
    {
        std::lock_guard lock(mutex_);
        ++free_;
        --running_;
        used_ -= bytes;
    }
    changed_.notify_all();
}

}  // namespace graftal::studio
