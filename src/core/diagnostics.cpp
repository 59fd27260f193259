#include "graftal/core/diagnostics.hpp"

#include <sstream>

namespace graftal {

std::string SourceLocation::toString() const {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) {
        s += ':' + std::to_string(line);
        if (column > 0) s += ':' + std::to_string(column);
    }
    return s;
}

static const char* severityName(Severity s) {
    switch (s) {
        case Severity::Error:
            return "error";
        case Severity::Warning:
            return "warning";
        case Severity::Note:
            return "note";
    }
    return "error";
}

std::string requestRemedyText(Remedy r) {
    switch (r) {
        case Remedy::LowerSteps:
            return "lower steps";
        case Remedy::RaiseMemoryLimit:
            return "raise memoryLimit";
        case Remedy::Stream:
            return "set stream to StreamPolicy::Always";
        case Remedy::RaiseStreamLimit:
            return "raise streamLimit";
    }
    return {};
}

std::string Diagnostic::toString() const {
    return toString(requestRemedyText, [](const std::string& f) { return f; });
}

std::string Diagnostic::toString(
    const std::function<std::string(Remedy)>& remedy,
    const std::function<std::string(const std::string&)>& field) const {
    std::string s = location.toString() + ": " + severityName(severity) + ": " + message;
    for (std::size_t i = 0; i < fields.size(); ++i) s += (i == 0 ? ": " : ", ") + field(fields[i]);
    for (std::size_t i = 0; i < remedies.size(); ++i)
        s += (i == 0 ? "; " : i + 1 == remedies.size() ? " or " : ", ") + remedy(remedies[i]);
    return s;
}

std::ostream& operator<<(std::ostream& os, const SourceLocation& loc) {
    return os << loc.toString();
}

std::ostream& operator<<(std::ostream& os, const Diagnostic& d) {
    return os << d.toString();
}

void DiagnosticList::error(SourceLocation loc, std::string message) {
    items_.push_back({Severity::Error, std::move(loc), std::move(message)});
}

void DiagnosticList::warning(SourceLocation loc, std::string message) {
    items_.push_back({Severity::Warning, std::move(loc), std::move(message)});
}

bool DiagnosticList::hasErrors() const {
    for (const auto& d : items_)
        if (d.severity == Severity::Error) return true;
    return false;
}

std::string DiagnosticList::toString() const {
    std::string s;
    for (const auto& d : items_) s += d.toString() + '\n';
    return s;
}

static std::string joinMessages(const std::vector<Diagnostic>& ds) {
    std::string s;
    for (size_t i = 0; i < ds.size(); ++i) {
        if (i) s += '\n';
        s += ds[i].toString();
    }
    return s;
}

Error::Error(Diagnostic d) : Error(std::vector<Diagnostic>{std::move(d)}) {}

std::string Error::messages() const {
    if (diagnostics_.empty()) return what();
    std::string s;
    for (const auto& d : diagnostics_) {
        if (!s.empty()) s += "; ";
        s += d.message;
    }
    return s;
}

Error::Error(std::vector<Diagnostic> ds)
    : std::runtime_error(joinMessages(ds)), diagnostics_(std::move(ds)) {}

Error::Error(SourceLocation loc, const std::string& message)
    : Error(Diagnostic{Severity::Error, std::move(loc), message}) {}

}  // namespace graftal
