#!/usr/bin/env python3
"""Checks that every source file of the library's layers is either compiled by the web build
or listed as native-only in cmake/web.cmake, and that neither list names a file that is gone.

    scripts/web_sources.py [ROOT]      exit 0 when the lists agree with src/, 1 otherwise
"""
import pathlib
import re
import sys

LAYERS = ["core", "lang", "rewrite", "geometry", "maps", "turtle", "output", "music", "pipeline"]


def cmake_list(text, name):
    text = re.sub(r"#[^\n]*", "", text)  # comments may hold parentheses
    match = re.search(r"set\(" + name + r"\b(.*?)\)", text, re.S)
    if not match:
        sys.exit(f"cmake/web.cmake: no set({name} ...)")
    return set(word for word in match.group(1).split() if word.startswith("src/"))


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    text = (root / "cmake/web.cmake").read_text()
    web = cmake_list(text, "GRAFTAL_WEB_SOURCES")
    native = cmake_list(text, "GRAFTAL_NATIVE_ONLY_SOURCES")
    sources = set()
    for layer in LAYERS:
        sources |= {p.relative_to(root).as_posix() for p in (root / "src" / layer).glob("*.cpp")}
    problems = []
    for f in sorted(sources - web - native):
        problems.append(f"{f}: in neither the web build's sources nor the native-only ones")
    for f in sorted(web & native):
        problems.append(f"{f}: in both lists")
    for f in sorted((web | native) - {p.relative_to(root).as_posix() for p in root.glob("src/*/*.cpp")}):
        problems.append(f"{f}: listed in cmake/web.cmake but not in src/")
    for p in problems:
        print("cmake/web.cmake: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
