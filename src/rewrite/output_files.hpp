// The files a model writes with fopen/fprintf: only inside the model's folder or the
// working directory, so that a model cannot overwrite files elsewhere.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "graftal/lang/expression.hpp"

namespace graftal {

class ModelOutputFiles : public OutputFiles {
  public:
    explicit ModelOutputFiles(std::filesystem::path modelFolder);
    double open(const std::string& name, bool append, const SourceLocation& where) override;
    void write(double handle, std::string_view text, const SourceLocation& where) override;
    void flush(double handle, const SourceLocation& where) override;
    void close(double handle, const SourceLocation& where) override;

  private:
    std::ofstream& file(double handle, const SourceLocation& where);

    std::filesystem::path folder_;
    std::vector<std::unique_ptr<std::ofstream>> files_;  // handle k is files_[k - 1]
};

}  // namespace graftal
