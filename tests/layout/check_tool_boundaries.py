#!/usr/bin/python3
"""No tool compiles another: each tools/<tool>/ includes only its own headers, libcommon's
(tfmb/common/...) and formats' (tfmb/formats/...), and links only its own libraries,
tfmb_common, tfmb_gmsh and tfmb_formats. What two stages share is a file kind or a helper
(DESIGN.md). Prints every crossing as file:line and exits 1 if there is one.

  check_tool_boundaries.py SOURCE_DIR    check the tree
  check_tool_boundaries.py --self-test   check that a planted crossing is found
"""
import pathlib
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
ADD_LIBRARY = re.compile(r"add_library\(\s*([A-Za-z0-9_:]+)")
LINK = re.compile(r"target_link_libraries\(([^)]*)\)", re.S)
SHARED_LIBRARIES = {"tfmb_common", "tfmb_formats", "tfmb_gmsh"}


def owner_of_include(name, tools):
    """The tool an include path belongs to, or None (own-folder, libcommon, formats, system)."""
    first = name.split("/")[0]
    if first in tools:  # "tfmb-input/model.hpp"
        return first
    parts = name.split("/")
    if len(parts) > 2 and parts[0] == "tfmb" and "tfmb-" + parts[1] in tools:  # "tfmb/beam/..."
        return "tfmb-" + parts[1]
    return None


def crossings(source_dir):
    tools_dir = pathlib.Path(source_dir) / "tools"
    tools = sorted(p.name for p in tools_dir.iterdir() if p.is_dir())
    libraries = {}  # library target -> tool
    for tool in tools:
        cmake = tools_dir / tool / "CMakeLists.txt"
        if cmake.exists():
            for lib in ADD_LIBRARY.findall(cmake.read_text()):
                libraries[lib] = tool
    found = []
    for tool in tools:
        for path in sorted((tools_dir / tool).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h"):
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = INCLUDE.match(line)
                if match:
                    owner = owner_of_include(match.group(1), tools)
                    if owner and owner != tool:
                        found.append(f"{path}:{number}: {tool} includes {owner}'s header {match.group(1)}")
        cmake = tools_dir / tool / "CMakeLists.txt"
        if not cmake.exists():
            continue
        text = cmake.read_text()
        for match in LINK.finditer(text):
            number = text.count("\n", 0, match.start()) + 1
            for word in match.group(1).split()[1:]:
                owner = libraries.get(word)
                if owner and owner != tool and word not in SHARED_LIBRARIES:
                    found.append(f"{cmake}:{number}: {tool} links {owner}'s library {word}")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for tool in ("tfmb-a", "tfmb-b"):
            (root / "tools" / tool).mkdir(parents=True)
        (root / "tools/tfmb-a/CMakeLists.txt").write_text("add_library(tfmb_a STATIC a.cpp)\n")
        (root / "tools/tfmb-a/a.cpp").write_text('#include "tfmb/common/log.hpp"\n#include "a.hpp"\n')
        (root / "tools/tfmb-b/CMakeLists.txt").write_text(
            "add_library(tfmb_b STATIC b.cpp)\ntarget_link_libraries(tfmb_b PUBLIC tfmb_common)\n")
        (root / "tools/tfmb-b/b.cpp").write_text('#include "tfmb/formats/model.hpp"\n')
        if crossings(root):
            return "a clean tree was reported: " + "; ".join(crossings(root))
        (root / "tools/tfmb-b/b.cpp").write_text('#include "tfmb-a/a.hpp"\n')
        (root / "tools/tfmb-b/CMakeLists.txt").write_text(
            "add_library(tfmb_b STATIC b.cpp)\ntarget_link_libraries(tfmb_b PUBLIC tfmb_a tfmb_common)\n")
        found = crossings(root)
        if len(found) != 2:
            return "expected the planted include and link, found: " + "; ".join(found)
    return None


def main():
    if sys.argv[1:] == ["--self-test"]:
        problem = self_test()
        print(problem or "self-test: a planted include and link are found")
        return 1 if problem else 0
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = crossings(sys.argv[1])
    for line in found:
        print(line)
    print(f"{len(found)} crossing(s) between tools")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
