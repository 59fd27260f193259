// graftal animate: a model's development as a GIF, WebP, MP4 or a folder of PNG frames.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

#include "commands.hpp"
#include "graftal/pipeline/animation.hpp"

namespace graftal::cli {

class AnimateCommand {
  public:
    // Adds the subcommand to `app`; `addInputOptions` adds the options every subcommand
    // shares (the file, -n, -D, --seed, ...).
    AnimateCommand(CLI::App& app, const std::function<void(CLI::App&)>& addInputOptions);
    bool chosen() const { return command_->parsed(); }
    int run(const InputOptions& in);

  private:
    CLI::App* command_ = nullptr;
    AnimationRequest request_;
    std::string output_, size_, background_, color_, view_;
    std::string quality_;           // --quality low|medium|high|N
    std::optional<int> tubeSides_;  // --tube-sides, over what --quality gives
    std::string viewpoint_, target_, up_, light_;
    std::optional<int> to_;
    std::optional<int> frames_;
};

}  // namespace graftal::cli
