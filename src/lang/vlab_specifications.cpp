// Reading the cpfg command of vlab's `specifications` file (see the header). The file lists
// the folder's files, then `ignore:` patterns, then a menu tree indented with tabs whose
// leaves are shell commands; the model's command is the first that runs cpfg.
#include "graftal/lang/vlab_specifications.hpp"

#include <vector>

namespace graftal {

namespace {

// The words of a command line; double quotes group words (`-P "vlabcpp -DN=8"`).
std::vector<std::string> words(std::string_view line) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        if (i >= line.size()) break;
        std::string word;
        bool quoted = false;
        while (i < line.size() &&
               (quoted || (line[i] != ' ' && line[i] != '\t' && line[i] != '\r'))) {
            if (line[i] == '"')
                quoted = !quoted;
            else
                word += line[i];
            ++i;
        }
        out.push_back(std::move(word));
    }
    return out;
}

bool endsWith(const std::string& s, std::string_view tail) {
    return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// cpfg's options that take arguments, and how many (cpfg's command-line reader).
int argumentsOf(const std::string& option) {
    if (option == "-w" || option == "-wr" || option == "-wp" || option == "-wpr") return 2;
    if (option == "-m" || option == "-m1" || option == "-m2" || option == "-m3" || option == "-M" ||
        option == "-e" || option == "-P" || option == "-str" || option == "-rgb" ||
        option == "-ray" || option == "-homo" || option == "-d" || option == "-c")
        return 1;
    return 0;
}

}  // namespace

std::optional<VlabCommand> cpfgCommandOf(std::string_view specifications) {
    std::size_t at = 0;
    while (at < specifications.size()) {
        std::size_t end = specifications.find('\n', at);
        if (end == std::string_view::npos) end = specifications.size();
        std::vector<std::string> w = words(specifications.substr(at, end - at));
        at = end + 1;
        if (w.empty() || (w[0] != "cpfg" && !endsWith(w[0], "/cpfg"))) continue;
        VlabCommand command;
        for (std::size_t k = 1; k < w.size(); ++k) {
            const std::string& a = w[k];
            if (!a.empty() && a[0] == '-') {
                const int n = argumentsOf(a);
                if (n == 1 && k + 1 < w.size()) {
                    const std::string& value = w[k + 1];
                    if ((a == "-m" || a == "-m1") && command.colorMap.empty())
                        command.colorMap = value;
                    if (a == "-M") command.materials = value;
                    if (a == "-e") command.environment = value;
                }
                k += static_cast<std::size_t>(n);
                continue;
            }
            if (command.lFile.empty() && endsWith(a, ".l"))
                command.lFile = a;
            else if (command.viewFile.empty() && endsWith(a, ".v"))
                command.viewFile = a;
        }
        if (command.lFile.empty()) continue;
        return command;
    }
    return std::nullopt;
}

}  // namespace graftal
