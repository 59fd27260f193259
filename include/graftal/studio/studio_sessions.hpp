// The page's sessions: one derivation at a time each. A new derivation for a session
// cancels the one before it (the user typed on), and its picture is kept for the 3D view.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "graftal/core/cancellation.hpp"
#include "graftal/studio/studio_model.hpp"

namespace graftal::studio {

class StudioSessions {
  public:
    // The token of a new derivation for `session`; the previous one's is raised.
    CancellationToken begin(const std::string& session) {
        std::lock_guard lock(mutex_);
        Entry& e = entry(session);
        e.running.cancel();
        e.running = CancellationToken{};
        return e.running;
    }

    void keep(const std::string& session, const std::string& key,
              std::shared_ptr<const StudioPicture> picture) {
        std::lock_guard lock(mutex_);
        Entry& e = entry(session);
        e.key = key;
        e.picture = std::move(picture);
    }

    // The picture kept for `session` when it was made from the same input.
    std::shared_ptr<const StudioPicture> kept(const std::string& session, const std::string& key) {
        std::lock_guard lock(mutex_);
        auto it = entries_.find(session);
        if (it == entries_.end() || it->second.key != key) return nullptr;
        return it->second.picture;
    }

  private:
    struct Entry {
        CancellationToken running;
        std::string key;
        std::shared_ptr<const StudioPicture> picture;
        unsigned long used = 0;
    };

    // Sessions beyond the limit forget the least recently used one (pages come and go).
    Entry& entry(const std::string& session) {
        constexpr std::size_t kMaxSessions = 32;
        auto it = entries_.find(session);
        if (it == entries_.end()) {
            if (entries_.size() >= kMaxSessions) {
                auto oldest = entries_.begin();
                for (auto i = entries_.begin(); i != entries_.end(); ++i)
                    if (i->second.used < oldest->second.used) oldest = i;
                oldest->second.running.cancel();
                entries_.erase(oldest);
            }
            it = entries_.emplace(session, Entry{}).first;
        }
        it->second.used = ++clock_;
        return it->second;
    }

    std::mutex mutex_;
    std::map<std::string, Entry> entries_;
    unsigned long clock_ = 0;
};

}  // namespace graftal::studio
