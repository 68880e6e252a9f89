#!/usr/bin/env python3
"""The include rule of the tree (common/README.md, "Rooms"), checked.

Reads the rule from common/README.md and master/README.md (the block after
"<!-- rooms -->" in each), finds every #include "..." in common/, protocol/,
master/ and worker/, and prints each one that breaks it:
  - a room of common/ (or of master/) includes its own files and those of
    rooms on earlier lines of its block; never a room on its own line or a
    later one (master/'s own files, the programs' main()s, may include any);
  - protocol/ includes common/ only up to the room named `protocol:` there;
  - common/ includes nothing outside itself; master/ and worker/ never each other.
Exit 1 when anything breaks the rule, 0 otherwise. ctest runs it (include_rule).
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def read_block(folder):
    """{room: level} of folder/README.md's rooms block, and its `protocol: ROOM` line's room, if any."""
    text = open(os.path.join(ROOT, folder, "README.md"), encoding="utf-8").read()
    start = text.index("<!-- rooms -->")
    block = text[start:].split("```")[1]
    levels, protocol_top = {}, None
    for line in block.strip().splitlines():
        line = line.split("#")[0].strip()
        if not line:
            continue
        if line.startswith("protocol:"):
            protocol_top = line.split(":", 1)[1].strip()
            continue
        level = len(set(levels.values()))
        for room in line.split():
            levels[room] = level
    return levels, protocol_top


def read_rule():
    levels, protocol_top = read_block("common")
    if protocol_top not in levels:
        sys.exit("check_includes: common/README.md names no 'protocol: ROOM' in its rooms block")
    return levels, levels[protocol_top]


def resolve(including_file, name):
    """The file an include names, as a path relative to ROOT, or None (a system or generated header)."""
    folder = os.path.dirname(including_file)
    for base in (folder, "common", ".", "master", "worker"):
        path = os.path.normpath(os.path.join(base, name))
        if os.path.isfile(os.path.join(ROOT, path)):
            return path
    return None


def room_of(path):
    """('common', 'scene'), ('protocol', None), ('master', 'trust'), ('master', '.') ..."""
    parts = path.split(os.sep)
    if parts[0] in ("common", "master"):
        return parts[0], parts[1] if len(parts) > 2 else "."
    return parts[0], None


def main():
    levels, protocol_level = read_rule()
    master_levels, _ = read_block("master")
    broken, seen = [], 0
    for top in ("common", "protocol", "master", "worker"):
        for folder, _, files in os.walk(os.path.join(ROOT, top)):
            for f in sorted(files):
                if not f.endswith((".h", ".cpp")):
                    continue
                path = os.path.relpath(os.path.join(folder, f), ROOT)
                src = room_of(path)
                if src[0] == "common" and src[1] not in levels:
                    broken.append(f"{path}: common/{src[1]}/ is no room of the rule (common/README.md)")
                    continue
                if src[0] == "master" and src[1] != "." and src[1] not in master_levels:
                    broken.append(f"{path}: master/{src[1]}/ is no room of the rule (master/README.md)")
                    continue
                for number, line in enumerate(open(os.path.join(ROOT, path), encoding="utf-8"), 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    target = resolve(path, m.group(1))
                    if target is None:
                        continue
                    seen += 1
                    dst = room_of(target)
                    why = None
                    if src[0] == "common":
                        if dst[0] != "common":
                            why = "common/ includes nothing outside itself"
                        elif dst[1] != src[1] and levels[dst[1]] >= levels[src[1]]:
                            why = f"common/{src[1]}/ may not include common/{dst[1]}/ (not a lower room)"
                    elif src[0] == "protocol":
                        if dst[0] in ("master", "worker"):
                            why = "protocol/ includes no program"
                        elif dst[0] == "common" and levels[dst[1]] > protocol_level:
                            why = f"protocol/ includes common/ up to the core room, not common/{dst[1]}/"
                    elif {src[0], dst[0]} == {"master", "worker"}:
                        why = "master/ and worker/ never include each other"
                    elif src[0] == dst[0] == "master" and src[1] != "." and dst[1] != src[1]:
                        if dst[1] == "." or master_levels[dst[1]] >= master_levels[src[1]]:
                            why = f"master/{src[1]}/ may not include master/{dst[1]}/ (not a lower room)"
                    if why:
                        broken.append(f"{path}:{number}: includes {m.group(1)}: {why}")
    for b in broken:
        print(b)
    print(f"check_includes: {seen} includes checked, {len(broken)} break the rule (common/README.md and master/README.md, \"Rooms\")")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
