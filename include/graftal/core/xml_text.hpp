// Text placed inside XML (SVG labels, MusicXML titles): the five characters markup gives
// a meaning to are written as entities.
#pragma once

#include <string>
#include <string_view>

namespace graftal {

std::string xmlEscaped(std::string_view text);

}  // namespace graftal
