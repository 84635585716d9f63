#!/usr/bin/env python3
"""The floors of mjarm's rooms, enforced: every #include against the table in docs/architecture.md.

The table under "## Rooms" in docs/architecture.md (columns: floor | room | holds | reads from)
is the one statement of the layering; this script reads it and every `#include` of the library
(include/mjarm/**, src/**), the CLI (app/), the bindings (python/src/) and the examples, and
fails, naming file, line and arrow, when

- a file includes a room that its room's "reads from" cell does not list,
- the table lets a room read a room on its own floor or above (a room reads only lower floors),
- a file lies in a room the table does not have, or the table has a room with no folder,
- a file includes another room's private header (`src/<room>/...`, or a `detail/` folder of the
  other room's public headers), or a public header includes a private one (it would not compile
  once installed), or code outside the library includes the library's own headers under src/,
- a top-level header (`mjarm/*.hpp`, `src/*.hpp`: floor 0, readable by every room) includes a
  room,
- the drawing of the floors in the same section ("floor N   room/ room/") disagrees with the table.

Arrows the table lists but the code does not use are printed as information only. Standard
library only: run by CTest with any python3 (`architecture_floors`), or by hand:
    python3 scripts/check_floors.py [--root DIR] [--graph]
"""

import argparse
import os
import re
import sys

ROOMS_HEADING = "## Rooms"
TABLE_HEADER = ["floor", "room", "holds", "reads from"]
# a "reads from" cell that means every room on a lower floor (the CLI, the bindings, the examples)
EVERY_ROOM_BELOW = "every room below"
# a "reads from" cell that means no room
NO_ROOM = {"", "—", "-", "none"}
SOURCE_SUFFIXES = (".hpp", ".h", ".cpp", ".cc", ".inl")
INCLUDE_LINE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


class Tree:
    """Where each part of the source tree lies and what its compiler's include path holds."""

    def __init__(self, root):
        self.root = os.path.abspath(root)
        self.public = os.path.join(self.root, "include")
        self.public_rooms = os.path.join(self.public, "mjarm")
        self.private = os.path.join(self.root, "src")
        # the consumers on the top floor: folder -> its room name in the table
        self.consumers = {os.path.join(self.root, "app"): "app",
                          os.path.join(self.root, "python", "src"): "python",
                          os.path.join(self.root, "examples"): "examples"}

    def rel(self, path):
        return os.path.relpath(path, self.root)

    def search_path(self, path):
        """The include directories the build gives the file at `path` (CMakeLists.txt)."""
        for folder in self.consumers:
            if is_under(path, folder):
                # the bindings add their own folder; the CLI and the examples only include/
                own = [folder] if self.consumers[folder] == "python" else []
                return own + [self.public]
        return [self.public, self.private]

    def place(self, path):
        """(room or None for the top level, kind) of a file. Kinds: public (include/mjarm), detail
        (a detail/ folder there: installed, but the room's own), private (src/), consumer."""
        for folder, room in self.consumers.items():
            if is_under(path, folder):
                return room, "consumer"
        for base, kind in ((self.public_rooms, "public"), (self.private, "private")):
            if is_under(path, base):
                parts = os.path.relpath(path, base).split(os.sep)
                if len(parts) == 1:
                    return None, kind
                if kind == "public" and "detail" in parts[1:-1]:
                    return parts[0], "detail"
                return parts[0], kind
        return None, "outside"


def is_under(path, folder):
    return os.path.commonpath([os.path.abspath(path), folder]) == folder


def split_row(line):
    cells = line.strip().strip("|").split("|")
    return [cell.strip() for cell in cells]


def strip_notes(text):
    """The cell without its parenthetical notes (nested parentheses too)."""
    previous = None
    while previous != text:
        previous = text
        text = re.sub(r"\([^()]*\)", "", text)
    return text


def room_name(text):
    return text.strip().strip("`").strip().rstrip("/")


def read_docs(docs_path, errors):
    """The lines of the "## Rooms" section of docs/architecture.md, with their line numbers."""
    try:
        with open(docs_path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        errors.append(f"{docs_path}: cannot read the rooms table: {e.strerror}")
        return []
    section = []
    in_section = False
    for number, line in enumerate(lines, start=1):
        if line.startswith("## "):
            in_section = line.strip() == ROOMS_HEADING
        elif in_section:
            section.append((number, line))
    if not section:
        errors.append(f"{docs_path}: no section '{ROOMS_HEADING}'")
    return section


def read_table(section, docs_name, errors):
    """{room: (floor, [rooms it may read] or EVERY_ROOM_BELOW, line)} from the rooms table."""
    table = {}
    header_at = None
    for number, line in section:
        if header_at is None:
            if line.startswith("|") and [c.lower() for c in split_row(line)] == TABLE_HEADER:
                header_at = number
            continue
        if number == header_at + 1:
            continue  # the |---| line
        if not line.startswith("|"):
            break
        cells = split_row(line)
        where = f"{docs_name}:{number}"
        if len(cells) != len(TABLE_HEADER):
            errors.append(f"{where}: a row of the rooms table has {len(cells)} cells, expected "
                          f"{len(TABLE_HEADER)} ({' | '.join(TABLE_HEADER)})")
            continue
        floor_text, room_text, _, reads_text = cells
        room = room_name(room_text)
        if not re.fullmatch(r"[a-z_][a-z0-9_]*", room):
            errors.append(f"{where}: room '{room_text}' is not a folder name like `model/`")
            continue
        if not floor_text.isdigit():
            errors.append(f"{where}: room {room}: floor '{floor_text}' is not a whole number")
            continue
        if room in table:
            errors.append(f"{where}: room {room} is listed twice (first on line {table[room][2]})")
            continue
        reads_text = strip_notes(reads_text).strip()
        if reads_text.lower() == EVERY_ROOM_BELOW:
            reads = EVERY_ROOM_BELOW
        else:
            reads = [room_name(item) for item in reads_text.split(",")]
            reads = [r for r in reads if r.lower() not in NO_ROOM]
        table[room] = (int(floor_text), reads, number)
    if header_at is None and section:
        errors.append(f"{docs_name}: no rooms table under '{ROOMS_HEADING}' with the columns "
                      f"{' | '.join(TABLE_HEADER)}")
    return table


def check_drawing(section, table, docs_name, errors):
    """The drawing (the section's lines "floor N   room/ room/ …") puts each room where the
    table does."""
    drawn = {}
    for number, line in section:
        match = re.match(r"^floor\s+(\d+)\s(.*)$", line)
        if not match:
            continue
        for word in match.group(2).split():
            if re.fullmatch(r"[a-z_][a-z0-9_]*/", word):
                drawn.setdefault(word[:-1], []).append((int(match.group(1)), number))
    if not drawn:
        errors.append(f"{docs_name}: no drawing of the floors under '{ROOMS_HEADING}' (lines "
                      f"'floor N   room/ room/')")
        return
    for room, places in sorted(drawn.items()):
        if room not in table:
            errors.append(f"{docs_name}:{places[0][1]}: the drawing has room {room}, "
                          f"the table does not")
        elif len(places) > 1:
            errors.append(f"{docs_name}:{places[1][1]}: the drawing has room {room} twice")
        elif places[0][0] != table[room][0]:
            errors.append(f"{docs_name}:{places[0][1]}: the drawing puts {room} on floor "
                          f"{places[0][0]}, the table (line {table[room][2]}) on floor "
                          f"{table[room][0]}")
    for room in sorted(set(table) - set(drawn)):
        errors.append(f"{docs_name}:{table[room][2]}: room {room} is not in the drawing of "
                      f"the floors")


def check_table(table, docs_name, errors):
    """Each listed arrow names a room of the table on a lower floor.
    Returns {room: the set of rooms it may read}."""
    allowed = {}
    for room, (floor, reads, number) in table.items():
        if reads == EVERY_ROOM_BELOW:
            allowed[room] = {other for other, (f, _, _) in table.items() if f < floor}
            continue
        allowed[room] = set()
        for other in reads:
            if other not in table:
                errors.append(f"{docs_name}:{number}: room {room} reads from '{other}', which "
                              f"is not a room of the table")
            elif table[other][0] >= floor:
                errors.append(f"{docs_name}:{number}: arrow {room} -> {other} goes from floor "
                              f"{floor} to floor {table[other][0]}: a room reads only rooms on "
                              f"lower floors")
            else:
                allowed[room].add(other)
    return allowed


def source_files(tree):
    folders = [tree.public, tree.private] + list(tree.consumers)
    for folder in folders:
        for directory, subdirs, files in os.walk(folder):
            subdirs.sort()
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.join(directory, name)


def includes(path):
    """(line number, delimiter, included name) of each #include in the file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, start=1):
            match = INCLUDE_LINE.match(line)
            if match:
                yield number, match.group(1), match.group(2)


def resolve(tree, path, delimiter, name):
    """The file an #include names, as the compiler finds it; None for a system or third-party
    header."""
    candidates = [os.path.dirname(path)] if delimiter == '"' else []
    for folder in candidates + tree.search_path(path):
        target = os.path.normpath(os.path.join(folder, name))
        if os.path.isfile(target):
            return target
    return None


def describe(room):
    return room if room is not None else "(top level)"


def check_include(tree, table, allowed, path, target):
    """The reason an include breaks the floors, or None."""
    room, kind = tree.place(path)
    target_room, target_kind = tree.place(target)
    arrow = f"arrow {describe(room)} -> {describe(target_room)}"
    header = tree.rel(target)
    if target_kind in ("outside", "consumer") and target_room != room:
        return f"{arrow}: {header} belongs to no room of the library"
    if kind in ("public", "detail") and target_kind == "private":
        return f"{arrow}: a public header includes {header}, which is not installed"
    if kind == "consumer" and target_kind in ("private", "detail"):
        return f"{arrow}: {header} is private to the library; {room} reads only the public headers"
    if target_room is None or target_room == room:
        return None  # the top level (floor 0, every room's), or the room's own header
    if room is None:
        return f"{arrow}: the top level is floor 0 and reads no room"
    if target_kind in ("private", "detail"):
        return f"{arrow}: {header} is a private header of {target_room}"
    if target_room not in allowed.get(room, set()):
        floor = table[room][0]
        target_floor = table[target_room][0] if target_room in table else None
        if target_floor is None:
            why = f"{target_room} is not a room of the table"
        elif target_floor >= floor:
            why = f"{target_room} is on floor {target_floor}, not below {room}'s floor {floor}"
        else:
            listed = sorted(allowed.get(room, set()))
            why = f"{room} reads only {', '.join(listed) if listed else 'no room'}"
        return f"{arrow} is not in the table: {why}"
    return None


def run(root, show_graph):
    tree = Tree(root)
    docs_path = os.path.join(tree.root, "docs", "architecture.md")
    docs_name = tree.rel(docs_path)
    errors = []
    section = read_docs(docs_path, errors)
    table = read_table(section, docs_name, errors)
    if section:
        check_drawing(section, table, docs_name, errors)
    allowed = check_table(table, docs_name, errors)

    # every folder that holds a room is in the table, every room of the table has a folder
    found_rooms = set()
    for base in (tree.public_rooms, tree.private):
        if os.path.isdir(base):
            found_rooms.update(e for e in os.listdir(base) if os.path.isdir(os.path.join(base, e)))
    for room in sorted(found_rooms - set(table)):
        errors.append(f"room {room} (include/mjarm/{room} or src/{room}) is not in "
                      f"{docs_name}'s rooms table")
    consumers = set(tree.consumers.values())
    for room in sorted(set(table) - found_rooms - consumers):
        errors.append(f"{docs_name}:{table[room][2]}: room {room} has no folder "
                      f"include/mjarm/{room} or src/{room}")
    for folder, room in tree.consumers.items():
        if room not in table and os.path.isdir(folder):
            errors.append(f"{tree.rel(folder)}/ is room {room}, which is not in {docs_name}'s "
                          f"rooms table")

    used = {}
    for path in source_files(tree):
        room, _ = tree.place(path)
        # a room missing from the table is reported once above; its arrows still make the graph
        report = room is None or room in table
        for number, delimiter, name in includes(path):
            target = resolve(tree, path, delimiter, name)
            if target is None:
                if name.startswith("mjarm/"):
                    errors.append(f"{tree.rel(path)}:{number}: includes {name}, which does not "
                                  f"exist")
                continue
            target_room, _ = tree.place(target)
            if room is not None and target_room is not None and target_room != room:
                used.setdefault(room, set()).add(target_room)
            reason = check_include(tree, table, allowed, path, target) if report else None
            if reason:
                errors.append(f"{tree.rel(path)}:{number}: #include {delimiter}{name}"
                              f"{'>' if delimiter == '<' else delimiter}: {reason}")

    if show_graph:
        print("the include graph (room -> rooms it includes):")
        for room in sorted(used, key=lambda r: (table.get(r, (99,))[0], r)):
            floor = table[room][0] if room in table else "?"
            print(f"  {room} (floor {floor}) -> {' '.join(sorted(used[room]))}")
    unused = []
    for room, (floor, reads, _) in sorted(table.items()):
        if reads == EVERY_ROOM_BELOW:
            continue
        unused += [f"{room} -> {other}" for other in sorted(set(reads) - used.get(room, set()))
                   if other in table]
    if unused:
        print(f"info: arrows {docs_name} allows that no include uses: {', '.join(unused)}")
    for error in errors:
        print(f"error: {error}")
    if errors:
        print(f"architecture floors: {len(errors)} error(s); the table is {docs_name}, "
              f"'{ROOMS_HEADING}'")
        return 1
    arrows = sum(len(v) for v in used.values())
    print(f"architecture floors: ok ({len(table)} rooms, {arrows} arrows between rooms, all down "
          f"the floors)")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--root", default=os.path.join(here, ".."),
                        help="the source tree (default: this script's repository)")
    parser.add_argument("--graph", action="store_true",
                        help="print the include graph between rooms")
    args = parser.parse_args()
    if not os.path.isdir(args.root):
        print(f"error: --root '{args.root}' is not a folder", file=sys.stderr)
        return 2
    return run(args.root, args.graph)


if __name__ == "__main__":
    sys.exit(main())
