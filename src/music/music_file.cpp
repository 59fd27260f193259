// A score written in the format its file name asks for.
#include <cctype>

#include "graftal/core/atomic_file.hpp"
#include "graftal/music/music.hpp"

namespace graftal {

std::optional<MusicFormat> musicFormatFor(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".mid" || ext == ".midi") return MusicFormat::Midi;
    if (ext == ".wav") return MusicFormat::Wav;
    if (ext == ".ly") return MusicFormat::LilyPond;
    if (ext == ".pdf") return MusicFormat::Pdf;
    if (ext == ".png") return MusicFormat::Png;
    if (ext == ".svg") return MusicFormat::Svg;
    if (ext == ".musicxml" || ext == ".xml") return MusicFormat::MusicXml;
    return std::nullopt;
}

std::string musicExtensionList() {
    return ".mid .wav .ly .pdf .png .svg .musicxml";
}

void writeScore(const Score& score, const std::filesystem::path& path, const AudioOptions& audio) {
    std::optional<MusicFormat> format = musicFormatFor(path);
    if (!format)
        throw fileError(path, "unknown music format '" + path.extension().string() +
                                  "' (expected " + musicExtensionList() + ")");
    writeScore(score, *format, Destination::file(path), audio);
}

void writeScore(const Score& score, MusicFormat format, const Destination& destination,
                const AudioOptions& audio) {
    switch (format) {
        case MusicFormat::Midi:
            writeMidi(score, destination);
            break;
        case MusicFormat::Wav:
            writeWav(score, destination, audio);
            break;
        case MusicFormat::LilyPond:
            writeLilyPond(score, destination);
            break;
        case MusicFormat::Pdf:
        case MusicFormat::Png:
        case MusicFormat::Svg:
            engraveScore(score, format, destination, audio.memoryLimit);
            break;
        case MusicFormat::MusicXml:
            writeMusicXml(score, destination);
            break;
    }
}

}  // namespace graftal
