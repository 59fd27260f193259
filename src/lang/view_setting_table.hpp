// The one table of view settings: each setting's name in a .l file, its spellings in a cpfg
// view file and how that file writes the value, how it is checked and stored, and how it is
// printed. The .l parser, the view-file reader and the printer all read it.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/lang/parser_target.hpp"
#include "graftal/lang/view_settings.hpp"

namespace graftal {

// Which files state a setting. `Reader` settings are parts of a view-file line the reader
// hands on by name (a `tropism:` line's direction and elasticity); no file names them.
enum class SettingSources { LFile, ViewFile, Both, Reader };

// What the value is; the .l parser reads it so (a number and a vector as constant
// expressions, a word or a file name as trimmed text) and applyViewSetting() checks it.
enum class SettingValue {
    Number,
    Vector,
    Word,        // a word (`spline: path`)
    FileOrWord,  // a word, a colour or a file name (`color map: plant.map`)
    File,        // a file the target loads itself (`contour: 1 leaf.con`)
    None,        // a view-file line that sets nothing (read and warned)
};

// How a cpfg view file writes a setting, where it differs from the .l file.
enum class CpfgSyntax {
    Same,                 // as the .l file: a number, three numbers or the text
    Percent,              // `scale factor: 0.9`: a share of the window, graftal's in percent
    TenthsOfDegree,       // `twist: 450`: 45 degrees
    PolygonizationLevel,  // `polygonization level: L`: 2^(L + 1) cylinder sides
    WidthWithUnit,        // `initial line width: W [pixels]`: also the line width unit
    StyleWithUnit,        // `line style: pixel|polygon|cylinder`: also the line width unit
    Fields,               // `tropism: T: x,y,z E: e` (and torque:)
    Light,                // `light: V: x,y,z D: r g b A: r g b`
    Ignored,              // read and warned: not drawn (the note says why)
    NotCpfg,              // no cpfg line either: warned (the note says what to do instead)
};

struct CpfgSpelling {
    std::string_view name;  // lower case, without the ':'
    CpfgSyntax syntax = CpfgSyntax::Same;
};

struct ViewSettingDescriptor {
    std::string_view name;  // as a .l file writes it, and the ViewSetting::name it is sent as
    SettingValue value;
    SettingSources sources;
    std::vector<std::string_view> aliases;  // other .l spellings (`colour map`)
    // The view file's spellings; empty with a view-file source: the name, CpfgSyntax::Same.
    std::vector<CpfgSpelling> cpfg;
    std::string_view note;  // Ignored and NotCpfg lines: why
    // Checks the value (of the kind `value` says) and stores it; returns "" or the message.
    // Null: the target reads it (File) or nothing is stored.
    std::string (*apply)(ViewSettings&, const ViewSetting&) = nullptr;
    // Writes the setting's lines when it differs from the default: in .l syntax when the .l
    // file accepts it, else in the view file's. Null: printed with another setting, or not at
    // all (files the target loads into the L-system).
    void (*print)(std::ostream&, const ViewSettings&) = nullptr;

    bool inLFile() const {
        return sources == SettingSources::LFile || sources == SettingSources::Both;
    }
    bool inViewFile() const {
        return sources == SettingSources::ViewFile || sources == SettingSources::Both;
    }
};

const std::vector<ViewSettingDescriptor>& viewSettingTable();

// The setting a .l file names `name` (its name or an alias), or null.
const ViewSettingDescriptor* findLFileSetting(std::string_view name);

// The setting a view-file line names `name` (lower case), or null; `spelling` is set to the
// matching spelling.
const ViewSettingDescriptor* findViewFileSetting(std::string_view name,
                                                 const CpfgSpelling*& spelling);

// The names a .l file's view-setting lines may start with, in table order, aliases included.
const std::vector<std::string>& lFileSettingNames();

}  // namespace graftal
