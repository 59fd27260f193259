// Progress of a long derivation on a terminal's stderr: percent done, rate and time left,
// rewritten in place. Only the command prints it; the library reports steps and modules.
#pragma once

#include <chrono>
#include <cstddef>
#include <vector>

namespace graftal::cli {

class ProgressLine {
  public:
    // The modules expected at every step 0..n (stats --predict's counts): the work of a
    // held derivation is the sum of the strings it makes, that of a streamed one its last
    // string. Empty: progress counts steps.
    void expect(std::vector<double> modulesPerStep);
    // From DerivationOptions::progress: after step `step` of a held derivation its string
    // has `modules`; during a streamed one (step n), `modules` of the last string are out.
    void report(int step, std::size_t modules);
    // Ends the line (a newline) if one is shown.
    void end();

  private:
    double fractionDone(int step, double modules) const;

    std::vector<double> perStep_;
    std::vector<double> doneThrough_;  // modules made by steps 1..k
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point lastShown_{};
    double lastFraction_ = 0;
    bool shown_ = false;
};

}  // namespace graftal::cli
